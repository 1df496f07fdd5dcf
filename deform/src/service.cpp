// deform::Service: one worker thread, a superseding request slot, a command queue, snapshots published
// through an atomic shared_ptr (see service.hpp).
#include "pushpull/deform/service.hpp"

#ifdef __linux__
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "pushpull/deform/cpu_affinity.hpp"
#include "pushpull/deform/mesh_validation.hpp"
#include "snapshot_handoff.hpp"

namespace pushpull::deform {
namespace {

// A preview request without a rate hint is not stopped by a newer one of its setup before it has a
// contraction rate, or this many iterations (the rate needs 16 on the estimate's 8-pair window; solve_preview
// says why).
constexpr int kUnhintedRequestIterations = 24;

// The worker's place on the machine: its CPUs (worker_cpus), then its niceness (setpriority on the calling
// thread: Linux threads have their own) or the idle scheduling class.
void place_worker_thread(int nice, bool idle, const std::vector<int>& cpus) {
  (void)pin_calling_thread(cpus);
#ifdef __linux__
  if (nice > 0) (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), std::min(nice, 19));
  if (idle) {
    sched_param none{};
    (void)::sched_setscheduler(0, SCHED_IDLE, &none);
  }
#else
  (void)nice;
  (void)idle;
#endif
}

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

bool same_handle(const Request& a, const Request& b) {
  if (a.handle.index() != b.handle.index()) return false;
  if (const auto* sa = std::get_if<SurfaceHandle>(&a.handle)) {
    const auto& sb = std::get<SurfaceHandle>(b.handle);
    return sa->point.face == sb.point.face && sa->point.point == sb.point.point && sa->radius == sb.radius;
  }
  return std::get<VertexHandle>(a.handle).vertices == std::get<VertexHandle>(b.handle).vertices;
}

bool same_options(const DeformOptions& a, const DeformOptions& b) {
  return a.method == b.method && a.mu == b.mu && a.stretch_direction == b.stretch_direction &&
         a.asan_base == b.asan_base && a.max_iterations == b.max_iterations && a.tolerance == b.tolerance &&
         a.energy_tolerance == b.energy_tolerance && a.anderson_window == b.anderson_window &&
         a.smooth_start_min_free == b.smooth_start_min_free &&
         a.coarse_start_min_free == b.coarse_start_min_free && a.arap_n_rings == b.arap_n_rings &&
         a.sr_arap_alpha == b.sr_arap_alpha && a.arap_h_lambda == b.arap_h_lambda && a.validate == b.validate;
}

// Same Deformer setup: handle, region and options (d may differ).
bool same_setup(const Request& a, const Request& b) {
  return a.drag == b.drag && same_handle(a, b) && a.region.max_distance == b.region.max_distance &&
         a.region.fixed == b.region.fixed && a.region.attach_parts == b.region.attach_parts &&
         a.region.attach_reach == b.region.attach_reach && same_options(a.options, b.options);
}

double largest_displacement(const Eigen::MatrixXd& V, const Eigen::MatrixXd& rest) {
  return V.rows() == 0 ? 0.0 : (V - rest).rowwise().norm().maxCoeff();
}

}  // namespace

std::uint64_t position_hash(const Eigen::MatrixXd& V) {
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash ^= bytes[i];
      hash *= 1099511628211ull;
    }
  };
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    for (Eigen::Index c = 0; c < V.cols(); ++c) {
      double x = V(r, c);
      if (x == 0.0) x = 0.0;  // -0 and +0 hash alike
      mix(&x, sizeof x);
    }
  }
  return hash;
}

struct Service::Impl {
  struct Pending {
    std::uint64_t sequence = 0;
    Request request;
    Clock::time_point submitted;
  };
  enum class CommandKind { Commit, Undo, Redo, Cancel };
  struct Command {
    CommandKind kind = CommandKind::Commit;
    std::shared_ptr<const Pending> request;  // Commit: what to commit
    Clock::time_point issued;
  };
  // The worker's current solve setup, reused while a drag's requests keep handle, region and options.
  struct Active {
    Request request;  // the last request solved with this setup
    std::uint64_t state_id = 0;
    std::unique_ptr<Deformer> deformer;
    std::shared_ptr<const RegionOfInterest> region;
    std::optional<AttachedParts> parts;                   // when the request attaches parts
    std::shared_ptr<const Eigen::MatrixXd> last_iterate;  // warm start for the next request of the drag
    std::optional<double> last_rate;  // the contraction rate known when last_iterate was made (its hint)
    bool last_rate_settled = false;   // and whether it was settled (DeformResult::rate_settled)
    // A request of this setup was held for a rate (solve_preview) and had none after
    // kUnhintedRequestIterations (a method whose rate comes late or never): the next are not held.
    bool hold_exhausted = false;

