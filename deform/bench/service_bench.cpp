// service_bench: does the frame loop stay as fast with the deformation service solving as without, and how
// quickly do drag requests come back as previews and converged results?
//
// A frame thread ticks at 90 Hz. Each frame it reads the newest snapshot (Service::latest()) and copies its
// positions into a float buffer, as the renderer's upload does; during a drag it also submits one request
// per frame (or every k-th frame for slower drag rates) with the hand's current d, as the headset loop does.
// The worker solves asan (the default options) on a jittered height field of 10K or 50K vertices, the whole
// sheet as region, a disk handle at the centre, the border fixed. The hand moves along a curve so that the
// direction of d changes every request (asan then refactors every request, the expensive case).
//
// Printed per size: the frame thread's snapshot read (longest, 99th percentile), its mean busy time per
// frame idle and with solves running and their ratio (goal <= 1.05), the latency from submit() to the first
// preview snapshot of that request and to its converged snapshot, and per drag rate the share of requests
// that reach a converged result before the next one supersedes them. Then 12 short drags, each with the hand
// held still at its end: the latency from the last submit() to the converged shape, what the reviewer waits
// for once the hand stops (one sample per drag; the per-rate converged latencies above rest on 1-2), and how
// far that converged shape is from the energy's minimiser (solved to 1e-9 |d|) against its estimate.
//
// Usage: service_bench [--quick]   (--quick: 10K only, shorter drags)
#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <thread>
#include <vector>

#include "height_field.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/service.hpp"

namespace pd = pushpull::deform;
namespace pb = pushpull::bench;

namespace {

using Clock = std::chrono::steady_clock;
double ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}
double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// Per-request times seen by the worker's publication hook.
struct RequestTimes {
  Clock::time_point submitted, first_preview, converged, final;
  bool has_preview = false, has_converged = false, has_final = false;
  double per_iteration_ms = 0.0;  // solve time / iterations of its last snapshot
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  std::shared_ptr<const Eigen::MatrixXd> converged_positions;  // its converged snapshot's, when it has one
  double converged_estimate = NAN;                             // and that snapshot's error estimate / |d|
};

// One drag held still at its end (Bench::drags_then_hold).
struct HeldDrag {
  double latency_ms = NAN;  // last submit() -> converged snapshot; NaN: it did not converge
  RequestTimes last;        // the drag's last request
};

struct FrameStats {
  std::vector<double> read_ms;    // latest() alone
  std::vector<double> busy_ms;    // read + copy + normals: the same work idle and during drags
  std::vector<double> submit_ms;  // submit() during drags
};

class Bench {
 public:
  explicit Bench(const pb::HeightFieldProblem& problem) : problem_(problem) {
    pd::ServiceOptions options;
    options.on_publish = [this](const std::shared_ptr<const pd::Snapshot>& s) {
      if (s->kind != pd::Snapshot::Kind::Preview) return;
      const auto now = Clock::now();
      std::lock_guard lock(mutex_);
      auto it = times_.find(s->request);
      if (it == times_.end()) return;
      if (!it->second.has_preview) it->second.first_preview = now, it->second.has_preview = true;
      if (s->final && s->converged && !it->second.has_converged) {
        it->second.converged = now, it->second.has_converged = true;
        it->second.converged_positions = s->positions;
        it->second.converged_estimate = s->error_estimate.value_or(NAN);
      }
      if (s->final) it->second.final = now, it->second.has_final = true;
      if (s->iteration > 0) it->second.per_iteration_ms = s->solve_ms / s->iteration;
    };
    service_ = std::make_unique<pd::Service>(std::make_shared<const pd::Mesh>(problem.mesh), options);
    buffer_.resize(static_cast<std::size_t>(3 * problem.mesh.V.rows()));
    normals_.resize(buffer_.size());
  }

