// Instance, system, view configurations, paths, time conversion and function lookup, through the loader.
#include "sim_fixture.hpp"

#include "../src/loader_interface.hpp"

#include <dlfcn.h>

#include <gtest/gtest.h>

#include <cstring>
#include <ctime>
#include <string>

using namespace sim_test;

namespace {

class InstanceTest : public ::testing::Test {
 protected:
  void SetUp() override { use_simulated_runtime(); }
};

TEST_F(InstanceTest, AdvertisesTheExtensionsOfTheIssue) {
  uint32_t n = 0;
  ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr), XR_SUCCESS);
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES});
  ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data()), XR_SUCCESS);
  std::vector<std::string> names;
  for (const auto& p : props) names.push_back(p.extensionName);
  for (const char* e : {"XR_KHR_vulkan_enable", "XR_KHR_vulkan_enable2", "XR_KHR_convert_timespec_time",
                        "XR_EXT_conformance_automation", "XR_EXT_hp_mixed_reality_controller",
                        "XR_HTC_vive_cosmos_controller_interaction", "XR_EXT_samsung_odyssey_controller"})
    EXPECT_NE(std::find(names.begin(), names.end(), e), names.end()) << e;
}

// The no-controller-extensions quirk: a runtime with the core interaction profiles only lists none of the
// extensions that bring others, and refuses an instance that asks for one.
TEST_F(InstanceTest, WithoutControllerExtensionsTheyAreNeitherListedNorAccepted) {
  setenv("PUSHPULL_XR_SIM_QUIRKS", "no-controller-extensions", 1);
  struct Unset {
    ~Unset() { unsetenv("PUSHPULL_XR_SIM_QUIRKS"); }
  } unset;
  uint32_t n = 0;
  ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr), XR_SUCCESS);
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES});
  ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data()), XR_SUCCESS);
  for (const auto& p : props) EXPECT_EQ(std::string(p.extensionName).find("controller"), std::string::npos);
  const char* asked[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
                         XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME};
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::strcpy(ci.applicationInfo.applicationName, "quirk");
  ci.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  ci.enabledExtensionCount = 2;
  ci.enabledExtensionNames = asked;
  XrInstance instance = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateInstance(&ci, &instance), XR_ERROR_EXTENSION_NOT_PRESENT);
}

TEST_F(InstanceTest, PropertiesNameTheRuntime) {
  Sim sim;
  XrInstanceProperties p{XR_TYPE_INSTANCE_PROPERTIES};
  ASSERT_EQ(xrGetInstanceProperties(sim.instance, &p), XR_SUCCESS);
  EXPECT_STREQ(p.runtimeName, "pushpull simulated runtime");
}

TEST_F(InstanceTest, RejectsUnknownExtensionAndEmptyName) {
  const char* ext[] = {"XR_FB_nonexistent_extension"};
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "t");
  ci.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  ci.enabledExtensionCount = 1;
  ci.enabledExtensionNames = ext;
  XrInstance instance = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateInstance(&ci, &instance), XR_ERROR_EXTENSION_NOT_PRESENT);
}

TEST_F(InstanceTest, SystemIsAnHmdAndHandheldIsUnsupported) {
  Sim sim;
  EXPECT_NE(sim.system, XR_NULL_SYSTEM_ID);
  XrSystemGetInfo si{XR_TYPE_SYSTEM_GET_INFO};
  si.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
  XrSystemId id = XR_NULL_SYSTEM_ID;
  EXPECT_EQ(xrGetSystem(sim.instance, &si, &id), XR_ERROR_FORM_FACTOR_UNSUPPORTED);
  XrSystemProperties props{XR_TYPE_SYSTEM_PROPERTIES};
  ASSERT_EQ(xrGetSystemProperties(sim.instance, sim.system, &props), XR_SUCCESS);
  EXPECT_TRUE(props.trackingProperties.positionTracking);
  EXPECT_EQ(xrGetSystemProperties(sim.instance, sim.system + 7, &props), XR_ERROR_SYSTEM_INVALID);
}