    // The solver's positions with the attached parts moved along (a new matrix when there are parts).
    std::shared_ptr<const Eigen::MatrixXd> with_parts(std::shared_ptr<const Eigen::MatrixXd> V) const {
      if (!parts || parts->parts().empty()) return V;
      auto moved = std::make_shared<Eigen::MatrixXd>(*V);
      parts->apply(*moved);
      return moved;
    }
  };
  struct State {  // one committed state of the history
    std::uint64_t id = 0;
    HistoryEntry entry;
  };

  ServiceOptions options;

  // Guarded by mutex: the hand-off between callers and the worker (held for moves, never while solving).
  mutable std::mutex mutex;
  std::condition_variable wake;          // worker waits for work
  mutable std::condition_variable idle;  // wait_idle() waits for the worker
  // Built outside the lock; only the pointers move under it.
  std::shared_ptr<const Pending> pending;         // newest request not yet taken by the worker
  std::shared_ptr<const Pending> last_submitted;  // what commit() commits
  std::deque<Command> commands;
  std::uint64_t next_sequence = 1;
  bool busy = false;
  bool stop = false;

  std::atomic<bool> interrupt{
      false};  // new work arrived: the running preview solve stops at its next iteration
  std::atomic<bool> stopping{false};  // destructor: every solve stops at its next iteration
  // A command (commit, cancel, undo, ...) is queued: unlike a newer request, it also stops a preview's coarse
  // solve (solve_preview says why). Cleared with interrupt.
  std::atomic<bool> command_waiting{false};
  detail::NewestValue<const Snapshot> newest;
  std::atomic<std::uint64_t> revision{1};

  // Guarded by history_mutex (written by the worker, read by history()).
  mutable std::mutex history_mutex;
  std::vector<State> states;
  std::size_t position = 0;
  std::uint64_t next_state_id = 2;

  // Worker-only.
  std::uint64_t generation = 0;
  std::optional<Active> active;

  std::thread worker;  // last: started once everything above exists

  const State& current() const { return states[position]; }  // worker, or under history_mutex

  void publish(Snapshot snapshot) {
    snapshot.generation = ++generation;
    auto shared = std::make_shared<const Snapshot>(std::move(snapshot));
    newest.store(shared);
    if (!options.on_publish) return;
    // The snapshot is published whatever the callback does: a throw from it must not fail the request (a
    // commit already in the history would be reported failed) nor, thrown again from the error snapshot
    // the worker publishes for it, end the process.
    try {
      options.on_publish(shared);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pushpull: the deformation service's on_publish callback failed: %s\n", e.what());
    } catch (...) {
      std::fprintf(stderr, "pushpull: the deformation service's on_publish callback failed\n");
    }
  }

  Snapshot state_snapshot(Snapshot::Kind kind, std::uint64_t request, Clock::time_point since) const {
    Snapshot s;
    s.kind = kind;
    s.request = request;
    s.revision = current().id;
    s.rest = current().entry.state;
    s.positions = std::shared_ptr<const Eigen::MatrixXd>(s.rest, &s.rest->V);  // aliases the state's V
    s.final = true;
    s.converged = kind != Snapshot::Kind::Error;
    s.latency_ms = ms_between(since, Clock::now());
    return s;
  }

  void publish_error(std::uint64_t request, Clock::time_point since, std::string what, bool commit) {
    Snapshot s = state_snapshot(Snapshot::Kind::Error, request, since);
    s.error = std::move(what);
    s.failed_commit = commit;
    publish(std::move(s));
  }

