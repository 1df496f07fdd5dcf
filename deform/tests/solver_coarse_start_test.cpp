// The coarse-to-fine start of asan cold solves (deform/src/region_coarsening.hpp, coarse_start.hpp,
// DeformOptions::coarse_start_min_free): the coarse tessellation keeps every constrained vertex, stays a
// manifold disk with no flipped triangle and maps every vertex to a kept one; strips of border vertices do
// not coarsen. A solve started coarse-to-fine ends at the minimiser (checked against a reference solved to
// 1e-9 |d|) in fewer iterations than from rest, with an honest estimate; it can be cancelled during its
// coarse solve; warm starts, small regions under the default threshold, other methods and the paper's setting
// do not use it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "../src/region_coarsening.hpp"
#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

// A region in the solver's local numbering: free vertices first, then the handle, then the fixed ones.
struct LocalRegion {
  Eigen::Matrix3Xd P;
  Eigen::MatrixX3i faces;
  int n_free = 0;
};

LocalRegion local_region(const Mesh& mesh, const RegionOfInterest& roi) {
  std::vector<int> local(static_cast<std::size_t>(mesh.V.rows()), -1);
  std::vector<int> order;
  for (const std::vector<int>* group : {&roi.free, &roi.handle, &roi.fixed})
    for (int v : *group)
      local[static_cast<std::size_t>(v)] = static_cast<int>(order.size()), order.push_back(v);
  LocalRegion r;
  r.n_free = static_cast<int>(roi.free.size());
  r.P.resize(3, static_cast<Eigen::Index>(order.size()));
  for (std::size_t k = 0; k < order.size(); ++k)
    r.P.col(static_cast<Eigen::Index>(k)) = mesh.V.row(order[k]).transpose();
  std::vector<Eigen::Vector3i> faces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3i t;
    for (int c = 0; c < 3; ++c) t[c] = local[static_cast<std::size_t>(mesh.F(f, c))];
    if (t.minCoeff() >= 0) faces.push_back(t);
  }
  r.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    r.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return r;
}

