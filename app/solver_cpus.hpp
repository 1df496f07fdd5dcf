// `pushpull review --solver-cpus`: the CPUs the headset review gives the solver (the deformation service's
// worker and the snapshots' conversion to vertex data), the others staying with the frame loop and the
// threads it starts (a CPU renderer's, e.g. lavapipe's). With a GPU this keeps the frame thread's core free
// of solves; with lavapipe, whose rendering is CPU work, it keeps solves from slowing the frames down at the
// price of the renderer's cores (scripts/bench-review measures both).
//
// Thread-safety: plain functions.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {

struct CpuSplit {
  std::vector<int> solver;  // ascending, never empty
  std::vector<int> frames;  // the allowed CPUs not in `solver`, ascending, never empty
};

// The CPUs sharing a physical core with `cpu` (SMT siblings, itself included), from Linux's sysfs topology;
// just {cpu} where it cannot be read.
[[nodiscard]] std::vector<int> core_siblings(int cpu);

// The largest CPU number a list may name (Linux's fixed-size cpu_set_t holds 0..1023).
inline constexpr int kLargestCpu = 1023;

// spec: "none" (no split: nullopt), "auto" (the physical core of the last allowed CPU, all its allowed SMT
// siblings, when other CPUs remain for the frames; else that CPU alone when others remain; else none), or a
// list of CPU numbers and ranges, "1", "2-3", "1,3,5-7". allowed: the CPUs the process may run on
// (deform::allowed_cpus()); siblings: core_siblings, or a stand-in (tests). Throws std::invalid_argument
// naming the problem (for the caller to put after "--solver-cpus"): a malformed list, a CPU not allowed, or a
// list that leaves no CPU for the frames.
[[nodiscard]] std::optional<CpuSplit> split_cpus(
    const std::string& spec, const std::vector<int>& allowed,
    const std::function<std::vector<int>(int)>& siblings = core_siblings);

// "0-1,3": ascending CPUs as a list with ranges.
[[nodiscard]] std::string cpu_list_text(const std::vector<int>& cpus);

}  // namespace pushpull::app