  // The Deformer for `request` on the current state: the active one when the setup is the same.
  Active& setup_for(const Request& request, double& setup_ms) {
    const auto start = Clock::now();
    setup_ms = 0.0;
    if (active && active->state_id == current().id && same_setup(active->request, request)) return *active;
    active.reset();  // frees the old factorization before building the new one
    const Mesh& mesh = *current().entry.state;
    std::vector<int> handle;
    if (const auto* surface = std::get_if<SurfaceHandle>(&request.handle)) {
      handle = surface_handle(mesh, surface->point, surface->radius);
    } else {
      handle = std::get<VertexHandle>(request.handle).vertices;
    }
    RegionOfInterest roi = build_roi(mesh, handle, request.region.fixed, request.region.max_distance);
    DeformOptions options = request.options;
    options.progress = nullptr;
    options.threads = 1;  // the worker alone: the frame loop keeps the other core
    Active a;
    a.request = request;
    a.state_id = current().id;
    a.region = std::make_shared<const RegionOfInterest>(roi);
    if (request.region.attach_parts) a.parts.emplace(mesh, roi, AttachOptions{request.region.attach_reach});
    a.deformer = std::make_unique<Deformer>(current().entry.state, std::move(roi), options);
    active = std::move(a);
    setup_ms = ms_between(start, Clock::now());
    return *active;
  }

  // A snapshot of request p's positions V (the solver's, parts not yet moved) on the current state.
  Snapshot request_snapshot(Snapshot::Kind kind, const Pending& p, const Active& a,
                            std::shared_ptr<const Eigen::MatrixXd> V) const {
    Snapshot s;
    s.kind = kind;
    s.request = p.sequence;
    s.revision = current().id;
    s.rest = current().entry.state;
    s.positions = a.with_parts(std::move(V));
    s.region = a.region;
    s.attached_parts = a.parts ? a.parts->parts().size() : 0;
    s.method = p.request.options.method;
    s.d = p.request.d;
    s.max_displacement = largest_displacement(*s.positions, s.rest->V);
    s.latency_ms = ms_between(p.submitted, Clock::now());
    return s;
  }

  Snapshot result_snapshot(const Pending& p, const Active& a, const DeformResult& r,
                           Snapshot::Kind kind) const {
    Snapshot s = request_snapshot(kind, p, a, std::make_shared<const Eigen::MatrixXd>(r.V));
    s.iteration = r.iterations;
    s.converged = r.converged;
    s.error_estimate = r.error_estimate;
    s.estimate_rate = r.estimate_rate;
    s.contraction_rate = r.contraction_rate;
    s.probe_rate = r.probe_rate;
    s.probe_evaluations = r.probe_evaluations;
    s.smooth_start = r.smooth_start;
    s.coarse_start = r.coarse_start;
    s.coarse_evaluations = r.coarse_evaluations;
    s.per_iteration_ms = r.timing.per_iteration;
    s.final = true;
    s.energy = r.energy_trace.empty() ? r.initial_energy : r.energy_trace.back();
    s.factorize_ms = r.timing.factorize;
    s.solve_ms = r.timing.solve;
    s.warnings = r.warnings;
    return s;
  }

  bool stale(const Request& request) const {
    return request.revision != 0 && request.revision != current().id;
  }

  // Whether the newest request waiting for the worker has the setup of `request` (same_setup).
  bool newest_shares_setup(const Request& request) const {
    std::lock_guard lock(mutex);
    return pending && same_setup(pending->request, request);
  }

