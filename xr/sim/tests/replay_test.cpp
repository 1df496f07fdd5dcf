// Determinism: the same input script replayed twice gives identical poses and action states frame by
// frame (the virtual clock makes a run independent of how fast the machine is).
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <cstring>

using namespace sim_test;

namespace {

constexpr const char* kScript = R"(# a short scripted session
{"t": 0.0, "path": "/user/head", "pose": {"p": [0, 1.6, 0], "q": [0, 0, 0, 1]}}
{"t": 1.0, "path": "/user/head", "pose": {"p": [0.2, 1.55, -0.1], "q": [0, 0.3826834, 0, 0.9238795]}}
{"t": 0.0, "path": "/user/hand/right/input/aim/pose", "pose": {"p": [0.2, 1.3, -0.4], "q": [0, 0, 0, 1]}}
{"t": 0.5, "path": "/user/hand/right/input/aim/pose", "pose": {"p": [0.1, 1.2, -0.6], "q": [0.258819, 0, 0, 0.9659258]}}
{"t": 0.3, "path": "/user/hand/right/input/trigger/value", "value": 0.9}
{"t": 0.6, "path": "/user/hand/right/input/trigger/value", "value": 0.0}
{"t": 0.2, "path": "/user/hand/right/input/thumbstick", "value": [0.5, -0.25]}
{"t": 0.4, "path": "/user/hand/right/input/a/click", "value": true}
{"t": 0.7, "path": "/user/hand/right/input/a/click", "value": false}
)";

struct FrameRecord {
  XrTime time_from_start;
  XrPosef eyes[2];
  XrPosef aim;
  XrSpaceLocationFlags aim_flags;
  float trigger;
  XrVector2f stick;
  XrBool32 a, a_changed;
  bool operator==(const FrameRecord& o) const { return std::memcmp(this, &o, sizeof *this) == 0; }
};