  // Runs the 90 Hz frame loop for `seconds`; submits a drag request every `every` frames (0 = never).
  FrameStats run(double seconds, int every, std::uint64_t drag) {
    FrameStats stats;
    const auto period = std::chrono::nanoseconds(1'000'000'000 / 90);
    const int frames = static_cast<int>(seconds * 90.0);
    auto next = Clock::now();
    for (int frame = 0; frame < frames; ++frame) {
      std::this_thread::sleep_until(next);
      next += period;
      const auto t0 = Clock::now();
      const std::shared_ptr<const pd::Snapshot> s = service_->latest();
      const auto t1 = Clock::now();
      upload(*s->positions);
      const auto t2 = Clock::now();
      if (every > 0 && frame % every == 0) {
        submit(frame / 90.0, drag);
        stats.submit_ms.push_back(ms(Clock::now() - t2));
      }
      stats.read_ms.push_back(ms(t1 - t0));
      stats.busy_ms.push_back(ms(t2 - t0));
    }
    return stats;
  }

  void wait_idle() { (void)service_->wait_idle(); }

  // `drags` drags of `seconds` each at 90 / `every` requests per second, the hand held still at the end of
  // each: per drag, the latency from its last submit() to its converged snapshot (what the reviewer waits
  // for once the hand stops) and that request's record.
  std::vector<HeldDrag> drags_then_hold(int drags, double seconds, int every, std::uint64_t first_drag) {
    std::vector<HeldDrag> held;
    for (int k = 0; k < drags; ++k) {
      (void)run(seconds, every, first_drag + static_cast<std::uint64_t>(k));
      wait_idle();
      std::lock_guard lock(mutex_);
      HeldDrag h;
      h.last = times_.rbegin()->second;
      if (h.last.has_converged) h.latency_ms = ms(h.last.converged - h.last.submitted);
      held.push_back(std::move(h));
      times_.clear();
    }
    return held;
  }

  // Share of submitted requests that converged, and their latencies; clears the record.
  void report(const char* label) {
    std::lock_guard lock(mutex_);
    std::vector<double> to_preview, to_converged, stop_delay, iteration;
    int converged = 0;
    const RequestTimes* previous = nullptr;
    for (const auto& [id, t] : times_) {
      if (t.has_preview) to_preview.push_back(ms(t.first_preview - t.submitted));
      if (t.has_converged) to_converged.push_back(ms(t.converged - t.submitted)), ++converged;
      // A request superseded mid-solve: how long after the next submit did its solve stop?
      if (previous && previous->has_final && !previous->has_converged && previous->final > t.submitted) {
        stop_delay.push_back(ms(previous->final - t.submitted));
        iteration.push_back(previous->per_iteration_ms);
      }
      previous = &t;
    }
    std::printf(
        "  %-22s %5zu requests, %5.1f%% converged before superseded | submit->first preview median %6.1f"
        " p99 %6.1f ms | submit->converged median %6.1f p99 %6.1f ms\n",
        label, times_.size(), 100.0 * converged / std::max<std::size_t>(1, times_.size()),
        percentile(to_preview, 0.5), percentile(to_preview, 0.99), percentile(to_converged, 0.5),
        percentile(to_converged, 0.99));
    if (!stop_delay.empty()) {
      std::printf(
          "  %-22s superseded mid-solve: %zu; stopped after the next submit within median %.2f, longest %.2f "
          "ms"
          " (one iteration: median %.2f ms)\n",
          "", stop_delay.size(), percentile(stop_delay, 0.5),
          *std::max_element(stop_delay.begin(), stop_delay.end()), percentile(iteration, 0.5));
    }
    times_.clear();
  }

  // What the renderer does on the CPU with a new snapshot: positions to floats, area-weighted vertex normals.
  void upload(const Eigen::MatrixXd& V) {
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      for (int c = 0; c < 3; ++c) buffer_[static_cast<std::size_t>(3 * v + c)] = static_cast<float>(V(v, c));
    }
    std::fill(normals_.begin(), normals_.end(), 0.0f);
    const Eigen::MatrixXi& F = problem_.mesh.F;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      const Eigen::Vector3f n = (b - a).cross(c - a).cast<float>();
      for (int k = 0; k < 3; ++k) {
        float* out = &normals_[static_cast<std::size_t>(3 * F(f, k))];
        out[0] += n.x(), out[1] += n.y(), out[2] += n.z();
      }
    }
  }

 private:
  void submit(double t, std::uint64_t drag) {
    // The hand: 100 mm out along a gentle curve over ~2 s, direction turning as it goes.
    const double s = std::min(1.0, t / 2.0);
    const double angle = 0.6 * std::sin(std::numbers::pi * t);
    pd::Request r;
    r.drag = drag;
    r.handle = pd::VertexHandle{problem_.handle};
    r.region.fixed = problem_.fixed;
    r.d = 0.1 * s * Eigen::Vector3d(std::sin(angle) * 0.5, 0.2 * s, std::cos(angle));
    r.options.method = pd::Method::Asan;
    std::lock_guard lock(mutex_);
    const auto now = Clock::now();
    const Eigen::Vector3d d = r.d;
    const std::uint64_t id = service_->submit(std::move(r));
    times_[id].submitted = now;
    times_[id].d = d;
  }

  const pb::HeightFieldProblem& problem_;
  std::unique_ptr<pd::Service> service_;
  std::vector<float> buffer_, normals_;
  std::mutex mutex_;
  std::map<std::uint64_t, RequestTimes> times_;
};

