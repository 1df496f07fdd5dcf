#include "pushpull/xr/runtime_calls.hpp"

namespace pushpull::xr {
namespace {
thread_local int g_depth = 0;
}  // namespace

RuntimeCallScope::RuntimeCallScope() {
  ++g_depth;
}
RuntimeCallScope::~RuntimeCallScope() {
  --g_depth;
}

bool inside_runtime_call() {
  return g_depth > 0;
}

}  // namespace pushpull::xr
