// Deformer: construction (validation, local numbering, clusters, symbolic analysis) and the public API.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

#include "cotangent.hpp"
#include "deformer_impl.hpp"
#include "mesh_graph.hpp"
#include "solver_errors.hpp"

namespace pushpull::deform {
namespace {

void check_options(const DeformOptions& o) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("deform options: " + what); };
  if (!(o.mu > 1.0) || !std::isfinite(o.mu))
    fail("mu must be a finite value > 1, got " + std::to_string(o.mu));
  if (o.asan_base != Method::ArapSR && o.asan_base != Method::ArapM) {
    fail("asan_base must be arap-sr or arap-m, got " + std::string(method_name(o.asan_base)));
  }
  if (o.max_iterations < 0) fail("max_iterations must be >= 0");
  if (!(o.tolerance >= 0.0)) fail("tolerance must be >= 0");
  if (!(o.energy_tolerance >= 0.0)) fail("energy_tolerance must be >= 0");
  if (o.anderson_window < 0) fail("anderson_window must be >= 0");
  if (o.smooth_start_min_free < -1) fail("smooth_start_min_free must be >= -1 (-1: never)");
  if (o.coarse_start_min_free < -1) fail("coarse_start_min_free must be >= -1 (-1: never)");
  if (o.threads < 0) fail("threads must be 0 (automatic) or >= 1, got " + std::to_string(o.threads));
  if (o.arap_n_rings < 1) fail("arap_n_rings must be >= 1, got " + std::to_string(o.arap_n_rings));
  if (!(o.sr_arap_alpha >= 0.0) || !std::isfinite(o.sr_arap_alpha))
    fail("sr_arap_alpha must be finite and >= 0");
  if (!(o.arap_h_lambda >= 0.0) || !std::isfinite(o.arap_h_lambda))
    fail("arap_h_lambda must be finite and >= 0");
  if (o.stretch_direction &&
      (!o.stretch_direction->allFinite() || o.stretch_direction->stableNorm() == 0.0)) {
    fail("stretch_direction must be finite and non-zero");
  }
}

detail::ModelSpec model_spec(const DeformOptions& o) {
  detail::ModelSpec spec;
  switch (o.method) {
    case Method::ArapS:
      spec.structure = Method::ArapS;
      break;
    case Method::ArapSR:
      spec.structure = Method::ArapSR;
      break;
    case Method::ArapM:
      spec.structure = Method::ArapM;
      break;
    case Method::ArapN:
      spec.structure = Method::ArapN;
      spec.n_rings = o.arap_n_rings;
      break;
    case Method::SrArap:
      spec.structure = Method::ArapSR;
      spec.smooth_alpha = o.sr_arap_alpha;
      break;
    case Method::ArapH:
      spec.structure = Method::ArapM;
      spec.bending_lambda = o.arap_h_lambda;
      spec.bending_own_rotation = true;
      break;
    case Method::ArapSrH:
      spec.structure = Method::ArapSR;
      spec.bending_lambda = o.arap_h_lambda;
      break;
    case Method::Asan:
      spec.structure = o.asan_base;
      break;
  }
  return spec;
}

}  // namespace