TEST_F(InstanceTest, PrimaryStereoWithConfiguredResolution) {
  setenv("PUSHPULL_XR_SIM_WIDTH", "640", 1);
  setenv("PUSHPULL_XR_SIM_HEIGHT", "480", 1);
  Sim sim;
  uint32_t n = 0;
  ASSERT_EQ(xrEnumerateViewConfigurations(sim.instance, sim.system, 0, &n, nullptr), XR_SUCCESS);
  ASSERT_EQ(n, 1u);
  XrViewConfigurationType type{};
  ASSERT_EQ(xrEnumerateViewConfigurations(sim.instance, sim.system, 1, &n, &type), XR_SUCCESS);
  EXPECT_EQ(type, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO);
  std::vector<XrViewConfigurationView> views(2, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
  ASSERT_EQ(xrEnumerateViewConfigurationViews(sim.instance, sim.system, type, 1, &n, views.data()),
            XR_ERROR_SIZE_INSUFFICIENT);
  ASSERT_EQ(xrEnumerateViewConfigurationViews(sim.instance, sim.system, type, 2, &n, views.data()),
            XR_SUCCESS);
  EXPECT_EQ(views[0].recommendedImageRectWidth, 640u);
  EXPECT_EQ(views[1].recommendedImageRectHeight, 480u);
  EXPECT_EQ(xrEnumerateViewConfigurationViews(sim.instance, sim.system,
                                              XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO, 0, &n, nullptr),
            XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
  XrEnvironmentBlendMode mode{};
  ASSERT_EQ(xrEnumerateEnvironmentBlendModes(sim.instance, sim.system, type, 1, &n, &mode), XR_SUCCESS);
  EXPECT_EQ(mode, XR_ENVIRONMENT_BLEND_MODE_OPAQUE);
}

TEST_F(InstanceTest, PathsRoundTripAndMalformedPathsFail) {
  Sim sim;
  const XrPath p = sim.path("/user/hand/left/input/select/click");
  EXPECT_EQ(sim.path("/user/hand/left/input/select/click"), p);
  char buffer[XR_MAX_PATH_LENGTH];
  uint32_t n = 0;
  ASSERT_EQ(xrPathToString(sim.instance, p, sizeof buffer, &n, buffer), XR_SUCCESS);
  EXPECT_STREQ(buffer, "/user/hand/left/input/select/click");
  XrPath bad = XR_NULL_PATH;
  for (const char* s : {"", "user", "/user/", "/user//hand", "/User/hand", "/user/../hand", "/user/ hand"})
    EXPECT_EQ(xrStringToPath(sim.instance, s, &bad), XR_ERROR_PATH_FORMAT_INVALID) << "'" << s << "'";
  EXPECT_EQ(xrPathToString(sim.instance, p + 1000, sizeof buffer, &n, buffer), XR_ERROR_PATH_INVALID);
}

TEST_F(InstanceTest, TimespecConversionRoundTrips) {
  Sim sim;
  auto to_time = sim.fn<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR");
  auto to_timespec = sim.fn<PFN_xrConvertTimeToTimespecTimeKHR>("xrConvertTimeToTimespecTimeKHR");
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  XrTime t = 0;
  ASSERT_EQ(to_time(sim.instance, &ts, &t), XR_SUCCESS);
  timespec back{};
  ASSERT_EQ(to_timespec(sim.instance, t, &back), XR_SUCCESS);
  EXPECT_EQ(back.tv_sec, ts.tv_sec);
  EXPECT_EQ(back.tv_nsec, ts.tv_nsec);
  EXPECT_EQ(to_timespec(sim.instance, 0, &back), XR_ERROR_TIME_INVALID);
}

TEST_F(InstanceTest, EveryCoreFunctionIsThere) {
  Sim sim;
  const char* core[] = {"xrGetInstanceProcAddr",
                        "xrEnumerateApiLayerProperties",
                        "xrEnumerateInstanceExtensionProperties",
                        "xrCreateInstance",
                        "xrDestroyInstance",
                        "xrGetInstanceProperties",
                        "xrPollEvent",
                        "xrResultToString",
                        "xrStructureTypeToString",
                        "xrGetSystem",
                        "xrGetSystemProperties",
                        "xrEnumerateEnvironmentBlendModes",
                        "xrCreateSession",
                        "xrDestroySession",
                        "xrEnumerateReferenceSpaces",
                        "xrCreateReferenceSpace",
                        "xrGetReferenceSpaceBoundsRect",
                        "xrCreateActionSpace",
                        "xrLocateSpace",
                        "xrDestroySpace",
                        "xrEnumerateViewConfigurations",
                        "xrGetViewConfigurationProperties",
                        "xrEnumerateViewConfigurationViews",
                        "xrEnumerateSwapchainFormats",
                        "xrCreateSwapchain",
                        "xrDestroySwapchain",
                        "xrEnumerateSwapchainImages",
                        "xrAcquireSwapchainImage",
                        "xrWaitSwapchainImage",
                        "xrReleaseSwapchainImage",
                        "xrBeginSession",
                        "xrEndSession",
                        "xrRequestExitSession",
                        "xrWaitFrame",
                        "xrBeginFrame",
                        "xrEndFrame",
                        "xrLocateViews",
                        "xrStringToPath",
                        "xrPathToString",
                        "xrCreateActionSet",
                        "xrDestroyActionSet",
                        "xrCreateAction",
                        "xrDestroyAction",
                        "xrSuggestInteractionProfileBindings",
                        "xrAttachSessionActionSets",
                        "xrGetCurrentInteractionProfile",
                        "xrGetActionStateBoolean",
                        "xrGetActionStateFloat",
                        "xrGetActionStateVector2f",
                        "xrGetActionStatePose",
                        "xrSyncActions",
                        "xrEnumerateBoundSourcesForAction",
                        "xrGetInputSourceLocalizedName",
                        "xrApplyHapticFeedback",
                        "xrStopHapticFeedback"};
  for (const char* name : core) {
    PFN_xrVoidFunction f = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(sim.instance, name, &f), XR_SUCCESS) << name;
    EXPECT_NE(f, nullptr) << name;
  }
  PFN_xrVoidFunction f = nullptr;
  EXPECT_EQ(xrGetInstanceProcAddr(sim.instance, "xrNoSuchFunctionKHR", &f), XR_ERROR_FUNCTION_UNSUPPORTED);

  // The same straight from the runtime, without the loader's trampolines in between: negotiate as the
  // loader does, create an instance through the runtime's xrGetInstanceProcAddr and look every name up.
  void* lib = dlopen(PUSHPULL_XR_SIM_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(lib, nullptr) << dlerror();
  using Negotiate = XrResult(XRAPI_PTR*)(const XrNegotiateLoaderInfo*, XrNegotiateRuntimeRequest*);
  auto negotiate = reinterpret_cast<Negotiate>(dlsym(lib, "xrNegotiateLoaderRuntimeInterface"));
  ASSERT_NE(negotiate, nullptr);
  XrNegotiateLoaderInfo info{XR_LOADER_INTERFACE_STRUCT_LOADER_INFO,
                             1,
                             sizeof(XrNegotiateLoaderInfo),
                             1,
                             1,
                             XR_MAKE_VERSION(1, 0, 0),
                             XR_MAKE_VERSION(1, 0x3ff, 0xfff)};
  XrNegotiateRuntimeRequest request{
      XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST, 1, sizeof(XrNegotiateRuntimeRequest), 0, 0, nullptr};
  XrNegotiateLoaderInfo wrong = info;
  wrong.minInterfaceVersion = wrong.maxInterfaceVersion = 7;
  EXPECT_EQ(negotiate(&wrong, &request), XR_ERROR_INITIALIZATION_FAILED);
  ASSERT_EQ(negotiate(&info, &request), XR_SUCCESS);
  EXPECT_EQ(request.runtimeInterfaceVersion, 1u);
  ASSERT_NE(request.getInstanceProcAddr, nullptr);
  PFN_xrVoidFunction create = nullptr;
  ASSERT_EQ(request.getInstanceProcAddr(XR_NULL_HANDLE, "xrCreateInstance", &create), XR_SUCCESS);
  EXPECT_EQ(request.getInstanceProcAddr(XR_NULL_HANDLE, "xrPollEvent", &f), XR_ERROR_HANDLE_INVALID);
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "direct");
  ci.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  XrInstance direct = XR_NULL_HANDLE;
  ASSERT_EQ(reinterpret_cast<PFN_xrCreateInstance>(create)(&ci, &direct), XR_SUCCESS);
  for (const char* name : core) {
    PFN_xrVoidFunction g = nullptr;
    EXPECT_EQ(request.getInstanceProcAddr(direct, name, &g), XR_SUCCESS) << name;
    EXPECT_NE(g, nullptr) << name;
  }
  PFN_xrVoidFunction destroy = nullptr;
  ASSERT_EQ(request.getInstanceProcAddr(direct, "xrDestroyInstance", &destroy), XR_SUCCESS);
  EXPECT_EQ(reinterpret_cast<PFN_xrDestroyInstance>(destroy)(direct), XR_SUCCESS);
  dlclose(lib);
}

TEST_F(InstanceTest, ExtensionFunctionsNeedTheExtensionEnabled) {
  Sim sim({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME});
  PFN_xrVoidFunction f = nullptr;
  EXPECT_EQ(xrGetInstanceProcAddr(sim.instance, "xrConvertTimeToTimespecTimeKHR", &f),
            XR_ERROR_FUNCTION_UNSUPPORTED);
  EXPECT_EQ(f, nullptr);
  EXPECT_EQ(xrGetInstanceProcAddr(sim.instance, "xrSetInputDeviceActiveEXT", &f),
            XR_ERROR_FUNCTION_UNSUPPORTED);
  EXPECT_EQ(xrGetInstanceProcAddr(sim.instance, "xrCreateVulkanInstanceKHR", &f), XR_SUCCESS);
  EXPECT_NE(f, nullptr);
}

TEST_F(InstanceTest, ResultAndStructureNames) {
  Sim sim;
  char buffer[XR_MAX_RESULT_STRING_SIZE];
  ASSERT_EQ(xrResultToString(sim.instance, XR_ERROR_SESSION_NOT_RUNNING, buffer), XR_SUCCESS);
  EXPECT_STREQ(buffer, "XR_ERROR_SESSION_NOT_RUNNING");
  char sbuffer[XR_MAX_STRUCTURE_NAME_SIZE];
  ASSERT_EQ(xrStructureTypeToString(sim.instance, XR_TYPE_FRAME_STATE, sbuffer), XR_SUCCESS);
  EXPECT_STREQ(sbuffer, "XR_TYPE_FRAME_STATE");
}

TEST_F(InstanceTest, WrongHandlesAreRejected) {
  Sim sim;
  XrSession fake = reinterpret_cast<XrSession>(reinterpret_cast<uintptr_t>(sim.instance) + 64);
  XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO};
  bi.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  EXPECT_EQ(xrBeginSession(fake, &bi), XR_ERROR_HANDLE_INVALID);
  // The instance handle passed where a session is expected.
  EXPECT_EQ(xrBeginSession(reinterpret_cast<XrSession>(sim.instance), &bi), XR_ERROR_HANDLE_INVALID);
  XrActionSet set = XR_NULL_HANDLE;
  XrActionSetCreateInfo ci{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(ci.actionSetName, "set");
  std::strcpy(ci.localizedActionSetName, "Set");
  ASSERT_EQ(xrCreateActionSet(sim.instance, &ci, &set), XR_SUCCESS);
  ASSERT_EQ(xrDestroyActionSet(set), XR_SUCCESS);
  EXPECT_EQ(xrDestroyActionSet(set), XR_ERROR_HANDLE_INVALID);  // destroyed
}

TEST_F(InstanceTest, ABadInputScriptFailsInstanceCreation) {
  setenv("PUSHPULL_XR_SIM_INPUT",
         write_temp_file("bad.jsonl", "{\"t\": 0.0, \"path\": \"/user/head\", \"pose\": {\"p\": [1, 2]}}\n")
             .c_str(),
         1);
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "t");
  ci.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  XrInstance instance = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateInstance(&ci, &instance), XR_ERROR_INITIALIZATION_FAILED);
  // Recording headers and other records without "t" are skipped; comments too.
  setenv("PUSHPULL_XR_SIM_INPUT",
         write_temp_file("ok.jsonl",
                         "{\"model\": \"car.glb\", \"version\": 1}\n# comment\n\n"
                         "{\"t\": 0.5, \"path\": \"/user/hand/left/input/menu/click\", \"value\": true}\n")
             .c_str(),
         1);
  ASSERT_EQ(xrCreateInstance(&ci, &instance), XR_SUCCESS);
  EXPECT_EQ(xrDestroyInstance(instance), XR_SUCCESS);
}

TEST_F(InstanceTest, SessionNeedsGraphicsRequirementsFirst) {
  Sim sim;
  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  XrSessionCreateInfo sci{XR_TYPE_SESSION_CREATE_INFO};
  sci.next = &binding;
  sci.systemId = sim.system;
  XrSession s = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateSession(sim.instance, &sci, &s), XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);
}

}  // namespace
