#include "frame_stats.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <numeric>

namespace pushpull::app {

double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}

double FrameStats::mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

double FrameStats::percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

void FrameStats::add_frame(bool solving, double ms, double cpu_ms) {
  if (++frames <= kWarmUpFrames) return;
  (solving ? solving_ms : idle_ms).push_back(ms);
  (solving ? solving_cpu_ms : idle_cpu_ms).push_back(cpu_ms);
}

void FrameStats::print() const {
  auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  std::printf(
      "frame time (%s; the first %zu frames left out as warm-up): "
      "idle %.2f ms mean, %.2f median, %.2f p95 (%zu frames); "
      "solver running %.2f ms mean, %.2f median, %.2f p95 (%zu frames); "
      "ratio %.3f of the means, %.3f of the medians\n",
      span, kWarmUpFrames, mean(idle_ms), percentile(idle_ms, 0.5), percentile(idle_ms, 0.95), idle_ms.size(),
      mean(solving_ms), percentile(solving_ms, 0.5), percentile(solving_ms, 0.95), solving_ms.size(),
      ratio(mean(solving_ms), mean(idle_ms)), ratio(percentile(solving_ms, 0.5), percentile(idle_ms, 0.5)));
  std::printf(
      "frame thread CPU time (the same span, without time spent preempted or waiting): idle %.2f ms "
      "median, %.2f p95; solver running %.2f ms median, %.2f p95; ratio %.3f of the medians\n",
      percentile(idle_cpu_ms, 0.5), percentile(idle_cpu_ms, 0.95), percentile(solving_cpu_ms, 0.5),
      percentile(solving_cpu_ms, 0.95), ratio(percentile(solving_cpu_ms, 0.5), percentile(idle_cpu_ms, 0.5)));
  std::printf(
      "largest region solved: %zu vertices; %zu new snapshots drawn, %.2f ms CPU each to turn into "
      "vertex data (positions, normals, colour-map scalars) on the scene's converter thread\n",
      region_vertices, snapshots, snapshots ? snapshot_ms / double(snapshots) : 0.0);
}

}  // namespace pushpull::app
