// Every method on a sheet with needles and caps of aspect 1e-6 .. 1e-12 next to the handle: the global matrix
// factors, the energy is never negative (the weights are PSD by construction), the result is finite and close
// to the same pull on the sheet without slivers. With clamped cotangents the caps made the matrix
// indefinite ("singular or indefinite") and the energy negative.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "sliver_mesh.hpp"

namespace pushpull::deform {
namespace {

using testing::Sliver;

constexpr int kCells = 16;
const Eigen::Vector3d kPull(0.0, 0.0, 0.05);

// Caps and needles in free cells around the centre (the handle is the centre vertex and its 4 neighbours),
// in both diagonal orientations.
const std::map<std::pair<int, int>, Sliver> kSlivers = {{{9, 8}, Sliver::Cap},    {{6, 8}, Sliver::Cap},
                                                        {{8, 5}, Sliver::Cap},    {{10, 10}, Sliver::Needle},
                                                        {{5, 9}, Sliver::Needle}, {{7, 6}, Sliver::Needle}};

RegionOfInterest sheet_roi(const testing::SliverSheet& s) {
  std::vector<int> handle, fixed;
  for (int v = 0; v < s.grid_vertices; ++v) {
    const Eigen::Vector3d p = s.mesh.V.row(v);
    if (std::hypot(p.x() - 0.5, p.y() - 0.5) < 0.07) handle.push_back(v);
    if (p.x() < 1e-9 || p.y() < 1e-9 || p.x() > 1 - 1e-9 || p.y() > 1 - 1e-9) fixed.push_back(v);
  }
  return make_roi(s.mesh, handle, fixed, {});
}

DeformOptions options_for(Method method) {
  DeformOptions o;
  o.method = method;
  o.max_iterations = 60;
  return o;
}

struct SliverCase {
  Method method;
  double aspect;
};

class SolverSlivers : public ::testing::TestWithParam<SliverCase> {};

TEST_P(SolverSlivers, FactorsWithNonNegativeEnergyAndFiniteResult) {
  const auto [method, aspect] = GetParam();
  const testing::SliverSheet s = testing::sliver_sheet(kCells, kSlivers, aspect);
  auto mesh = std::make_shared<const Mesh>(s.mesh);
  const RegionOfInterest roi = sheet_roi(s);
  for (int m : s.sliver_vertex) ASSERT_EQ(roi.role[static_cast<std::size_t>(m)], VertexRole::Free);

  std::optional<Deformer> deformer;
  DeformResult r;
  try {
    deformer.emplace(mesh, roi, options_for(method));
    r = deformer->solve(kPull);
  } catch (const std::runtime_error& e) {
    // Only arap-s may fail (its spoke energies are not PSD), and then it must say so and what to try.
    const std::string what = e.what();
    ASSERT_EQ(method, Method::ArapS) << what;
    EXPECT_NE(what.find("arap-s"), std::string::npos) << what;
    EXPECT_NE(what.find("use arap-sr or asan"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(roi.size()) + " vertices"), std::string::npos) << what;
    return;
  }
  ASSERT_TRUE(r.V.allFinite());
  ASSERT_FALSE(r.energy_trace.empty());
  for (double e : r.energy_trace) ASSERT_TRUE(std::isfinite(e));

  // The energy of a PSD form is never negative: allow round-off relative to the initial energy.
  if (method != Method::ArapS) {
    const double tolerance = 1e-12 * std::max(r.initial_energy, 1e-300);
    EXPECT_GE(r.initial_energy, 0.0);
    for (std::size_t k = 0; k < r.energy_trace.size(); ++k)
      EXPECT_GE(r.energy_trace[k], -tolerance) << "iteration " << k + 1;
    EXPECT_GE(deformer->energy(r.V), -tolerance);
    EXPECT_GE(deformer->energy(mesh->V), -tolerance);  // the rest shape: zero energy
  }

  // Nothing flies away: a 5 cm pull of the dome's top moves no vertex (slivers included) much more than that.
  const double largest = (r.V - mesh->V).rowwise().norm().maxCoeff();
  EXPECT_LE(largest, 1.5 * kPull.norm());

  // Close to the same pull without slivers, on the grid vertices both meshes share.
  const testing::SliverSheet plain = testing::sliver_sheet(kCells, {}, aspect);
  const DeformResult p = deform(plain.mesh, sheet_roi(plain), kPull, options_for(method));
  const double gap =
      (r.V.topRows(s.grid_vertices) - p.V.topRows(s.grid_vertices)).rowwise().norm().maxCoeff();
  RecordProperty("gap_to_plain", std::to_string(gap));
  // arap-h's bending term only sees |H'_i| (its rotation R_i is free): at a needle, the short edge's large
  // (mollified) weight lets x_m - x_c alone restore |(L x)_m| and |(L x)_c| in any direction, which frees the
  // shape around it. Measured (lambda = 1): gap 0.39 |d| here, 0.37 |d| converged to an estimate of 3e-5;
  // one needle alone 0.51 |d|, one cap alone 0.07 |d| (arap-sr-h: 0.05 |d|). The factorization, PSD and
  // finiteness checks above still hold for arap-h; its shape is not claimed to survive needles.
  if (method != Method::ArapH) {
    EXPECT_LE(gap, 0.25 * kPull.norm()) << "iterations " << r.iterations;
  }
}

std::vector<SliverCase> all_cases() {
  std::vector<SliverCase> cases;
  for (Method m : kAllMethods) {
    for (double aspect : {1e-6, 1e-8, 1e-10, 1e-12}) cases.push_back({m, aspect});
  }
  return cases;
}

std::string case_name(const ::testing::TestParamInfo<SliverCase>& info) {
  std::string name(method_name(info.param.method));
  for (char& c : name) c = c == '-' ? '_' : c;
  const long exponent = -std::lround(std::log10(info.param.aspect));
  return name + "_aspect_1em" + std::to_string(exponent);
}

INSTANTIATE_TEST_SUITE_P(NeedlesAndCaps, SolverSlivers, ::testing::ValuesIn(all_cases()), case_name);

}  // namespace
}  // namespace pushpull::deform