  void solve_preview(const Pending& p) {
    if (stale(p.request)) {
      publish_error(p.sequence, p.submitted,
                    "request " + std::to_string(p.sequence) + " was made for state " +
                        std::to_string(p.request.revision) + " but state " + std::to_string(current().id) +
                        " is committed now",
                    /*commit=*/false);
      return;
    }
    double setup_ms = 0.0;
    Active& a = setup_for(p.request, setup_ms);
    ConstraintTargets targets = a.deformer->push_pull_targets(p.request.d);
    // Warm start from the drag's previous iterate (previews only; commits start cold).
    if (a.last_iterate) {
      targets.initial_guess = *a.last_iterate;
      targets.rate_hint = a.last_rate;
      targets.rate_hint_settled = a.last_rate_settled;
    }
    const bool unhinted = !targets.rate_hint.has_value() && !a.hold_exhausted;
    bool held = false;  // went on past a newer request (below)
    const auto solve_start = Clock::now();
    auto progress = [&](const IterationReport& report) {
      // A cold request's coarse-to-fine start (iteration 0; regions of at least coarse_start_min_free free
      // vertices): a newer request does not stop its coarse solve (bounded: a tenth of the fine solve's time
      // or so), since the next request warm-starts from where this one stopped, and stopped there it would
      // start the whole drag from rest. Commands, the destructor and cancel() still stop it.
      if (report.probe_step > 0 && report.iteration == 0)
        return !command_waiting.load(std::memory_order_acquire) && !stopping.load(std::memory_order_acquire);
      if (report.probe_step > 0)  // the rate probe: nothing new to show, only whether to go on
        return !interrupt.load(std::memory_order_acquire) && !stopping.load(std::memory_order_acquire);
      Snapshot s = request_snapshot(Snapshot::Kind::Preview, p, a, report.V);
      s.iteration = report.iteration;
      s.error_estimate = report.error_estimate;
      s.energy = report.energy;
      s.setup_ms = setup_ms;
      s.solve_ms = ms_between(solve_start, Clock::now());
      a.last_iterate = report.V;
      a.last_rate = report.contraction_rate;
      a.last_rate_settled = report.rate_settled;
      publish(std::move(s));
      // A request without a rate hint (a drag's first) goes on past a newer request of the same setup until
      // it has a contraction rate to hand on (at most kUnhintedRequestIterations): the drag's next requests
      // warm-start with it as their (unsettled) hint and skip the rate probe (deformer.hpp:
      // ConstraintTargets::rate_hint). Stopped before (16 iterations give the first rate; 10K-vertex asan
      // requests at 30 a second got 14), no request of the drag ever had one, and the last, with the hand
      // held still, probed: 40 more local-global steps (service_bench on 2026-12-06, a quiet machine: 250-264
      // ms from the last submit to the converged shape on 10K vertices, 78-85 ms since). Commands still stop
      // it; a newer request of another setup (its own Deformer, which would not take the rate) too; and the
      // hold ends after ServiceOptions::hold_for_rate_ms of the solve (it says why).
      const bool interrupted = interrupt.load(std::memory_order_acquire);
      if (interrupted && unhinted && !report.contraction_rate &&
          report.iteration < kUnhintedRequestIterations &&
          ms_between(solve_start, Clock::now()) < options.hold_for_rate_ms &&
          newest_shares_setup(p.request)) {
        held = true;
        return !command_waiting.load(std::memory_order_acquire) && !stopping.load(std::memory_order_acquire);
      }
      return !interrupted && !stopping.load(std::memory_order_acquire);
    };
    const DeformResult r = a.deformer->solve(targets, progress);
    if (held && !r.contraction_rate && r.iterations >= kUnhintedRequestIterations) a.hold_exhausted = true;
    a.request = p.request;
    a.last_iterate = std::make_shared<const Eigen::MatrixXd>(r.V);
    a.last_rate = r.contraction_rate;
    a.last_rate_settled = r.rate_settled;
    Snapshot s = result_snapshot(p, a, r, Snapshot::Kind::Preview);
    s.setup_ms = setup_ms;
    publish(std::move(s));
  }