void Deformer::Impl::group_unheld_vertices(const detail::VertexGraph& graph,
                                           const std::vector<int>& global_to_local) {
  // Free vertices reached from a fixed vertex through free vertices are held; the others (all reached from a
  // handle vertex, the pinned aside) form the groups, each a connected set of unheld free vertices.
  auto local = [&](int v) { return global_to_local[static_cast<std::size_t>(v)]; };
  auto is_free = [&](int v) { return local(v) >= 0 && local(v) < n_free; };
  std::vector<char> seen(static_cast<std::size_t>(n_free), 0);
  std::vector<int> stack;
  for (int v : roi.fixed) stack.push_back(v);
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (const int* w = graph.begin(v); w != graph.end(v); ++w) {
      if (is_free(*w) && !seen[static_cast<std::size_t>(local(*w))]) {
        seen[static_cast<std::size_t>(local(*w))] = 1;
        stack.push_back(*w);
      }
    }
  }
  std::vector<int> handle_mark(static_cast<std::size_t>(n_handle), -1);  // last group that listed it
  for (int i = 0; i < n_free; ++i) {
    if (seen[static_cast<std::size_t>(i)]) continue;
    const int group = static_cast<int>(unheld_free_start.size()) - 1;
    seen[static_cast<std::size_t>(i)] = 1;
    stack.push_back(local_to_global[static_cast<std::size_t>(i)]);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      unheld_free.push_back(local(v));
      for (const int* w = graph.begin(v); w != graph.end(v); ++w) {
        const int lw = local(*w);
        if (lw < 0) continue;
        if (lw < n_free) {
          if (!seen[static_cast<std::size_t>(lw)]) {
            seen[static_cast<std::size_t>(lw)] = 1;
            stack.push_back(*w);
          }
        } else if (lw < n_free + n_handle && handle_mark[static_cast<std::size_t>(lw - n_free)] != group) {
          handle_mark[static_cast<std::size_t>(lw - n_free)] = group;
          unheld_handle.push_back(lw - n_free);
        }
      }
    }
    unheld_free_start.push_back(static_cast<int>(unheld_free.size()));
    unheld_handle_start.push_back(static_cast<int>(unheld_handle.size()));
  }
  // The parts of the region the free vertices lie in (every Omega vertex reachable, handle and fixed ones
  // included), when all of them are unheld: whole parts unless one holds a fixed vertex.
  if (n_free == 0 || unheld_free.size() != static_cast<std::size_t>(n_free)) return;
  std::vector<char> reached(local_to_global.size(), 0);
  for (int i = 0; i < n_free; ++i) {
    if (reached[static_cast<std::size_t>(i)]) continue;
    reached[static_cast<std::size_t>(i)] = 1;
    stack.push_back(local_to_global[static_cast<std::size_t>(i)]);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      const int lv = local(v);
      if (lv >= n_free + n_handle && lv < n_free + n_handle + n_fixed) {  // held after all: no whole parts
        whole_part_handle.clear();
        whole_part_start.assign(1, 0);
        return;
      }
      if (lv >= n_free && lv < n_free + n_handle) whole_part_handle.push_back(lv - n_free);
      for (const int* w = graph.begin(v); w != graph.end(v); ++w) {
        const int lw = local(*w);
        if (lw < 0 || reached[static_cast<std::size_t>(lw)]) continue;
        reached[static_cast<std::size_t>(lw)] = 1;
        stack.push_back(*w);
      }
    }
    whole_part_start.push_back(static_cast<int>(whole_part_handle.size()));
  }
  free_in_whole_parts = true;
}

std::optional<double> Deformer::Impl::start_unheld_groups(Eigen::Matrix3Xd& X) const {
  // The mean move of the handle vertices in `columns` (of the constrained block).
  auto mean_move = [&](const int* begin, const int* end) {
    Eigen::Vector3d move = Eigen::Vector3d::Zero();
    for (const int* k = begin; k != end; ++k) move += X.col(n_free + *k) - P.col(n_free + *k);
    return begin == end ? move : Eigen::Vector3d(move / static_cast<double>(end - begin));
  };
  for (std::size_t g = 0; g + 1 < unheld_free_start.size(); ++g) {
    const Eigen::Vector3d move = mean_move(unheld_handle.data() + unheld_handle_start[g],
                                           unheld_handle.data() + unheld_handle_start[g + 1]);
    for (int k = unheld_free_start[g]; k < unheld_free_start[g + 1]; ++k) {
      const int i = unheld_free[static_cast<std::size_t>(k)];
      X.col(i) = P.col(i) + move;
    }
  }
  if (!free_in_whole_parts || options.method == Method::ArapS) return std::nullopt;
  double gap = 0.0;
  for (std::size_t p = 0; p + 1 < whole_part_start.size(); ++p) {
    const int* begin = whole_part_handle.data() + whole_part_start[p];
    const int* end = whole_part_handle.data() + whole_part_start[p + 1];
    const Eigen::Vector3d move = mean_move(begin, end);
    for (const int* k = begin; k != end; ++k) {
      const double departure = (X.col(n_free + *k) - P.col(n_free + *k) - move).norm();
      if (departure > 1e-9 * move.norm()) return std::nullopt;
      gap = std::max(gap, departure);
    }
  }
  return gap;
}

