// The review loops' frame-time benchmark (`pushpull review --benchmark`): the work of each frame (headset:
// from xrWaitFrame's return to xrEndFrame's return; desktop: from the window's events to the present), in
// wall-clock and in the frame thread's own CPU time, split by whether the deformation service was solving
// meanwhile; printed as means, medians and 95th percentiles.
//
// Units: milliseconds. Thread-safety: one thread (the frame loop).
#pragma once

#include <cstddef>
#include <vector>

namespace pushpull::app {

// CPU time of the calling thread (ms): work done, without time spent preempted, blocked or sleeping.
[[nodiscard]] double thread_cpu_ms();

// Frame work (from xrWaitFrame's return to xrEndFrame's return), split by whether the solver was busy.
struct FrameStats {
  // The first frames build pipelines and upload the model: not what a frame costs.
  static constexpr size_t kWarmUpFrames = 30;
  size_t frames = 0;
  std::vector<double> idle_ms, solving_ms;
  std::vector<double> idle_cpu_ms, solving_cpu_ms;  // the frame thread's own CPU time over the same span
  size_t region_vertices = 0;                       // the largest region solved meanwhile
  double snapshot_ms = 0.0;                         // total time spent turning new snapshots into vertex data
  size_t snapshots = 0;
  // What a frame's time spans, as the first line prints it (the headset loop's by default).
  const char* span = "xrBeginFrame .. xrEndFrame, CPU";
  // One frame's wall-clock and frame-thread CPU time; the first kWarmUpFrames are counted, not kept.
  void add_frame(bool solving, double ms, double cpu_ms);
  // A new snapshot drawn, `cpu_ms` to turn it into vertex data.
  void add_snapshot(double cpu_ms) {
    snapshot_ms += cpu_ms;
    ++snapshots;
  }
  // Mean and q-quantile (0..1) of v; 0 when empty.
  static double mean(const std::vector<double>& v);
  static double percentile(std::vector<double> v, double q);
  // The benchmark's three lines on stdout.
  void print() const;
};

}  // namespace pushpull::app