// Undirected edges -> the number of triangles on them.
std::map<std::pair<int, int>, int> edge_uses(const Eigen::MatrixX3i& F) {
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = F(f, e), b = F(f, (e + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

Eigen::Vector3d normal(const Eigen::Matrix3Xd& P, int a, int b, int c) {
  return (P.col(b) - P.col(a)).cross(P.col(c) - P.col(a));
}

TEST(RegionCoarsening, KeepsTheConstrainedVerticesAndTheSurface) {
  const solver_testing::PulledSheet s = solver_testing::pulled_sheet(60, 0.1, 0.05);
  const LocalRegion r = local_region(*s.mesh, s.roi);
  const int n = static_cast<int>(r.P.cols());
  const detail::CoarseRegion c = detail::coarsen_region(r.P, r.faces, r.n_free, r.n_free / 9);
  const int m = static_cast<int>(c.kept.size());
  std::printf("free vertices %d -> %d, triangles %d -> %d\n", r.n_free, c.kept_free,
              static_cast<int>(r.faces.rows()), static_cast<int>(c.faces.rows()));
  // Most free vertices go (the target is a ninth; a third removed is the least the solver uses).
  EXPECT_LT(3 * c.kept_free, r.n_free);
  // Kept: ascending, free ones first, every constrained vertex among them.
  ASSERT_TRUE(std::is_sorted(c.kept.begin(), c.kept.end()));
  EXPECT_EQ(std::count_if(c.kept.begin(), c.kept.end(), [&](int v) { return v < r.n_free; }), c.kept_free);
  EXPECT_EQ(m - c.kept_free, n - r.n_free);
  for (int k = c.kept_free; k < m; ++k)
    EXPECT_EQ(c.kept[static_cast<std::size_t>(k)], r.n_free + k - c.kept_free);
  // Ancestors: a kept vertex maps to itself, every vertex to a kept one.
  ASSERT_EQ(static_cast<int>(c.ancestor.size()), n);
  for (int k = 0; k < m; ++k)
    EXPECT_EQ(c.ancestor[static_cast<std::size_t>(c.kept[static_cast<std::size_t>(k)])], k);
  for (int v = 0; v < n; ++v) {
    ASSERT_GE(c.ancestor[static_cast<std::size_t>(v)], 0);
    ASSERT_LT(c.ancestor[static_cast<std::size_t>(v)], m);
  }
  // The coarse triangles: valid, not degenerate, every edge on one or two of them, the same border, the same
  // topology (a disk: V - E + F = 1), every vertex used, none flipped (the sheet faces +z everywhere).
  ASSERT_GT(c.faces.rows(), 0);
  ASSERT_GE(c.faces.minCoeff(), 0);
  ASSERT_LT(c.faces.maxCoeff(), m);
  Eigen::Matrix3Xd coarse_P(3, m);
  for (int k = 0; k < m; ++k) coarse_P.col(k) = r.P.col(c.kept[static_cast<std::size_t>(k)]);
  std::vector<bool> used(static_cast<std::size_t>(m), false);
  for (Eigen::Index f = 0; f < c.faces.rows(); ++f) {
    const int a = c.faces(f, 0), b = c.faces(f, 1), d = c.faces(f, 2);
    ASSERT_TRUE(a != b && b != d && a != d);
    used[static_cast<std::size_t>(a)] = used[static_cast<std::size_t>(b)] =
        used[static_cast<std::size_t>(d)] = true;
    EXPECT_GT(normal(coarse_P, a, b, d).normalized().z(), 0.5) << "triangle " << f;
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  const auto fine_edges = edge_uses(r.faces), coarse_edges = edge_uses(c.faces);
  std::set<std::pair<int, int>> fine_border, coarse_border;
  for (const auto& [e, count] : fine_edges)
    if (count == 1) fine_border.insert(e);
  for (const auto& [e, count] : coarse_edges) {
    ASSERT_LE(count, 2);
    const int a = c.kept[static_cast<std::size_t>(e.first)], b = c.kept[static_cast<std::size_t>(e.second)];
    if (count == 1) coarse_border.insert({std::min(a, b), std::max(a, b)});
  }
  EXPECT_EQ(coarse_border, fine_border);
  EXPECT_EQ(m - static_cast<int>(coarse_edges.size()) + static_cast<int>(c.faces.rows()), 1);
}

TEST(RegionCoarsening, AStripOfBorderVerticesDoesNotCoarsen) {
  // Two rows of vertices: every vertex on the border, none interior, so none may go.
  const Mesh strip = solver_testing::sheet(40, 1, 4.0, 0.1);
  std::vector<int> handle{0}, fixed{40};
  const RegionOfInterest roi = make_roi(strip, handle, fixed, {});
  const LocalRegion r = local_region(strip, roi);
  const detail::CoarseRegion c = detail::coarsen_region(r.P, r.faces, r.n_free, r.n_free / 9);
  EXPECT_EQ(c.kept_free, r.n_free);
  EXPECT_EQ(c.faces.rows(), r.faces.rows());
}

struct Sheet : solver_testing::PulledSheet {
  Sheet() : PulledSheet(solver_testing::pulled_sheet(60, 0.1, 0.05)) {}
};

TEST(CoarseStartSolve, EndsAtTheMinimiserInFewerIterations) {
  const Sheet s;
  DeformOptions options;  // asan
  const Eigen::MatrixXd reference = solver_testing::asan_reference_from_rest(s);

  DeformOptions coarse_options;
  coarse_options.coarse_start_min_free = 0;
  Deformer coarse_deformer(s.mesh, s.roi, coarse_options);
  const DeformResult coarse = coarse_deformer.solve(s.d);
  DeformOptions rest_options;
  rest_options.coarse_start_min_free = -1;
  const DeformResult rest = Deformer(s.mesh, s.roi, rest_options).solve(s.d);
  EXPECT_TRUE(coarse.coarse_start);
  EXPECT_FALSE(coarse.smooth_start);
  EXPECT_FALSE(rest.coarse_start);
  ASSERT_TRUE(coarse.converged);
  std::printf("coarse-to-fine: %d iterations + %d coarse evaluations; from rest: %d iterations + %d probe\n",
              coarse.iterations, coarse.coarse_evaluations, rest.iterations, rest.probe_evaluations);
  EXPECT_GT(coarse.coarse_evaluations, 0);
  EXPECT_GT(coarse.probe_evaluations, 0);  // its early stop is probed as any cold solve's
  EXPECT_LT(coarse.iterations, rest.iterations);
  EXPECT_LT(coarse.initial_energy, 0.1 * rest.initial_energy);
  const double error = (coarse.V - reference).rowwise().norm().maxCoeff() / s.d.norm();
  EXPECT_LE(error, 2.0 * options.tolerance);
  ASSERT_TRUE(coarse.error_estimate.has_value());
  EXPECT_LE(error, 2.0 * *coarse.error_estimate);
  // Its time is in the solve but not per iteration.
  // (Counted in, per_iteration would be solve / evaluations to rounding; the coarse solve is a few % of it.)
  EXPECT_GT(
      coarse.timing.solve - coarse.timing.per_iteration * (coarse.iterations + coarse.probe_evaluations),
      1e-3 * coarse.timing.solve);

  // A second cold solve reuses the coarse region and gets the same; a warm start does not use it.
  const DeformResult again = coarse_deformer.solve(s.d);
  EXPECT_TRUE(again.coarse_start);
  EXPECT_EQ(again.iterations, coarse.iterations);
  EXPECT_EQ(again.V, coarse.V);
  ConstraintTargets warm = coarse_deformer.push_pull_targets(1.01 * s.d);
  warm.initial_guess = coarse.V;
  warm.rate_hint = coarse.contraction_rate;
  EXPECT_FALSE(coarse_deformer.solve(warm).coarse_start);
}

TEST(CoarseStartSolve, TheCoarseSolveCanBeCancelled) {
  const Sheet s;
  DeformOptions options;
  options.coarse_start_min_free = 0;
  Deformer deformer(s.mesh, s.roi, options);
  int asked = 0;
  const DeformResult r = deformer.solve(s.d, [&](const IterationReport& report) {
    EXPECT_EQ(report.iteration, 0);
    EXPECT_EQ(report.probe_step, asked + 1);
    EXPECT_NE(report.V, nullptr);
    return ++asked < 5;
  });
  EXPECT_EQ(asked, 5);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.stop_reason, StopReason::Cancelled);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.coarse_start);
  EXPECT_EQ(r.iterations, 0);
  // The positions it started from: the handle moved, the free vertices at rest.
  double farthest = 0.0;  // to rounding: the solver works relative to the region's centroid
  for (int v : s.roi.free) farthest = std::max(farthest, (r.V.row(v) - s.mesh->V.row(v)).norm());
  EXPECT_LT(farthest, 1e-12);
  for (int v : s.roi.handle) EXPECT_TRUE(r.V.row(v).isApprox(s.mesh->V.row(v) + s.d.transpose()));
  // Uncancelled, the same Deformer solves as usual.
  EXPECT_TRUE(deformer.solve(s.d).converged);
}

TEST(CoarseStartSolve, ACancelDuringTheCoarseSolveIsTheLastWord) {
  // With the smooth start also due, a cancel in the coarse solve starts nothing else: the result holds the
  // positions the callback was shown.
  const Sheet s;
  DeformOptions options;
  options.coarse_start_min_free = 0;
  options.smooth_start_min_free = 0;
  Deformer deformer(s.mesh, s.roi, options);
  std::shared_ptr<const Eigen::MatrixXd> shown;
  const DeformResult r = deformer.solve(s.d, [&](const IterationReport& report) {
    shown = report.V;
    return false;
  });
  ASSERT_NE(shown, nullptr);
  EXPECT_TRUE(r.cancelled);
  EXPECT_FALSE(r.smooth_start);
  EXPECT_FALSE(r.coarse_start);
  EXPECT_EQ(r.coarse_evaluations, 1);
  EXPECT_EQ(r.V, *shown);
  // An exception from the callback during the coarse solve reaches the caller.
  EXPECT_THROW(
      (void)deformer.solve(s.d, [](const IterationReport&) -> bool { throw std::logic_error("stop"); }),
      std::logic_error);
  // Neither left the Deformer unable to start coarse-to-fine.
  const DeformResult after = deformer.solve(s.d);
  EXPECT_TRUE(after.coarse_start);
  EXPECT_TRUE(after.converged);
}

TEST(CoarseStartSolve, SmallRegionsOtherMethodsAndThePaperSettingDoNotUseIt) {
  const Sheet s;
  DeformOptions options;  // asan
  ASSERT_GT(options.coarse_start_min_free, static_cast<int>(s.roi.free.size()));
  EXPECT_FALSE(Deformer(s.mesh, s.roi, options).solve(s.d).coarse_start);
  options.coarse_start_min_free = 0;
  EXPECT_FALSE(Deformer(s.mesh, s.roi, paper_iterations(options)).solve(s.d).coarse_start);
  options.method = Method::ArapSR;
  EXPECT_FALSE(Deformer(s.mesh, s.roi, options).solve(s.d).coarse_start);
  options.coarse_start_min_free = -2;
  EXPECT_THROW(Deformer(s.mesh, s.roi, options), std::invalid_argument);
}

}  // namespace
}  // namespace pushpull::deform