  void run_commit(const Pending& p, Clock::time_point issued) {
    if (stale(p.request)) {
      publish_error(p.sequence, issued,
                    "commit of request " + std::to_string(p.sequence) + ": it was made for state " +
                        std::to_string(p.request.revision) + " but state " + std::to_string(current().id) +
                        " is committed now",
                    /*commit=*/true);
      return;
    }
    double setup_ms = 0.0;
    Active& a = setup_for(p.request, setup_ms);
    // Cold: rest positions, identity rotations; a pure function of the request and the committed state.
    auto progress = [&](const IterationReport&) { return !stopping.load(std::memory_order_acquire); };
    const DeformResult r = a.deformer->solve(p.request.d, progress);
    if (r.cancelled) return;  // only when the service is being destroyed
    Snapshot s = result_snapshot(p, a, r, Snapshot::Kind::Committed);
    s.setup_ms = setup_ms;
    s.energy_trace = std::make_shared<const std::vector<double>>(r.energy_trace);
    s.initial_energy = r.initial_energy;
    if (a.parts) {
      s.attached = a.parts->parts();
      s.attach_reach = a.parts->reach();
    }
    s.latency_ms = ms_between(issued, Clock::now());
    auto next = std::make_shared<Mesh>();
    next->V = *s.positions;  // with the attached parts
    next->F = current().entry.state->F;
    State state;
    state.entry.hash = position_hash(next->V);
    state.entry.state = std::move(next);
    state.entry.request = p.request;
    state.entry.request->options.progress = nullptr;
    s.committed_request = std::make_shared<const Request>(*state.entry.request);

    {
      std::lock_guard lock(history_mutex);
      state.id = next_state_id++;
      states.resize(position + 1);  // a commit after undo drops the undone states
      states.push_back(std::move(state));
      position = states.size() - 1;
    }
    revision.store(current().id);
    active.reset();  // the setup belonged to the old state
    s.revision = current().id;
    s.rest = current().entry.state;
    s.positions = std::shared_ptr<const Eigen::MatrixXd>(s.rest, &s.rest->V);  // the new state itself
    publish(std::move(s));
  }

  void move_to(std::size_t index, Clock::time_point issued) {
    if (index != position) {
      {
        std::lock_guard lock(history_mutex);
        position = index;
      }
      revision.store(current().id);
      active.reset();
    }
    publish(state_snapshot(Snapshot::Kind::Rest, 0, issued));
  }

  void run_command(const Command& command) {
    switch (command.kind) {
      case CommandKind::Commit:
        run_commit(*command.request, command.issued);
        break;
      case CommandKind::Undo:
        move_to(position > 0 ? position - 1 : 0, command.issued);
        break;
      case CommandKind::Redo:
        move_to(position + 1 < states.size() ? position + 1 : position, command.issued);
        break;
      case CommandKind::Cancel:
        active.reset();
        publish(state_snapshot(Snapshot::Kind::Rest, 0, command.issued));
        break;
    }
  }

  void loop() {
    for (;;) {
      std::optional<Command> command;
      std::shared_ptr<const Pending> request;
      {
        std::unique_lock lock(mutex);
        busy = false;
        idle.notify_all();
        wake.wait(lock, [&] { return stop || !commands.empty() || pending != nullptr; });
        if (stop) return;
        busy = true;
        // Cleared while holding the lock: any work queued after this point sets it again.
        interrupt.store(false, std::memory_order_release);
        command_waiting.store(false, std::memory_order_release);
        if (!commands.empty()) {
          command = std::move(commands.front());
          commands.pop_front();
        } else {
          request = std::move(pending);
        }
      }
      const std::uint64_t sequence =
          command ? (command->request ? command->request->sequence : 0) : request->sequence;
      const Clock::time_point since = command ? command->issued : request->submitted;
      const bool commit = command && command->kind == CommandKind::Commit;
      try {
        if (command)
          run_command(*command);
        else
          solve_preview(*request);
      } catch (const std::exception& error) {
        active.reset();
        publish_error(sequence, since, error.what(), commit);
      } catch (...) {
        active.reset();
        publish_error(sequence, since, "unknown error in the deformation worker", commit);
      }
    }
  }

  // Queues a command; drops the request not yet taken (the command supersedes it). end_drag: commit() can no
  // longer commit the drag's requests.
  void post(Command command, bool end_drag = false) {
    std::shared_ptr<const Pending> dropped, ended;  // released outside the lock
    {
      std::lock_guard lock(mutex);
      if (end_drag) ended = std::move(last_submitted);
      dropped = queue_locked(std::move(command));
    }
    wake.notify_one();
  }
  // Queues a command with `mutex` held (one lock with whatever the caller read: a submit() or cancel() from
  // another thread cannot come in between); returns the request it dropped, to be released outside the lock.
  std::shared_ptr<const Pending> queue_locked(Command command) {
    std::shared_ptr<const Pending> dropped = std::move(pending);
    commands.push_back(std::move(command));
    command_waiting.store(true, std::memory_order_release);
    interrupt.store(true, std::memory_order_release);
    return dropped;
  }
};