void Deformer::Impl::setup() {
  const Mesh& m = *mesh;
  const int nv = static_cast<int>(m.V.rows());
  if (static_cast<int>(roi.role.size()) != nv) {
    throw std::invalid_argument("deformer: region of interest has " + std::to_string(roi.role.size()) +
                                " roles for a mesh of " + std::to_string(nv) + " vertices");
  }
  if (roi.handle.empty())
    throw std::invalid_argument("deformer: the region of interest has no handle vertex");
  // The lists must agree with the roles (a hand-made RegionOfInterest may not).
  for (const auto& [list, role, name] : {std::tuple{&roi.handle, VertexRole::Handle, "handle"},
                                         std::tuple{&roi.fixed, VertexRole::Fixed, "fixed"},
                                         std::tuple{&roi.free, VertexRole::Free, "free"}}) {
    for (int v : *list) {
      if (v < 0 || v >= nv || roi.role[static_cast<std::size_t>(v)] != role) {
        throw std::invalid_argument(std::string("deformer: region of interest lists vertex ") +
                                    std::to_string(v) + " as " + name +
                                    " but its role disagrees (or it is out of range)");
      }
    }
  }
  if (roi.size() !=
      static_cast<std::size_t>(std::count_if(roi.role.begin(), roi.role.end(),
                                             [](VertexRole r) { return r != VertexRole::Outside; }))) {
    throw std::invalid_argument("deformer: region of interest role counts disagree with its vertex lists");
  }
  check_options(options);
  if (options.validate) {
    validation = validate_mesh(m);
    setup_warnings = validation.warnings;
  }
  setup_warnings.insert(setup_warnings.end(), roi.warnings.begin(), roi.warnings.end());

  // Omega's faces: all three vertices in Omega, no repeated index, non-zero area (degenerate faces carry no
  // stiffness; leaving them out lets a vertex held only by them be pinned instead of making Q singular).
  auto in_omega = [&](int v) { return roi.role[static_cast<std::size_t>(v)] != VertexRole::Outside; };
  std::vector<int> omega_faces;
  for (int f = 0; f < m.F.rows(); ++f) {
    const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
    if (is_degenerate_triangle(m.V, a, b, c)) continue;
    if (in_omega(a) && in_omega(b) && in_omega(c)) omega_faces.push_back(f);
  }
  // Free vertices not connected to any constrained vertex through Omega's faces are pinned at rest.
  const detail::VertexGraph graph = detail::build_vertex_graph(nv, m.F, omega_faces);
  std::vector<char> reached(static_cast<std::size_t>(nv), 0);
  std::vector<int> stack;
  for (const auto* list : {&roi.handle, &roi.fixed}) {
    for (int v : *list) reached[static_cast<std::size_t>(v)] = 1, stack.push_back(v);
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (const int* n = graph.begin(v); n != graph.end(v); ++n) {
      if (!reached[static_cast<std::size_t>(*n)] &&
          roi.role[static_cast<std::size_t>(*n)] == VertexRole::Free) {
        reached[static_cast<std::size_t>(*n)] = 1;
        stack.push_back(*n);
      }
    }
  }
  std::vector<int> pinned;
  for (int v : roi.free) {
    if (reached[static_cast<std::size_t>(v)])
      local_to_global.push_back(v);
    else
      pinned.push_back(v);
  }
  n_free = static_cast<int>(local_to_global.size());
  n_handle = static_cast<int>(roi.handle.size());
  n_fixed = static_cast<int>(roi.fixed.size());
  n_pinned = static_cast<int>(pinned.size());
  local_to_global.insert(local_to_global.end(), roi.handle.begin(), roi.handle.end());
  local_to_global.insert(local_to_global.end(), roi.fixed.begin(), roi.fixed.end());
  local_to_global.insert(local_to_global.end(), pinned.begin(), pinned.end());
  if (!pinned.empty()) {
    setup_warnings.push_back(
        "deformer: " + std::to_string(pinned.size()) + " free vertices (e.g. vertex " +
        std::to_string(pinned.front()) +
        ") belong to a part of the region with no handle or fixed vertex; they stay at rest");
  }

  const int n = static_cast<int>(local_to_global.size());
  std::vector<int> global_to_local(static_cast<std::size_t>(nv), -1);
  P.resize(3, n);
  for (int i = 0; i < n; ++i) {
    global_to_local[static_cast<std::size_t>(local_to_global[static_cast<std::size_t>(i)])] = i;
    P.col(i) = m.V.row(local_to_global[static_cast<std::size_t>(i)]).transpose();
  }
  // The origin: the centroid, rounded to a multiple of a power of two near a sixteenth of the region's
  // extent, so that a model moved by a multiple of that step (e.g. 1024 m) gives the same centred positions,
  // hence the same solve, bit for bit (subtractions of nearby multiples of a power of two are exact).
  if (n > 0) {
    const double extent = (P.rowwise().maxCoeff() - P.rowwise().minCoeff()).maxCoeff();
    const Eigen::Vector3d centroid = P.rowwise().mean();
    if (extent > 0.0 && std::isfinite(extent) && centroid.allFinite()) {
      const double step = std::ldexp(1.0, std::ilogb(extent) - 4);
      origin = (centroid / step).array().round().matrix() * step;
    }
  }
  P.colwise() -= origin;
  group_unheld_vertices(graph, global_to_local);
  faces.resize(static_cast<Eigen::Index>(omega_faces.size()), 3);
  for (std::size_t k = 0; k < omega_faces.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      faces(static_cast<Eigen::Index>(k), c) =
          global_to_local[static_cast<std::size_t>(m.F(omega_faces[k], c))];
    }
  }
  mollify_eps = detail::mollification_margin(P, faces);
  const detail::HalfCotangents rest_weights = detail::half_cotangents(P, faces, mollify_eps);
  rest_half_cot = rest_weights.values;
  if (rest_weights.added_length > 0.0) {
    char added[32];
    std::snprintf(added, sizeof added, "%.3g", rest_weights.added_length);
    setup_warnings.push_back(std::string("deformer: the region has sliver triangles; its weights use edge "
                                         "lengths lengthened by ") +
                             added + " model units (intrinsic mollification) to stay positive definite");
  }

  // arap-h, arap-sr-h: vertices whose every mesh face is in Omega and whose every edge has two faces (mean
  // curvature is defined there).
  std::vector<char> bending_vertex(static_cast<std::size_t>(n), 0);
  if (options.method == Method::ArapH || options.method == Method::ArapSrH) {
    std::vector<int> mesh_faces(static_cast<std::size_t>(nv), 0), omega_count(static_cast<std::size_t>(n), 0);
    for (int f = 0; f < m.F.rows(); ++f) {
      for (int c = 0; c < 3; ++c) ++mesh_faces[static_cast<std::size_t>(m.F(f, c))];
    }
    std::vector<std::tuple<int, int>> edges;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      for (int c = 0; c < 3; ++c) {
        ++omega_count[static_cast<std::size_t>(faces(f, c))];
        const int i = faces(f, c), j = faces(f, (c + 1) % 3);
        edges.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
    for (int i = 0; i < n; ++i) {
      bending_vertex[static_cast<std::size_t>(i)] =
          omega_count[static_cast<std::size_t>(i)] > 0 &&
          omega_count[static_cast<std::size_t>(i)] ==
              mesh_faces[static_cast<std::size_t>(local_to_global[static_cast<std::size_t>(i)])];
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t s = 0; s < edges.size();) {
      std::size_t e = s;
      while (e < edges.size() && edges[e] == edges[s]) ++e;
      if (e - s != 2) {
        bending_vertex[static_cast<std::size_t>(std::get<0>(edges[s]))] = 0;
        bending_vertex[static_cast<std::size_t>(std::get<1>(edges[s]))] = 0;
      }
      s = e;
    }
  }

  model =
      detail::build_energy_model(P, faces, model_spec(options), rest_half_cot, rest_half_cot, bending_vertex);
  system.analyze(model.Q, n_free);
  plan_local_split();
}

