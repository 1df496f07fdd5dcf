// pushpull::deform::Service: the asynchronous deformation service between the frame loop and the solver.
//
// The headset loop runs at 72-120 Hz and a solve takes tens to hundreds of milliseconds, so the loop never
// waits for the solver: it submits requests and draws the newest snapshot it finds.
//
//   Service service(std::make_shared<const Mesh>(car));
//   // press: p0 on the surface; every frame of the drag:
//   service.submit({.handle = SurfaceHandle{hit, 0.05}, .region = {.max_distance = 1.0}, .d = d});
//   (with ServiceOptions::on_publish, every snapshot is also handed to a callback on the worker)
//   auto s = service.latest();           // never waits for a solve; draw s->positions (may be a preview
//   iterate)
//   // release:
//   service.commit();                    // the last request, solved from the committed state, becomes it
//   service.undo(); service.redo();
//
// Model: one worker thread owns every Deformer. Requests are cheap values; the newest one supersedes the
// one being solved at its next iteration boundary (the solver's progress callback returns false), not
// after its solve; a cold request's coarse-to-fine start (DeformOptions::coarse_start_min_free) finishes its
// coarse solve first, so that the drag's next request starts from the coarse shape, and a request without a
// rate hint (a drag's first) goes on until it has a contraction rate (at most 24 iterations and
// ServiceOptions::hold_for_rate_ms) when the newer request has its setup, so that the drag's next requests
// start with that rate as their hint and skip the solver's rate probe (commands and the destructor still stop
// it at once). During a drag (same drag
// id, same handle, region and options, new d) the worker reuses the Deformer of the previous request
// (symbolic analysis; numeric factorization when the weights are unchanged: always for the isotropic methods,
// for asan while d keeps its line) and starts from the previous request's last iterate (a warm start:
// previews converge in a few iterations).
//
// Commands (commit, undo, redo, cancel) are queued in call order and run by the worker between solves; they
// too interrupt a running preview solve (not a commit's solve, nor the region and Deformer setup or a cold
// start's preparation, which finish first). A commit solves its request again from the committed state with a
// cold start (rest positions, identity rotations: DeformResult is then a pure function of the request and
// the committed state), so commits never depend on previews, timing or thread scheduling: the same request
// sequence gives bit-identical commits on the same machine (a replay depends on it).
//
// Snapshots: immutable (std::shared_ptr<const Snapshot>), numbered by a generation that increases by one
// with every publication. Positions are those of the whole mesh (#V by 3): the renderer uploads one vertex
// buffer for the whole model and a commit needs the whole state; a 50K-vertex copy costs ~0.1 ms and is made
// once per published iterate, on the worker (measured in service_bench).
//
// Thread-safety: every public member may be called from any thread. submit() and the command calls take a
// short internal lock that the worker only ever holds to move a request or a command (never while it
// computes) and notify the worker; latest() copies one shared_ptr under a spin flag that the worker holds
// only for a pointer swap (no mutex, never held during a solve; see src/snapshot_handoff.hpp). The
// destructor interrupts the running solve at its next iteration and joins the worker.
// Units: model units (metres for glTF). Frame: model space.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "pushpull/deform/attached_parts.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/surface_point.hpp"

