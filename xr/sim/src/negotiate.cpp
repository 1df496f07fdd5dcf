// Loader negotiation and xrGetInstanceProcAddr: the only symbol the shared library exports is
// xrNegotiateLoaderRuntimeInterface; everything else is reached through the function table.
#include "dispatch.hpp"
#include "loader_interface.hpp"

#include <cstring>

namespace pushpull::xrsim {
namespace {

const FunctionTable& table() {
  static const FunctionTable t = [] {
    FunctionTable f;
    add_instance_functions(f);
    add_session_functions(f);
    add_frame_functions(f);
    add_space_functions(f);
    add_action_functions(f);
    add_swapchain_functions(f);
    add_vulkan_functions(f);
    add_automation_functions(f);
    return f;
  }();
  return t;
}

XrResult XRAPI_CALL get_instance_proc_addr(XrInstance instance, const char* name,
                                           PFN_xrVoidFunction* function) {
  if (function == nullptr || name == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *function = nullptr;
  const auto& entries = table().entries;
  const auto it = entries.find(name);
  if (instance == XR_NULL_HANDLE) {
    // Only these may be fetched without an instance.
    static const char* const global[] = {"xrEnumerateInstanceExtensionProperties",
                                         "xrEnumerateApiLayerProperties", "xrCreateInstance",
                                         "xrGetInstanceProcAddr"};
    for (const char* g : global)
      if (std::strcmp(g, name) == 0) {
        if (std::strcmp(name, "xrGetInstanceProcAddr") == 0) {
          *function = reinterpret_cast<PFN_xrVoidFunction>(&get_instance_proc_addr);
          return XR_SUCCESS;
        }
        if (it == entries.end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
        *function = it->second.function;
        return XR_SUCCESS;
      }
    return XR_ERROR_HANDLE_INVALID;
  }
  Lock lock(big_lock());
  Instance* inst = lookup<Instance>(instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (std::strcmp(name, "xrGetInstanceProcAddr") == 0) {
    *function = reinterpret_cast<PFN_xrVoidFunction>(&get_instance_proc_addr);
    return XR_SUCCESS;
  }
  if (it == entries.end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
  if (it->second.extension != nullptr && inst->extensions.count(it->second.extension) == 0)
    return XR_ERROR_FUNCTION_UNSUPPORTED;
  *function = it->second.function;
  return XR_SUCCESS;
}

}  // namespace
}  // namespace pushpull::xrsim

extern "C" __attribute__((visibility("default"))) XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loader_info, XrNegotiateRuntimeRequest* request) {
  if (loader_info == nullptr || request == nullptr ||
      loader_info->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loader_info->structVersion != PUSHPULL_XR_LOADER_INFO_STRUCT_VERSION ||
      loader_info->structSize != sizeof(XrNegotiateLoaderInfo) ||
      request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
      request->structVersion != PUSHPULL_XR_RUNTIME_INFO_STRUCT_VERSION ||
      request->structSize != sizeof(XrNegotiateRuntimeRequest))
    return XR_ERROR_INITIALIZATION_FAILED;
  if (loader_info->minInterfaceVersion > PUSHPULL_XR_CURRENT_LOADER_RUNTIME_VERSION ||
      loader_info->maxInterfaceVersion < PUSHPULL_XR_CURRENT_LOADER_RUNTIME_VERSION)
    return XR_ERROR_INITIALIZATION_FAILED;
  if (XR_VERSION_MAJOR(loader_info->minApiVersion) > 1 || XR_VERSION_MAJOR(loader_info->maxApiVersion) < 1)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->runtimeInterfaceVersion = PUSHPULL_XR_CURRENT_LOADER_RUNTIME_VERSION;
  request->runtimeApiVersion = XR_CURRENT_API_VERSION;
  request->getInstanceProcAddr = &pushpull::xrsim::get_instance_proc_addr;
  return XR_SUCCESS;
}