Service::Service(std::shared_ptr<const Mesh> initial, ServiceOptions options)
    : impl_(std::make_unique<Impl>()) {
  if (!initial) throw std::invalid_argument("deformation service: the initial mesh is null");
  (void)validate_mesh(*initial);  // throws MeshValidationError naming the problem
  impl_->options = std::move(options);
  Impl::State state;
  state.id = 1;
  state.entry.state = std::move(initial);
  state.entry.hash = position_hash(state.entry.state->V);
  impl_->states.push_back(std::move(state));
  impl_->publish(impl_->state_snapshot(Snapshot::Kind::Rest, 0, Clock::now()));
  impl_->worker = std::thread([impl = impl_.get(), nice = impl_->options.worker_nice,
                               idle = impl_->options.worker_idle, cpus = impl_->options.worker_cpus] {
    place_worker_thread(nice, idle, cpus);
    impl->loop();
  });
}

Service::~Service() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stop = true;
    impl_->interrupt.store(true);
    impl_->stopping.store(true);
  }
  impl_->wake.notify_one();
  impl_->worker.join();
}

std::uint64_t Service::submit(Request request) {
  request.options.progress = nullptr;
  auto p = std::make_shared<Impl::Pending>(Impl::Pending{0, std::move(request), Clock::now()});
  std::shared_ptr<const Impl::Pending> superseded;  // released outside the lock
  std::uint64_t sequence = 0;
  {
    std::lock_guard lock(impl_->mutex);
    sequence = p->sequence = impl_->next_sequence++;  // numbered in the order the slot sees them
    impl_->last_submitted = p;
    superseded = std::exchange(impl_->pending, std::move(p));
    impl_->interrupt.store(true, std::memory_order_release);
  }
  impl_->wake.notify_one();
  return sequence;
}

std::uint64_t Service::commit() {
  std::shared_ptr<const Impl::Pending> dropped;  // released outside the lock
  std::uint64_t sequence = 0;
  {
    // What to commit and the command in one lock: a submit() between them would be dropped unsolved and
    // committed by the next commit(), a cancel() between them queued before the commit of what it cancelled.
    std::lock_guard lock(impl_->mutex);
    std::shared_ptr<const Impl::Pending> what = std::move(impl_->last_submitted);
    if (!what) return 0;
    sequence = what->sequence;
    dropped = impl_->queue_locked({Impl::CommandKind::Commit, std::move(what), Clock::now()});
  }
  impl_->wake.notify_one();
  return sequence;
}

void Service::undo() {
  impl_->post({Impl::CommandKind::Undo, nullptr, Clock::now()}, /*end_drag=*/true);
}

void Service::redo() {
  impl_->post({Impl::CommandKind::Redo, nullptr, Clock::now()}, /*end_drag=*/true);
}

void Service::cancel() {
  impl_->post({Impl::CommandKind::Cancel, nullptr, Clock::now()}, /*end_drag=*/true);
}

std::shared_ptr<const Snapshot> Service::latest() const {
  return impl_->newest.load();
}

std::shared_ptr<const Snapshot> Service::wait_idle() const {
  std::unique_lock lock(impl_->mutex);
  impl_->idle.wait(lock, [&] { return !impl_->busy && impl_->commands.empty() && !impl_->pending; });
  return latest();
}

bool Service::idle() const {
  std::lock_guard lock(impl_->mutex);
  return !impl_->busy && impl_->commands.empty() && !impl_->pending;
}

std::uint64_t Service::revision() const {
  return impl_->revision.load();
}

std::vector<HistoryEntry> Service::history() const {
  std::lock_guard lock(impl_->history_mutex);
  std::vector<HistoryEntry> out;
  out.reserve(impl_->states.size());
  for (const auto& s : impl_->states) out.push_back(s.entry);
  return out;
}

Service::Current Service::current() const {
  std::lock_guard lock(impl_->history_mutex);
  return {impl_->states[impl_->position].entry, impl_->position};
}

std::size_t Service::history_position() const {
  std::lock_guard lock(impl_->history_mutex);
  return impl_->position;
}

std::size_t Service::history_size() const {
  std::lock_guard lock(impl_->history_mutex);
  return impl_->states.size();
}

}  // namespace pushpull::deform