std::vector<FrameRecord> run_script(int frames) {
  Sim sim;
  sim.create_session();
  XrActionSetCreateInfo sci{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(sci.actionSetName, "replay");
  std::strcpy(sci.localizedActionSetName, "Replay");
  XrActionSet set = XR_NULL_HANDLE;
  XRC(xrCreateActionSet(sim.instance, &sci, &set));
  const auto action = [&](const char* name, XrActionType type) {
    XrActionCreateInfo ci{XR_TYPE_ACTION_CREATE_INFO};
    std::strcpy(ci.actionName, name);
    std::strcpy(ci.localizedActionName, name);
    ci.actionType = type;
    XrAction a = XR_NULL_HANDLE;
    XRC(xrCreateAction(set, &ci, &a));
    return a;
  };
  XrAction aim = action("aim", XR_ACTION_TYPE_POSE_INPUT);
  XrAction trigger = action("trigger", XR_ACTION_TYPE_FLOAT_INPUT);
  XrAction stick = action("stick", XR_ACTION_TYPE_VECTOR2F_INPUT);
  XrAction a = action("a", XR_ACTION_TYPE_BOOLEAN_INPUT);
  const XrActionSuggestedBinding bindings[] = {{aim, sim.path("/user/hand/right/input/aim/pose")},
                                               {trigger, sim.path("/user/hand/right/input/trigger/value")},
                                               {stick, sim.path("/user/hand/right/input/thumbstick")},
                                               {a, sim.path("/user/hand/right/input/a/click")}};
  XrInteractionProfileSuggestedBinding sb{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
  sb.interactionProfile = sim.path("/interaction_profiles/oculus/touch_controller");
  sb.countSuggestedBindings = 4;
  sb.suggestedBindings = bindings;
  XRC(xrSuggestInteractionProfileBindings(sim.instance, &sb));
  XrSessionActionSetsAttachInfo ai{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
  ai.countActionSets = 1;
  ai.actionSets = &set;
  XRC(xrAttachSessionActionSets(sim.session, &ai));
  XrActionSpaceCreateInfo asi{XR_TYPE_ACTION_SPACE_CREATE_INFO};
  asi.action = aim;
  asi.poseInActionSpace.orientation.w = 1.f;
  XrSpace aim_space = XR_NULL_HANDLE;
  XRC(xrCreateActionSpace(sim.session, &asi, &aim_space));
  XrSpace stage = sim.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  sim.begin_session();

  std::vector<FrameRecord> records;
  XrTime start = 0;
  for (int i = 0; i < frames; ++i) {
    XrFrameState fs{XR_TYPE_FRAME_STATE};
    XRC(xrWaitFrame(sim.session, nullptr, &fs));
    XRC(xrBeginFrame(sim.session, nullptr));
    sim.poll_states();
    if (start == 0) start = fs.predictedDisplayTime;
    XrActiveActionSet active{set, XR_NULL_PATH};
    XrActionsSyncInfo si{XR_TYPE_ACTIONS_SYNC_INFO};
    si.countActiveActionSets = 1;
    si.activeActionSets = &active;
    const XrResult sync = xrSyncActions(sim.session, &si);
    if (sync != XR_SUCCESS && sync != XR_SESSION_NOT_FOCUSED) XRC(sync);
    FrameRecord r{};
    r.time_from_start = fs.predictedDisplayTime - start;
    XrViewLocateInfo li{XR_TYPE_VIEW_LOCATE_INFO};
    li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    li.displayTime = fs.predictedDisplayTime;
    li.space = stage;
    XrViewState vs{XR_TYPE_VIEW_STATE};
    XrView views[2] = {{XR_TYPE_VIEW}, {XR_TYPE_VIEW}};
    uint32_t n = 0;
    XRC(xrLocateViews(sim.session, &li, &vs, 2, &n, views));
    r.eyes[0] = views[0].pose;
    r.eyes[1] = views[1].pose;
    XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION};
    XRC(xrLocateSpace(aim_space, stage, fs.predictedDisplayTime, &loc));
    r.aim = loc.pose;
    r.aim_flags = loc.locationFlags;
    XrActionStateGetInfo gi{XR_TYPE_ACTION_STATE_GET_INFO};
    gi.action = trigger;
    XrActionStateFloat f{XR_TYPE_ACTION_STATE_FLOAT};
    XRC(xrGetActionStateFloat(sim.session, &gi, &f));
    r.trigger = f.currentState;
    gi.action = stick;
    XrActionStateVector2f v{XR_TYPE_ACTION_STATE_VECTOR2F};
    XRC(xrGetActionStateVector2f(sim.session, &gi, &v));
    r.stick = v.currentState;
    gi.action = a;
    XrActionStateBoolean b{XR_TYPE_ACTION_STATE_BOOLEAN};
    XRC(xrGetActionStateBoolean(sim.session, &gi, &b));
    r.a = b.currentState;
    r.a_changed = b.changedSinceLastSync;
    records.push_back(r);
    XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
    ei.displayTime = fs.predictedDisplayTime;
    ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    XRC(xrEndFrame(sim.session, &ei));
  }
  return records;
}

TEST(ReplayTest, SameScriptGivesIdenticalPosesAndActionStatesFrameByFrame) {
  use_simulated_runtime();
  setenv("PUSHPULL_XR_SIM_INPUT", write_temp_file("session.jsonl", kScript).c_str(), 1);
  setenv("PUSHPULL_XR_SIM_RATE", "30", 1);
  const auto first = run_script(40);
  const auto second = run_script(40);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_TRUE(first[i] == second[i]) << "frame " << i;
  // The script really moves things: frame n is at n / 30 s, the head turns, the trigger goes up and down.
  EXPECT_EQ(first[30].time_from_start, 1000000000);
  EXPECT_NE(first[0].eyes[0].orientation.y, first[30].eyes[0].orientation.y);
  EXPECT_NEAR(first[15].aim.position.z, -0.6f, 1e-6);  // t = 0.5 s
  EXPECT_FLOAT_EQ(first[12].trigger, 0.9f);            // t = 0.4 s
  EXPECT_FLOAT_EQ(first[24].trigger, 0.f);             // t = 0.8 s
  EXPECT_FLOAT_EQ(first[10].stick.y, -0.25f);
  EXPECT_TRUE(first[12].a && first[12].a_changed);
  EXPECT_TRUE(first[13].a && !first[13].a_changed);
}

}  // namespace