double Deformer::Impl::prepare_weights(const Eigen::Vector3d& push_direction,
                                       std::vector<std::string>& warnings) {
  const auto start = std::chrono::steady_clock::now();
  if (options.method == Method::Asan) {
    const Eigen::Vector3d d_o = options.stretch_direction.value_or(push_direction);
    std::optional<Eigen::Vector3d> unit;
    // A direction given as 1e300 1e300 0 or 1e-200 0 0 (whose plain norm overflows or underflows) is a
    // direction all the same: scaled by its stable norm first (other directions keep the plain path's bits).
    const double length = d_o.norm(), stable = d_o.stableNorm();
    if (length > 0.0 && std::isfinite(length))
      unit = d_o.normalized();
    else if (stable > 0.0 && std::isfinite(stable))
      unit = (d_o / stable).normalized();
    else
      warnings.push_back("asan: zero push/pull direction, the unstretched (arap) weights are used");
    // tau depends on d_o d_o^T only: opposite directions share weights. Bit-equal directions only, so that
    // the weights of a solve never depend on the directions of earlier solves (deform::Service commits and
    // replays rely on it).
    const bool same = unit.has_value() == weight_direction.has_value() &&
                      (!unit || *unit == *weight_direction || *unit == -*weight_direction);
    if (!same || !factored) {
      // The stretched copy is mollified with the rest region's margin (see cotangent.hpp for why).
      if (unit) {
        const Eigen::Matrix3Xd stretched = detail::stretch_along(P, *unit, options.mu);
        model.set_weights(detail::half_cotangents(stretched, faces, mollify_eps).values);
      } else {
        model.set_weights(rest_half_cot);
      }
      weight_direction = unit;
      factored = false;
    }
  }
  if (!factored) {
    try {
      system.factorize(model.Q);
    } catch (const detail::FactorizationError& e) {
      throw std::runtime_error(detail::factorization_failure_message(
          options.method, {static_cast<int>(P.cols()), n_free, n_handle, n_fixed}, e.what(), options.mu));
    }
    factored = true;
    ++factorizations;
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Eigen::MatrixXd Deformer::Impl::to_full(const Eigen::Matrix3Xd& X) const {
  Eigen::MatrixXd V = mesh->V;
  for (int i = 0; i < n_free; ++i)
    V.row(local_to_global[static_cast<std::size_t>(i)]) = (X.col(i) + origin).transpose();
  for (Eigen::Index k = 0; k < constrained_model.cols(); ++k)
    V.row(local_to_global[static_cast<std::size_t>(n_free + k)]) = constrained_model.col(k).transpose();
  return V;
}

Deformer::Deformer(std::shared_ptr<const Mesh> rest, RegionOfInterest roi, const DeformOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const auto start = std::chrono::steady_clock::now();
  if (!rest) throw std::invalid_argument("deformer: the rest mesh is null");
  impl_->mesh = std::move(rest);
  impl_->roi = std::move(roi);
  impl_->options = options;
  impl_->setup();
  impl_->precompute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Deformer::~Deformer() = default;
Deformer::Deformer(Deformer&&) noexcept = default;
Deformer& Deformer::operator=(Deformer&&) noexcept = default;

ConstraintTargets Deformer::push_pull_targets(const Eigen::Vector3d& d) const {
  if (!d.allFinite()) throw std::invalid_argument("deformer: the displacement d is not finite");
  ConstraintTargets targets;
  targets.handle_positions.resize(impl_->n_handle, 3);
  for (int k = 0; k < impl_->n_handle; ++k) {
    targets.handle_positions.row(k) =
        impl_->mesh->V.row(impl_->roi.handle[static_cast<std::size_t>(k)]) + d.transpose();
  }
  targets.push_direction = d;
  return targets;
}

const std::shared_ptr<const Mesh>& Deformer::rest_mesh() const {
  return impl_->mesh;
}

DeformResult Deformer::solve(const Eigen::Vector3d& d, const ProgressCallback& progress) {
  return solve(push_pull_targets(d), progress);
}

DeformResult Deformer::solve(const ConstraintTargets& targets, const ProgressCallback& progress) {
  Impl& s = *impl_;
  auto shape = [](const Eigen::MatrixXd& M) {
    return std::to_string(M.rows()) + " by " + std::to_string(M.cols());
  };
  if (targets.handle_positions.rows() != s.n_handle || targets.handle_positions.cols() != 3) {
    throw std::invalid_argument("deformer: handle_positions must be " + std::to_string(s.n_handle) +
                                " by 3 (one row per handle vertex), got " + shape(targets.handle_positions));
  }
  if (targets.fixed_positions.size() != 0 &&
      (targets.fixed_positions.rows() != s.n_fixed || targets.fixed_positions.cols() != 3)) {
    throw std::invalid_argument("deformer: fixed_positions must be empty or " + std::to_string(s.n_fixed) +
                                " by 3, got " + shape(targets.fixed_positions));
  }
  if (targets.initial_guess.size() != 0 &&
      (targets.initial_guess.rows() != s.mesh->V.rows() || targets.initial_guess.cols() != 3)) {
    throw std::invalid_argument("deformer: initial_guess must be empty or #V by 3, got " +
                                shape(targets.initial_guess));
  }
  if (!targets.handle_positions.allFinite() || !targets.fixed_positions.allFinite() ||
      !targets.initial_guess.allFinite() ||
      (targets.push_direction && !targets.push_direction->allFinite())) {
    throw std::invalid_argument("deformer: a target position or direction is not finite");
  }
  if (targets.rate_hint && !(*targets.rate_hint >= 0.0 && *targets.rate_hint < 1.0)) {
    throw std::invalid_argument("deformer: rate_hint must be in [0, 1), got " +
                                std::to_string(*targets.rate_hint));
  }
  const int nc = s.n_handle + s.n_fixed + s.n_pinned;
  // Model coordinates, then relative to the solver's origin.
  s.constrained_model.resize(3, nc);
  for (int k = 0; k < nc; ++k)
    s.constrained_model.col(k) =
        s.mesh->V.row(s.local_to_global[static_cast<std::size_t>(s.n_free + k)]).transpose();
  // d when the caller gives no direction: the handle's mean move from rest.
  const Eigen::Vector3d mean_move =
      s.n_handle > 0
          ? Eigen::Vector3d((targets.handle_positions.transpose() - s.constrained_model.leftCols(s.n_handle))
                                .rowwise()
                                .mean())
          : Eigen::Vector3d::Zero();
  s.constrained_model.leftCols(s.n_handle) = targets.handle_positions.transpose();
  if (targets.fixed_positions.size() != 0)
    s.constrained_model.middleCols(s.n_handle, s.n_fixed) = targets.fixed_positions.transpose();
  Eigen::Matrix3Xd X_c = s.constrained_model.colwise() - s.origin;
  const Eigen::Vector3d push = targets.push_direction.value_or(mean_move);
  DeformResult result = s.run(X_c, push, targets.initial_guess, targets.rate_hint, targets.rate_hint_settled,
                              progress ? progress : s.options.progress);
  // arap-s is the one method whose energy is not PSD (negative spoke weights): a negative energy proves the
  // negative weights won, and the shape means nothing (Le Vaou et al. 2020, Fig. 3). Say so, not return it.
  if (s.options.method == Method::ArapS && !result.cancelled && !result.energy_trace.empty() &&
      result.energy_trace.back() < -1e-9 * std::max(result.initial_energy, 0.0)) {
    throw std::runtime_error(detail::negative_energy_message(
        Method::ArapS, {static_cast<int>(s.P.cols()), s.n_free, s.n_handle, s.n_fixed},
        result.energy_trace.back(), result.initial_energy));
  }
  return result;
}

const RegionOfInterest& Deformer::roi() const {
  return impl_->roi;
}
const DeformOptions& Deformer::options() const {
  return impl_->options;
}
const ValidationReport& Deformer::validation() const {
  return impl_->validation;
}

double Deformer::energy(const Eigen::MatrixXd& V) const {
  const Impl& s = *impl_;
  if (V.rows() != s.mesh->V.rows() || V.cols() != 3)
    throw std::invalid_argument("deformer: energy needs #V by 3 positions");
  Eigen::Matrix3Xd X(3, s.P.cols());
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    X.col(i) = V.row(s.local_to_global[static_cast<std::size_t>(i)]).transpose() - s.origin;
  std::vector<Eigen::Matrix3d> R(static_cast<std::size_t>(s.model.cluster_count),
                                 Eigen::Matrix3d::Identity());
  std::vector<Eigen::Quaterniond> q(R.size(), Eigen::Quaterniond::Identity());
  return s.local_step(X, R, q, /*R_valid=*/false, /*sweeps=*/20);
}

std::string_view stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::ErrorTolerance:
      return "error-tolerance";
    case StopReason::EnergyTolerance:
      return "energy-tolerance";
    case StopReason::MaxIterations:
      return "max-iterations";
    case StopReason::Cancelled:
      return "cancelled";
  }
  return "unknown";
}

DeformOptions paper_iterations(DeformOptions base) {
  base.max_iterations = 50;
  base.anderson_window = 0;
  base.tolerance = 0.0;
  base.energy_tolerance = 0.0;
  base.smooth_start_min_free = -1;
  base.coarse_start_min_free = -1;
  return base;
}

DeformResult deform(const Mesh& mesh, const RegionOfInterest& roi, const Eigen::Vector3d& d,
                    const DeformOptions& options) {
  Deformer deformer(std::make_shared<const Mesh>(mesh), roi, options);
  return deformer.solve(d);
}

}  // namespace pushpull::deform
