// bvh_bench: the headset's hit test. TriangleBvh build, refit and ray_hit on a jittered height field of about
// 500K triangles (the size issue 12 sets the < 1 ms goal for), rays from a reviewer's hand positions towards
// random points of the sheet; closest_point for comparison. Printed, not a timed test.
//
//   ./build/deform/bench/bvh_bench [--quick]     (--quick: ~50K triangles)
#include "height_field.hpp"

#include "pushpull/deform/triangle_bvh.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int n = quick ? 160 : 501;  // 2 (n-1)^2 triangles: 50K or 500K
  const auto problem = pushpull::bench::make_height_field(n);
  const auto& mesh = problem.mesh;
  std::printf("bvh_bench: height field %d x %d, %ld vertices, %ld triangles\n", n, n, long(mesh.V.rows()),
              long(mesh.F.rows()));

  auto start = Clock::now();
  pushpull::deform::TriangleBvh bvh(mesh.V, mesh.F);
  std::printf("build:        %8.1f ms\n", ms_since(start));
  Eigen::MatrixXd moved = mesh.V;
  moved.col(2) *= 1.01;
  start = Clock::now();
  bvh.refit(moved);
  std::printf("refit:        %8.1f ms\n", ms_since(start));

  // Rays from hand positions 0.3-0.8 above the sheet, aimed at random points on it (every ray hits).
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.05, 0.95), h(0.3, 0.8);
  const int rays = quick ? 2000 : 10000;
  std::vector<double> times;
  times.reserve(size_t(rays));
  int hits = 0;
  for (int i = 0; i < rays; ++i) {
    const Eigen::Vector3d origin(u(rng), u(rng), h(rng));
    const Eigen::Vector3d target(u(rng), u(rng), 0.0);
    start = Clock::now();
    const auto hit = bvh.ray_hit(moved, origin, target - origin);
    times.push_back(ms_since(start));
    hits += hit.has_value();
  }
  std::sort(times.begin(), times.end());
  double sum = 0.0;
  for (double t : times) sum += t;
  std::printf("ray_hit:      mean %.4f ms, median %.4f ms, p99 %.4f ms, max %.4f ms over %d rays (%d hits); "
              "goal < 1 ms\n",
              sum / rays, times[times.size() / 2], times[size_t(0.99 * double(times.size()))], times.back(), rays,
              hits);
  times.clear();
  for (int i = 0; i < rays; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), h(rng) - 0.5);
    start = Clock::now();
    (void)bvh.closest_point(moved, p);
    times.push_back(ms_since(start));
  }
  std::sort(times.begin(), times.end());
  std::printf("closest_point: median %.4f ms, p99 %.4f ms\n", times[times.size() / 2],
              times[size_t(0.99 * double(times.size()))]);
  return 0;
}
