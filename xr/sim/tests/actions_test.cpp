// Action sets, actions, suggested bindings, interaction profiles, xrSyncActions and states, bound
// sources, haptics, and input driven through XR_EXT_conformance_automation, through the loader.
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>

using namespace sim_test;

namespace {

class ActionsTest : public ::testing::Test {
 protected:
  void SetUp() override { use_simulated_runtime(); }

  XrActionSet make_set(Sim& sim, const char* name, const char* localized, XrResult expected = XR_SUCCESS) {
    XrActionSetCreateInfo ci{XR_TYPE_ACTION_SET_CREATE_INFO};
    std::strcpy(ci.actionSetName, name);
    std::strcpy(ci.localizedActionSetName, localized);
    XrActionSet set = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateActionSet(sim.instance, &ci, &set), expected) << name;
    return set;
  }
  XrAction make_action(XrActionSet set, const char* name, XrActionType type, std::vector<XrPath> subactions,
                       XrResult expected = XR_SUCCESS) {
    XrActionCreateInfo ci{XR_TYPE_ACTION_CREATE_INFO};
    std::strcpy(ci.actionName, name);
    std::strcpy(ci.localizedActionName, name);
    ci.actionType = type;
    ci.countSubactionPaths = static_cast<uint32_t>(subactions.size());
    ci.subactionPaths = subactions.data();
    XrAction action = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateAction(set, &ci, &action), expected) << name;
    return action;
  }
  XrResult suggest(Sim& sim, const char* profile, std::vector<std::pair<XrAction, const char*>> bindings) {
    std::vector<XrActionSuggestedBinding> b;
    for (auto& [a, p] : bindings) b.push_back({a, sim.path(p)});
    XrInteractionProfileSuggestedBinding s{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
    s.interactionProfile = sim.path(profile);
    s.countSuggestedBindings = static_cast<uint32_t>(b.size());
    s.suggestedBindings = b.data();
    return xrSuggestInteractionProfileBindings(sim.instance, &s);
  }
  XrResult attach(Sim& sim, XrActionSet set) {
    XrSessionActionSetsAttachInfo ai{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
    ai.countActionSets = 1;
    ai.actionSets = &set;
    return xrAttachSessionActionSets(sim.session, &ai);
  }
  XrResult sync(Sim& sim, XrActionSet set) {
    XrActiveActionSet active{set, XR_NULL_PATH};
    XrActionsSyncInfo si{XR_TYPE_ACTIONS_SYNC_INFO};
    si.countActiveActionSets = 1;
    si.activeActionSets = &active;
    return xrSyncActions(sim.session, &si);
  }
};

TEST_F(ActionsTest, NameRulesAndDuplicates) {
  Sim sim;
  XrActionSet set = make_set(sim, "gameplay", "Gameplay");
  make_set(sim, "Bad Name", "Bad", XR_ERROR_NAME_INVALID);
  make_set(sim, "gameplay", "Other", XR_ERROR_NAME_DUPLICATED);
  make_set(sim, "other", "Gameplay", XR_ERROR_LOCALIZED_NAME_DUPLICATED);
  make_action(set, "grab", XR_ACTION_TYPE_FLOAT_INPUT, {});
  make_action(set, "grab", XR_ACTION_TYPE_FLOAT_INPUT, {}, XR_ERROR_NAME_DUPLICATED);
  make_action(set, "bad", XR_ACTION_TYPE_BOOLEAN_INPUT, {sim.path("/user/hand")}, XR_ERROR_PATH_UNSUPPORTED);
  const XrPath left = sim.path("/user/hand/left");
  make_action(set, "twice", XR_ACTION_TYPE_BOOLEAN_INPUT, {left, left}, XR_ERROR_PATH_UNSUPPORTED);
}

TEST_F(ActionsTest, BindingsForAnUnknownProfileOrInputAreUnsupported) {
  Sim sim;
  XrActionSet set = make_set(sim, "s", "S");
  XrAction click = make_action(set, "click", XR_ACTION_TYPE_BOOLEAN_INPUT, {});
  XrAction pose = make_action(set, "pose", XR_ACTION_TYPE_POSE_INPUT, {});
  EXPECT_EQ(
      suggest(sim, "/interaction_profiles/acme/teleporter", {{click, "/user/hand/left/input/select/click"}}),
      XR_ERROR_PATH_UNSUPPORTED);
  EXPECT_EQ(
      suggest(sim, "/interaction_profiles/khr/simple_controller", {{click, "/user/hand/left/input/x/click"}}),
      XR_ERROR_PATH_UNSUPPORTED);
  EXPECT_EQ(suggest(sim, "/interaction_profiles/khr/simple_controller",
                    {{pose, "/user/hand/left/input/menu/click"}}),
            XR_ERROR_PATH_UNSUPPORTED);
  for (const char* profile :
       {"/interaction_profiles/khr/simple_controller", "/interaction_profiles/oculus/touch_controller",
        "/interaction_profiles/valve/index_controller", "/interaction_profiles/htc/vive_controller",
        "/interaction_profiles/microsoft/motion_controller"})
    EXPECT_EQ(suggest(sim, profile, {{pose, "/user/hand/right/input/aim/pose"}}), XR_SUCCESS) << profile;
  // Identifiers without a component are completed (".../select" -> ".../select/click").
  EXPECT_EQ(
      suggest(sim, "/interaction_profiles/khr/simple_controller", {{click, "/user/hand/left/input/select"}}),
      XR_SUCCESS);
}

// The profiles three extensions bring (HP Reverb G2, Vive Cosmos, Samsung Odyssey controllers) exist for an
// instance only with their extension enabled; with it they bind and are chosen like the core ones.
TEST_F(ActionsTest, ExtensionProfilesNeedTheirExtension) {
  const std::vector<std::pair<const char*, const char*>> profiles = {
      {"/interaction_profiles/hp/mixed_reality_controller",
       XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME},
      {"/interaction_profiles/htc/vive_cosmos_controller",
       XR_HTC_VIVE_COSMOS_CONTROLLER_INTERACTION_EXTENSION_NAME},
      {"/interaction_profiles/samsung/odyssey_controller", XR_EXT_SAMSUNG_ODYSSEY_CONTROLLER_EXTENSION_NAME}};
  {
    Sim sim;
    XrActionSet set = make_set(sim, "s", "S");
    XrAction trigger = make_action(set, "trigger", XR_ACTION_TYPE_FLOAT_INPUT, {});
    for (const auto& [profile, extension] : profiles)
      EXPECT_EQ(suggest(sim, profile, {{trigger, "/user/hand/right/input/trigger/value"}}),
                XR_ERROR_PATH_UNSUPPORTED)
          << profile << " without " << extension;
  }
  for (const auto& [profile, extension] : profiles) {
    Sim sim({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME,
             XR_EXT_CONFORMANCE_AUTOMATION_EXTENSION_NAME, extension});
    sim.create_session();
    XrActionSet set = make_set(sim, "s", "S");
    const XrPath right = sim.path("/user/hand/right");
    XrAction trigger = make_action(set, "trigger", XR_ACTION_TYPE_FLOAT_INPUT, {right});
    XrAction menu = make_action(set, "menu", XR_ACTION_TYPE_BOOLEAN_INPUT, {right});
    // Each has a trigger value and a thumbstick click on both hands; the HP's X button is the left hand's.
    ASSERT_EQ(suggest(sim, profile,
                      {{trigger, "/user/hand/right/input/trigger/value"},
                       {menu, "/user/hand/right/input/thumbstick/click"}}),
              XR_SUCCESS)
        << profile;
    if (std::strcmp(extension, XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME) == 0) {
      EXPECT_EQ(suggest(sim, profile, {{menu, "/user/hand/left/input/x/click"}}), XR_SUCCESS);
      EXPECT_EQ(suggest(sim, profile, {{menu, "/user/hand/right/input/x/click"}}), XR_ERROR_PATH_UNSUPPORTED);
      ASSERT_EQ(suggest(sim, profile,
                        {{trigger, "/user/hand/right/input/trigger/value"},
                         {menu, "/user/hand/right/input/thumbstick/click"}}),
                XR_SUCCESS);
    }
    ASSERT_EQ(attach(sim, set), XR_SUCCESS);
    XrInteractionProfileState ps{XR_TYPE_INTERACTION_PROFILE_STATE};
    ASSERT_EQ(xrGetCurrentInteractionProfile(sim.session, right, &ps), XR_SUCCESS);
    EXPECT_EQ(ps.interactionProfile, sim.path(profile));
  }
}

TEST_F(ActionsTest, AttachChoosesAProfileAndLocksTheSets) {
  Sim sim;
  sim.create_session();
  XrActionSet set = make_set(sim, "s", "S");
  const XrPath left = sim.path("/user/hand/left"), right = sim.path("/user/hand/right");
  XrAction menu = make_action(set, "menu", XR_ACTION_TYPE_BOOLEAN_INPUT, {left, right});
  ASSERT_EQ(
      suggest(sim, "/interaction_profiles/htc/vive_controller", {{menu, "/user/hand/left/input/menu/click"}}),
      XR_SUCCESS);
  XrInteractionProfileState ps{XR_TYPE_INTERACTION_PROFILE_STATE};
  EXPECT_EQ(xrGetCurrentInteractionProfile(sim.session, left, &ps), XR_ERROR_ACTIONSET_NOT_ATTACHED);
  ASSERT_EQ(attach(sim, set), XR_SUCCESS);
  EXPECT_EQ(attach(sim, set), XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
  make_action(set, "late", XR_ACTION_TYPE_BOOLEAN_INPUT, {}, XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
  EXPECT_EQ(suggest(sim, "/interaction_profiles/khr/simple_controller",
                    {{menu, "/user/hand/left/input/menu/click"}}),
            XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
  ASSERT_EQ(xrGetCurrentInteractionProfile(sim.session, left, &ps), XR_SUCCESS);
  EXPECT_EQ(ps.interactionProfile, sim.path("/interaction_profiles/htc/vive_controller"));
  ASSERT_EQ(xrGetCurrentInteractionProfile(sim.session, sim.path("/user/head"), &ps), XR_SUCCESS);
  EXPECT_EQ(ps.interactionProfile, XR_NULL_PATH);
  sim.poll_states();
  bool profile_event = false;
  for (const auto& e : sim.other_events)
    profile_event |= e.type == XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
  EXPECT_TRUE(profile_event);
  // Bound sources and their names.
  XrBoundSourcesForActionEnumerateInfo ei{XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO};
  ei.action = menu;
  uint32_t n = 0;
  ASSERT_EQ(xrEnumerateBoundSourcesForAction(sim.session, &ei, 0, &n, nullptr), XR_SUCCESS);
  ASSERT_EQ(n, 1u);
  XrPath source = XR_NULL_PATH;
  ASSERT_EQ(xrEnumerateBoundSourcesForAction(sim.session, &ei, 1, &n, &source), XR_SUCCESS);
  EXPECT_EQ(source, sim.path("/user/hand/left/input/menu/click"));
  XrInputSourceLocalizedNameGetInfo ni{XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO};
  ni.sourcePath = source;
  ni.whichComponents = XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT |
                       XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT |
                       XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT;
  char name[256];
  ASSERT_EQ(xrGetInputSourceLocalizedName(sim.session, &ni, sizeof name, &n, name), XR_SUCCESS);
  EXPECT_STREQ(name, "Left Hand HTC Vive Controller Menu Click");
}

TEST_F(ActionsTest, StatesFollowAutomationInputAndSubactionPaths) {
  const std::string haptics = temp_dir("haptics") + "/haptics.jsonl";
  setenv("PUSHPULL_XR_SIM_HAPTICS", haptics.c_str(), 1);
  Sim sim;
  sim.create_session();
  auto set_bool = sim.fn<PFN_xrSetInputDeviceStateBoolEXT>("xrSetInputDeviceStateBoolEXT");
  auto set_float = sim.fn<PFN_xrSetInputDeviceStateFloatEXT>("xrSetInputDeviceStateFloatEXT");
  auto set_vec = sim.fn<PFN_xrSetInputDeviceStateVector2fEXT>("xrSetInputDeviceStateVector2fEXT");
  XrActionSet set = make_set(sim, "s", "S");
  const XrPath left = sim.path("/user/hand/left"), right = sim.path("/user/hand/right");
  XrAction trigger = make_action(set, "trigger", XR_ACTION_TYPE_FLOAT_INPUT, {left, right});
  XrAction a_button = make_action(set, "a", XR_ACTION_TYPE_BOOLEAN_INPUT, {});
  XrAction stick = make_action(set, "stick", XR_ACTION_TYPE_VECTOR2F_INPUT, {});
  XrAction buzz = make_action(set, "buzz", XR_ACTION_TYPE_VIBRATION_OUTPUT, {left, right});
  XrAction grip = make_action(set, "grip", XR_ACTION_TYPE_POSE_INPUT, {left, right});
  ASSERT_EQ(suggest(sim, "/interaction_profiles/oculus/touch_controller",
                    {{trigger, "/user/hand/left/input/trigger/value"},
                     {trigger, "/user/hand/right/input/trigger/value"},
                     {a_button, "/user/hand/right/input/a/click"},
                     {stick, "/user/hand/right/input/thumbstick"},
                     {buzz, "/user/hand/left/output/haptic"},
                     {grip, "/user/hand/right/input/grip/pose"}}),
            XR_SUCCESS);
  ASSERT_EQ(attach(sim, set), XR_SUCCESS);
  XrActionSpaceCreateInfo asi{XR_TYPE_ACTION_SPACE_CREATE_INFO};
  asi.action = grip;
  asi.subactionPath = right;
  asi.poseInActionSpace.orientation.w = 1.f;
  XrSpace grip_space = XR_NULL_HANDLE;
  ASSERT_EQ(xrCreateActionSpace(sim.session, &asi, &grip_space), XR_SUCCESS);
  XrSpace stage = sim.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);

  EXPECT_EQ(sync(sim, set), XR_SESSION_NOT_FOCUSED);  // not focused yet: everything inactive
  sim.begin_session();
  const XrTime t = sim.frame();
  ASSERT_EQ(sim.poll_states().back(), XR_SESSION_STATE_FOCUSED);

  ASSERT_EQ(set_float(sim.session, left, sim.path("/user/hand/left/input/trigger/value"), 0.25f), XR_SUCCESS);
  ASSERT_EQ(set_float(sim.session, right, sim.path("/user/hand/right/input/trigger/value"), 0.75f),
            XR_SUCCESS);
  ASSERT_EQ(set_bool(sim.session, right, sim.path("/user/hand/right/input/a/click"), XR_TRUE), XR_SUCCESS);
  ASSERT_EQ(set_vec(sim.session, right, sim.path("/user/hand/right/input/thumbstick"), {0.5f, -1.f}),
            XR_SUCCESS);
  ASSERT_EQ(sync(sim, set), XR_SUCCESS);

  XrActionStateGetInfo gi{XR_TYPE_ACTION_STATE_GET_INFO};
  XrActionStateFloat f{XR_TYPE_ACTION_STATE_FLOAT};
  gi.action = trigger;
  gi.subactionPath = left;
  ASSERT_EQ(xrGetActionStateFloat(sim.session, &gi, &f), XR_SUCCESS);
  EXPECT_TRUE(f.isActive);
  EXPECT_FLOAT_EQ(f.currentState, 0.25f);
  gi.subactionPath = XR_NULL_PATH;
  ASSERT_EQ(xrGetActionStateFloat(sim.session, &gi, &f), XR_SUCCESS);
  EXPECT_FLOAT_EQ(f.currentState, 0.75f);  // the largest of both hands
  gi.subactionPath = sim.path("/user/head");
  EXPECT_EQ(xrGetActionStateFloat(sim.session, &gi, &f), XR_ERROR_PATH_UNSUPPORTED);
  XrActionStateBoolean b{XR_TYPE_ACTION_STATE_BOOLEAN};
  gi.action = a_button;
  gi.subactionPath = XR_NULL_PATH;
  ASSERT_EQ(xrGetActionStateBoolean(sim.session, &gi, &b), XR_SUCCESS);
  EXPECT_TRUE(b.currentState);
  EXPECT_TRUE(b.changedSinceLastSync);
  EXPECT_EQ(xrGetActionStateFloat(sim.session, &gi, &f), XR_ERROR_ACTION_TYPE_MISMATCH);
  XrActionStateVector2f v{XR_TYPE_ACTION_STATE_VECTOR2F};
  gi.action = stick;
  ASSERT_EQ(xrGetActionStateVector2f(sim.session, &gi, &v), XR_SUCCESS);
  EXPECT_FLOAT_EQ(v.currentState.x, 0.5f);
  EXPECT_FLOAT_EQ(v.currentState.y, -1.f);
  // A second sync without change: no longer "changed".
  ASSERT_EQ(sync(sim, set), XR_SUCCESS);
  gi.action = a_button;
  ASSERT_EQ(xrGetActionStateBoolean(sim.session, &gi, &b), XR_SUCCESS);
  EXPECT_FALSE(b.changedSinceLastSync);

  // The grip pose is located and follows automation.
  auto set_location = sim.fn<PFN_xrSetInputDeviceLocationEXT>("xrSetInputDeviceLocationEXT");
  XrPosef p{{0, 0, 0, 1}, {0.3f, 1.1f, -0.2f}};
  ASSERT_EQ(set_location(sim.session, right, sim.path("/user/hand/right/input/grip/pose"), stage, p),
            XR_SUCCESS);
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION};
  ASSERT_EQ(xrLocateSpace(grip_space, stage, t, &loc), XR_SUCCESS);
  EXPECT_NE(loc.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT, 0u);
  EXPECT_FLOAT_EQ(loc.pose.position.x, 0.3f);

  // Haptics go to bound outputs.
  XrHapticActionInfo hi{XR_TYPE_HAPTIC_ACTION_INFO};
  hi.action = buzz;
  XrHapticVibration vib{XR_TYPE_HAPTIC_VIBRATION};
  vib.amplitude = 0.5f;
  vib.duration = XR_MIN_HAPTIC_DURATION;
  vib.frequency = XR_FREQUENCY_UNSPECIFIED;
  EXPECT_EQ(xrApplyHapticFeedback(sim.session, &hi, reinterpret_cast<XrHapticBaseHeader*>(&vib)), XR_SUCCESS);
  EXPECT_EQ(xrStopHapticFeedback(sim.session, &hi), XR_SUCCESS);
  {
    std::ifstream in(haptics);
    std::string first, second;
    std::getline(in, first);
    std::getline(in, second);
    EXPECT_NE(first.find("\"path\":\"/user/hand/left/output/haptic\""), std::string::npos) << first;
    EXPECT_NE(first.find("\"amplitude\":0.5"), std::string::npos) << first;
    EXPECT_NE(second.find("\"stop\":true"), std::string::npos) << second;
  }
  hi.action = trigger;
  EXPECT_EQ(xrApplyHapticFeedback(sim.session, &hi, reinterpret_cast<XrHapticBaseHeader*>(&vib)),
            XR_ERROR_ACTION_TYPE_MISMATCH);

  // A device made inactive deactivates its actions.
  auto set_active = sim.fn<PFN_xrSetInputDeviceActiveEXT>("xrSetInputDeviceActiveEXT");
  ASSERT_EQ(
      set_active(sim.session, sim.path("/interaction_profiles/oculus/touch_controller"), right, XR_FALSE),
      XR_SUCCESS);
  ASSERT_EQ(sync(sim, set), XR_SUCCESS);
  gi.action = a_button;
  ASSERT_EQ(xrGetActionStateBoolean(sim.session, &gi, &b), XR_SUCCESS);
  EXPECT_FALSE(b.isActive);
  ASSERT_EQ(xrLocateSpace(grip_space, stage, t, &loc), XR_SUCCESS);
  EXPECT_EQ(loc.locationFlags, 0u);
}

TEST_F(ActionsTest, UnattachedSetsCannotBeSynced) {
  Sim sim;
  sim.create_session();
  XrActionSet set = make_set(sim, "s", "S");
  XrActionSet other = make_set(sim, "o", "O");
  XrAction a = make_action(set, "a", XR_ACTION_TYPE_BOOLEAN_INPUT, {});
  make_action(other, "b", XR_ACTION_TYPE_BOOLEAN_INPUT, {});
  EXPECT_EQ(sync(sim, set), XR_ERROR_ACTIONSET_NOT_ATTACHED);
  ASSERT_EQ(attach(sim, set), XR_SUCCESS);
  EXPECT_EQ(sync(sim, other), XR_ERROR_ACTIONSET_NOT_ATTACHED);
  XrActionStateGetInfo gi{XR_TYPE_ACTION_STATE_GET_INFO};
  gi.action = a;
  XrActionStateBoolean b{XR_TYPE_ACTION_STATE_BOOLEAN};
  ASSERT_EQ(xrGetActionStateBoolean(sim.session, &gi, &b), XR_SUCCESS);
  EXPECT_FALSE(b.isActive);  // no bindings suggested
}

}  // namespace
