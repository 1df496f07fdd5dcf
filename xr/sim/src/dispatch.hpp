// The table xrGetInstanceProcAddr answers from. Each area of the runtime (instance.cpp, session.cpp,
// ...) registers its entry points with add_*_functions(); the compiler checks every function against
// the PFN type of the OpenXR function it implements. Built once, then read-only (thread-safe).
#pragma once

#include "state.hpp"

#include <string>
#include <unordered_map>

namespace pushpull::xrsim {

struct FunctionTable {
  struct Entry {
    PFN_xrVoidFunction function;
    const char* extension;  // nullptr for core functions
  };
  std::unordered_map<std::string, Entry> entries;

  template <class Pfn>
  void add(const char* name, Pfn function, const char* extension = nullptr) {
    entries[name] = {reinterpret_cast<PFN_xrVoidFunction>(function), extension};
  }
};

#define PUSHPULL_XR_ADD(table, name, fn) (table).add<PFN_##name>(#name, fn)
#define PUSHPULL_XR_ADD_EXT(table, name, fn, ext) (table).add<PFN_##name>(#name, fn, ext)

void add_instance_functions(FunctionTable& table);
void add_session_functions(FunctionTable& table);
void add_frame_functions(FunctionTable& table);
void add_space_functions(FunctionTable& table);
void add_action_functions(FunctionTable& table);
void add_swapchain_functions(FunctionTable& table);
void add_vulkan_functions(FunctionTable& table);
void add_automation_functions(FunctionTable& table);

// Checks an output array of the two-call idiom and copies `count` items with `write(i)`.
template <class Write>
XrResult two_call(uint32_t capacity, uint32_t* count_output, uint32_t count, Write write) {
  if (count_output == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count_output = count;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < count) return XR_ERROR_SIZE_INSUFFICIENT;
  for (uint32_t i = 0; i < count; ++i) write(i);
  return XR_SUCCESS;
}

// Writes a string through the two-call idiom (count includes the terminating NUL).
XrResult two_call_string(const std::string& s, uint32_t capacity, uint32_t* count_output, char* buffer);

}  // namespace pushpull::xrsim