void bench_size(int n, double seconds) {
  const pb::HeightFieldProblem problem = pb::make_height_field(n);
  std::printf("\n%d vertices (region = whole sheet, %zu handle, %zu fixed), asan, 90 Hz frame thread\n",
              static_cast<int>(problem.mesh.V.rows()), problem.handle.size(), problem.fixed.size());
  Bench bench(problem);
  const FrameStats idle = bench.run(seconds, 0, 0);
  const FrameStats busy = bench.run(seconds, 1, 1);  // a request every frame (90 Hz drag)
  bench.wait_idle();
  bench.report("drag at 90 requests/s");
  std::vector<double> all_reads = idle.read_ms;
  all_reads.insert(all_reads.end(), busy.read_ms.begin(), busy.read_ms.end());
  std::printf("  snapshot read (latest()):  longest %.4f ms, p99 %.4f ms, median %.4f ms over %zu frames\n",
              *std::max_element(all_reads.begin(), all_reads.end()), percentile(all_reads, 0.99),
              percentile(all_reads, 0.5), all_reads.size());
  std::printf(
      "  frame work (read, positions to floats, vertex normals): idle %.3f ms, solving %.3f ms, ratio %.3f"
      " (goal <= 1.05); p99 idle %.3f, solving %.3f ms\n",
      mean(idle.busy_ms), mean(busy.busy_ms), mean(busy.busy_ms) / mean(idle.busy_ms),
      percentile(idle.busy_ms, 0.99), percentile(busy.busy_ms, 0.99));
  std::printf("  submit() on the frame thread: median %.4f ms, longest %.4f ms\n",
              percentile(busy.submit_ms, 0.5),
              *std::max_element(busy.submit_ms.begin(), busy.submit_ms.end()));
  for (int every : {3, 9, 18}) {  // 30, 10 and 5 requests per second
    (void)bench.run(seconds, every, static_cast<std::uint64_t>(every + 1));
    bench.wait_idle();
    char label[64];
    std::snprintf(label, sizeof label, "drag at %d requests/s", 90 / every);
    bench.report(label);
  }
  // The hand stops: 12 short drags along the same path (the curve's first 0.8 s: |d| up to 40 mm, its
  // direction turning) at 30 requests per second, each held still at its end.
  const int drags = 12;
  const std::vector<HeldDrag> held = bench.drags_then_hold(drags, 0.8, 3, 100);
  std::vector<double> hold;
  for (const HeldDrag& h : held)
    if (!std::isnan(h.latency_ms)) hold.push_back(h.latency_ms);
  std::printf(
      "  hand held still after a drag (%d drags of 0.8 s at 30 requests/s): last submit->converged median "
      "%.1f,"
      " p90 %.1f, longest %.1f ms%s\n",
      drags, percentile(hold, 0.5), percentile(hold, 0.9),
      hold.empty() ? 0.0 : *std::max_element(hold.begin(), hold.end()),
      hold.size() < held.size() ? " (some did not converge)" : "");
  // Is the held drag's "converged" honest? Its shape against the same energy solved to 1e-9 |d| from rest
  // (every drag ends at the same d; the reference is solved once).
  const pd::RegionOfInterest roi = pd::build_roi(problem.mesh, problem.handle, problem.fixed);
  const Eigen::Vector3d last_d = held.front().last.d;
  const Eigen::MatrixXd reference = pb::reference_solution(problem.mesh, roi, last_d, pd::Method::Asan);
  std::vector<double> ratio;
  int optimistic = 0;
  for (const HeldDrag& h : held) {
    if (!h.last.converged_positions || h.last.d != last_d) continue;
    const double truth =
        (*h.last.converged_positions - reference).rowwise().norm().maxCoeff() / last_d.norm();
    ratio.push_back(truth / h.last.converged_estimate);
    optimistic += ratio.back() > 2.0 ? 1 : 0;
  }
  std::printf(
      "  its converged shape against the energy solved to 1e-9 |d|: true distance / estimate median %.2f,"
      " largest %.2f; %d of %zu more than 2x optimistic\n",
      percentile(ratio, 0.5), ratio.empty() ? 0.0 : *std::max_element(ratio.begin(), ratio.end()), optimistic,
      ratio.size());
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::printf(
      "service_bench: deform::Service under a 90 Hz frame thread (this machine: %u hardware threads;"
      " the worker solves on one)\n",
      std::thread::hardware_concurrency());
  bench_size(100, quick ? 1.5 : 3.0);
  if (!quick) bench_size(224, 3.0);
  return 0;
}
