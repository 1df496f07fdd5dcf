// Which CPUs a thread may run on (Linux sched_setaffinity): the headset review keeps the solver's threads on
// CPUs of their own, so a solve never takes a core the frame loop (or a CPU renderer such as lavapipe, whose
// threads inherit the frame thread's set) is using.
//
// CPUs are numbered as the kernel numbers them (0, 1, ...). Elsewhere than Linux: nothing is pinned.
// Thread-safety: each call concerns the calling thread only.
#pragma once

#include <span>
#include <vector>

namespace pushpull::deform {

// The CPUs the calling thread may run on now, ascending; empty where this cannot be asked.
[[nodiscard]] std::vector<int> allowed_cpus();

// Restricts the calling thread (and the threads it starts afterwards) to `cpus`. Returns false when the
// system refused it or cannot do it (nothing changed then); an empty list changes nothing and returns true.
bool pin_calling_thread(std::span<const int> cpus);

}  // namespace pushpull::deform