namespace pushpull::deform {

// The handle grown along the surface from a point (a ray hit in the headset): see surface_point.hpp.
struct SurfaceHandle {
  SurfacePoint point;
  double radius = 0.0;  // model units, >= 0
};
// The handle as an explicit vertex list (rows of the mesh).
struct VertexHandle {
  std::vector<int> vertices;
};

struct RegionSpec {
  // Region grown along the surface from the handle up to this distance (build_roi); +inf = the handle's
  // whole component.
  double max_distance = std::numeric_limits<double>::infinity();
  std::vector<int> fixed;  // vertices the region never grows past (they stay at rest)
  // Separate parts near the region (lamps, plates, trims) follow the deformed surface (attached_parts.hpp).
  bool attach_parts = true;
  double attach_reach = 0.0;  // <= 0: automatic (AttachOptions)
};

struct Request {
  // The committed state this request applies to (Service::revision() when it was made); 0 = whatever is
  // committed when the worker takes it. A request made for another state is refused with an error snapshot.
  std::uint64_t revision = 0;
  // Requests of one press-drag-release share a drag id (and handle, region and options); a new drag id starts
  // a new solve setup. 0 is a valid id.
  std::uint64_t drag = 0;
  std::variant<SurfaceHandle, VertexHandle> handle;
  RegionSpec region;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();  // displacement of the handle, model units, model space
  DeformOptions options;  // method and parameters; options.progress and options.threads are the service's
};

// What the frame loop draws and the HUD shows. Immutable once published.
struct Snapshot {
  enum class Kind {
    Rest,       // the committed state (start, after a commit/undo/redo/cancel): positions == rest
    Preview,    // an iterate or the converged result of a drag request
    Committed,  // the result of commit(): positions are the new committed state
    Error,      // a request or command failed: `error` says why; positions are the committed state
  };
  std::uint64_t generation = 0;  // +1 for every snapshot published
  Kind kind = Kind::Rest;
  std::uint64_t request = 0;   // sequence number submit() returned for the request this snapshot belongs to
  std::uint64_t revision = 0;  // committed state the positions were computed from (Rest: this state)
  std::shared_ptr<const Eigen::MatrixXd> positions;  // #V by 3, whole mesh, never null
  std::shared_ptr<const Mesh> rest;                  // the committed state (positions of revision)
  std::shared_ptr<const RegionOfInterest> region;    // roles of the request's region (null for Rest/Error)
  std::size_t attached_parts = 0;                    // parts following the surface in these positions
  Method method = Method::Asan;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  int iteration = 0;
  bool converged = false;  // the solver met its stopping rule for this request
  bool final = false;      // the last snapshot of this request (converged, stopped, superseded or failed)
  std::optional<double> error_estimate;  // relative to |d|, when the solver gives one
  // Final snapshots of a solve only (empty, 0 otherwise): the rate behind error_estimate, the rate handed to
  // a warm start from these positions, and the solver's rate probe (DeformResult::estimate_rate,
  // contraction_rate, probe_rate, probe_evaluations).
  std::optional<double> estimate_rate, contraction_rate, probe_rate;
  int probe_evaluations = 0;
  // Final snapshots only: how the cold solve started and its per-iteration time (DeformResult::smooth_start,
  // coarse_start, coarse_evaluations, timing.per_iteration: the starts' time left out).
  bool smooth_start = false, coarse_start = false;
  int coarse_evaluations = 0;
  double per_iteration_ms = 0.0;
  double energy = 0.0;
  double max_displacement = 0.0;  // largest vertex displacement from rest (model units)
  double factorize_ms = 0.0;      // this request's weights + numeric factorization (0 when reused)
  double setup_ms = 0.0;          // this request's region + Deformer construction (0 when reused)
  double solve_ms = 0.0;          // iterations so far
  double latency_ms = 0.0;        // from submit() (or the command call) to this publication
  std::string error;              // Kind::Error: what went wrong
  // Kind::Error: commit() failed (the request is not committed; the state stays). False for a preview's
  // failure, which says nothing about the commit of the same request (solved again, cold).
  bool failed_commit = false;
  std::vector<std::string> warnings;
  // Kind::Committed only (empty otherwise): the commit's solve, its energy before the first iteration and
  // after each, and the separate parts bound to the surface (attached_parts.hpp) with the reach that chose
  // them.
  std::shared_ptr<const std::vector<double>> energy_trace;
  double initial_energy = 0.0;
  std::vector<AttachedPart> attached;
  double attach_reach = 0.0;
  // Kind::Committed only (null otherwise): the request the commit solved (its handle, region, d and options,
  // options.progress empty), so that a record of the commit can say how its region was asked for.
  std::shared_ptr<const Request> committed_request;
};

// One entry of the history that commit/undo/redo walk.
struct HistoryEntry {
  std::shared_ptr<const Mesh> state;  // the committed positions and the faces (a copy of the initial mesh's)
  std::optional<Request> request;     // the request whose commit produced it (none for the initial state)
  std::uint64_t hash = 0;             // position_hash(state->V)
};

// FNV-1a over the bytes of the positions (row-major doubles): equal hashes = bit-identical positions (up to
// collisions). Used to check commits in replays.
[[nodiscard]] std::uint64_t position_hash(const Eigen::MatrixXd& V);

struct ServiceOptions {
  // Called on the worker with every snapshot right after its publication (tests, recording; the first Rest
  // snapshot's on the thread constructing the Service, inside the constructor). Must be quick; it may call
  // submit(), commit(), undo(), redo() and cancel() (they never wait), nothing that blocks. It should not
  // throw: an exception from it is written to stderr and dropped (the snapshot stays published, the request
  // unaffected).
  std::function<void(const std::shared_ptr<const Snapshot>&)> on_publish;
  // Scheduling niceness of the worker thread, 0 (as the caller) to 19 (runs only when nothing else wants the
  // core). A frame loop sharing the machine's cores with the solver gives it > 0 so frames come first;
  // results do not depend on it, only how soon they arrive. Linux (setpriority on the thread); ignored
  // elsewhere.
  int worker_nice = 0;
  // The idle scheduling class (Linux SCHED_IDLE) for the worker (which solves on its own thread alone,
  // DeformOptions::threads = 1): it runs only on CPU time no normal thread wants, and a frame loop's thread
  // that wakes takes the core at once (with a niceness it waits for the solver's time slice: the frame-time
  // spikes of scripts/bench-review). Under a machine loaded by other work, previews then arrive late. Ignored
  // elsewhere.
  bool worker_idle = false;
  // CPUs the worker runs on (cpu_affinity.hpp; empty: wherever the caller's threads may); it solves on one
  // thread, so a second CPU serves only other work given the same set (the review's snapshot conversion). A
  // frame loop gives the solver CPUs of its own so solves never take the frame loop's cores. A set the
  // system refuses leaves the worker where it was (results do not depend on it).
  std::vector<int> worker_cpus;
  // How long (milliseconds since the request's solve began, its refactorization included) a preview request
  // without a rate hint, a drag's first, may go on past a newer request of its setup to reach a contraction
  // rate for the drag's next requests (then they skip the solver's rate probe). The hold delays the drag's
  // next preview by as much, and it only pays where the drag's last request would stop within the probe's
  // window: on 10K vertices (service_bench) the first rate came ~40 ms into the solve and the wait for the
  // converged shape with the hand held still fell from ~255 to ~80 ms; on 50K, where the rate comes after
  // 300-500 ms and the last request runs past the window anyway, holding lengthened that wait by 15-45%.
  // 0: never held; tests give a large value for timing-independent results.
  double hold_for_rate_ms = 50.0;
};

class Service {
 public:
  // Starts the worker and publishes the Rest snapshot of `initial` (revision 1). Throws
  // std::invalid_argument when the mesh is null or fails validation (MeshValidationError).
  explicit Service(std::shared_ptr<const Mesh> initial, ServiceOptions options = {});
  ~Service();  // interrupts the running solve at its next iteration, joins the worker
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  // Queues a request; supersedes any request not yet finished. Never waits for the solver. Returns the
  // request's sequence number (1, 2, ...), found again in its snapshots.
  std::uint64_t submit(Request request);
  // Commits the newest submitted request (solved again from the committed state, cold). No-op when nothing
  // was submitted since the last commit or cancel. Returns the sequence number of the committed request or 0.
  std::uint64_t commit();
  void undo();    // back to the previous committed state (no-op at the start of the history)
  void redo();    // forward again (no-op at its end); a commit after undo drops the undone states
  void cancel();  // stops a running preview solve, drops pending requests, shows the committed state again

  // The newest snapshot (never null). Never waits for a solve: one shared_ptr copy under a spin flag.
  [[nodiscard]] std::shared_ptr<const Snapshot> latest() const;
  // Blocks until the worker has nothing left to do (tests, replay). Returns the newest snapshot.
  std::shared_ptr<const Snapshot> wait_idle() const;
  // Whether the worker has nothing left to do now (wait_idle() would return at once). Never waits for a solve
  // (a short lock the worker holds only between steps); the answer may be stale as soon as it is returned
  // if other threads submit.
  [[nodiscard]] bool idle() const;

  // The committed revision (1 = the initial state; every commit, undo and redo moves it) and the history.
  // revision() reflects the commands the worker has run.
  [[nodiscard]] std::uint64_t revision() const;
  [[nodiscard]] std::vector<HistoryEntry> history() const;  // a copy, oldest first
  [[nodiscard]] std::size_t history_position() const;       // index of the current state in history()
  // The current state and its index, read together (history() and history_position() called one after the
  // other may straddle a commit, undo or redo).
  struct Current {
    HistoryEntry entry;
    std::size_t position = 0;
  };
  [[nodiscard]] Current current() const;
  [[nodiscard]] std::size_t history_size() const;           // history().size(), without the copy

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::deform
