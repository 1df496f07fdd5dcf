// Every kind of bad input gets a clear error naming where it is, or a documented repair; never NaN.
#include <gtest/gtest.h>

#include <limits>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/mesh_validation.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

void expect_error(const Mesh& mesh, const std::string& fragment) {
  try {
    (void)validate_mesh(mesh);
    FAIL() << "no error, expected '" << fragment << "'";
  } catch (const MeshValidationError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// Pulls the middle of a 10 x 10 sheet (fixed border) with the given method; checks the output is finite.
DeformResult pull_middle(const Mesh& mesh, Method method = Method::Asan) {
  std::vector<int> handle = {60}, fixed;
  for (int v = 0; v < 121; ++v) {
    const int i = v % 11, j = v / 11;
    if (i == 0 || j == 0 || i == 10 || j == 10) fixed.push_back(v);
  }
  DeformOptions options;
  options.method = method;
  const RegionOfInterest roi = make_roi(mesh, handle, fixed, {});
  return deform(mesh, roi, Eigen::Vector3d(0.0, 0.0, 0.2), options);
}

TEST(ValidationMesh, NonFiniteCoordinateNamesVertex) {
  Mesh mesh = solver_testing::sheet(2, 2, 1, 1);
  mesh.V(4, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_error(mesh, "vertex 4");
  mesh.V(4, 1) = std::numeric_limits<double>::infinity();
  expect_error(mesh, "vertex 4 has a non-finite");
}

TEST(ValidationMesh, OutOfRangeIndexNamesFace) {
  Mesh mesh = solver_testing::sheet(2, 2, 1, 1);
  mesh.F(3, 2) = 9;
  expect_error(mesh, "face 3 corner 2 references vertex 9");
  mesh.F(3, 2) = -1;
  expect_error(mesh, "face 3");
}

TEST(ValidationMesh, WrongShapes) {
  Mesh mesh = solver_testing::sheet(2, 2, 1, 1);
  mesh.V.conservativeResize(Eigen::NoChange, 2);
  expect_error(mesh, "#V by 3");
  Mesh quads = solver_testing::sheet(2, 2, 1, 1);
  quads.F = Eigen::MatrixXi::Zero(2, 4);
  expect_error(quads, "#F by 3");
}

TEST(ValidationMesh, ErrorsReachTheDeformerConstructor) {
  Mesh mesh = solver_testing::sheet(4, 4, 1, 1);
  const RegionOfInterest roi = make_roi(mesh, std::vector<int>{12}, std::vector<int>{0}, {});
  mesh.V(3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Deformer(std::make_shared<const Mesh>(mesh), roi), MeshValidationError);
}

TEST(ValidationMesh, DegenerateFacesAreSkippedNotNaN) {
  Mesh mesh = solver_testing::sheet(10, 10, 1, 1);
  // Collapse an interior vertex onto its neighbour: its faces get zero area (repaired: zero weights).
  mesh.V.row(61) = mesh.V.row(62);
  // A face repeating a vertex index.
  mesh.F.conservativeResize(mesh.F.rows() + 1, 3);
  mesh.F.row(mesh.F.rows() - 1) << 30, 30, 31;
  const ValidationReport report = validate_mesh(mesh);
  EXPECT_GE(report.degenerate_faces.size(), 3u);
  EXPECT_EQ(report.degenerate_faces.back(), mesh.F.rows() - 1);
  EXPECT_FALSE(report.clean());
  for (Method m : kAllMethods) {
    const DeformResult r = pull_middle(mesh, m);
    EXPECT_TRUE(r.V.allFinite()) << method_name(m);
    EXPECT_FALSE(r.warnings.empty());
  }
}

TEST(ValidationMesh, VertexHeldOnlyByZeroAreaFacesIsPinned) {
  // A free vertex whose every face is degenerate has no stiffness: it stays put (warning), no NaN, no throw.
  Mesh mesh = solver_testing::sheet(10, 10, 1, 1);
  mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
  mesh.V.row(121) = 0.5 * (mesh.V.row(40) + mesh.V.row(41));  // on edge (40, 41): its faces have zero area
  mesh.F.conservativeResize(mesh.F.rows() + 2, 3);
  mesh.F.bottomRows(2) << 40, 121, 41, 41, 121, 40;
  for (Method m : kAllMethods) {
    const DeformResult r = pull_middle(mesh, m);
    EXPECT_TRUE(r.V.allFinite()) << method_name(m);
    EXPECT_EQ(r.V.row(121), mesh.V.row(121)) << method_name(m);
  }
}

TEST(ValidationMesh, NearlyDegenerateFacesGetClampedFiniteWeights) {
  Mesh mesh = solver_testing::sheet(10, 10, 1, 1);
  mesh.V.row(61) = mesh.V.row(62) + Eigen::RowVector3d(1e-9, 1e-12, 0);
  for (Method m : kAllMethods) EXPECT_TRUE(pull_middle(mesh, m).V.allFinite()) << method_name(m);
}

TEST(ValidationMesh, UnreferencedVerticesAreReportedAndStay) {
  Mesh mesh = solver_testing::sheet(10, 10, 1, 1);
  mesh.V.conservativeResize(mesh.V.rows() + 2, 3);
  mesh.V.bottomRows(2) << 5, 5, 5, 6, 6, 6;
  const ValidationReport report = validate_mesh(mesh);
  EXPECT_EQ(report.unreferenced_vertices, (std::vector<int>{121, 122}));
  // In an explicit whole-mesh region they are free vertices with no connection: pinned, with a warning.
  std::vector<int> fixed;
  for (int v = 0; v < 11; ++v) fixed.push_back(v);
  const RegionOfInterest roi = make_roi(mesh, std::vector<int>{115}, fixed, {});
  const DeformResult r = deform(mesh, roi, Eigen::Vector3d(0, 0, 0.3));
  EXPECT_TRUE(r.V.allFinite());
  EXPECT_EQ(r.V.row(121), mesh.V.row(121));
  bool pinned_warning = false;
  for (const auto& w : r.warnings) pinned_warning |= w.find("stay at rest") != std::string::npos;
  EXPECT_TRUE(pinned_warning);
}

TEST(ValidationMesh, SeveralComponentsAndNonManifoldEdges) {
  Mesh a = solver_testing::sheet(4, 4, 1, 1);
  Mesh mesh;
  mesh.V.resize(2 * a.V.rows() + 1, 3);
  mesh.V << a.V, a.V.rowwise() + Eigen::RowVector3d(3, 0, 0), Eigen::RowVector3d(0.5, 0.5, 1.0);
  mesh.F.resize(2 * a.F.rows() + 1, 3);
  const int n = static_cast<int>(a.V.rows());
  mesh.F << a.F, a.F.array() + n, Eigen::RowVector3i(0, 1, 2 * n);  // third face on edge (0, 1)
  mesh.F.bottomRows(1) << 0, 1, 2 * n;
  // Make edge (0,1) carry three faces: the sheet's face uses it once, add two more.
  mesh.F.conservativeResize(mesh.F.rows() + 1, 3);
  mesh.F.bottomRows(1) << 1, 0, 2 * n;
  const ValidationReport report = validate_mesh(mesh);
  EXPECT_EQ(report.component_count, 2);
  EXPECT_FALSE(report.non_manifold_edges.empty());
  // Deforming one component leaves the other alone; the second has no constraint: pinned.
  const RegionOfInterest roi = make_roi(mesh, std::vector<int>{24}, std::vector<int>{0, 1, 2, 3, 4}, {});
  const DeformResult r = deform(mesh, roi, Eigen::Vector3d(0, 0, 0.5));
  EXPECT_TRUE(r.V.allFinite());
  EXPECT_EQ(r.V.middleRows(n, n), mesh.V.middleRows(n, n));
  EXPECT_GT((r.V.row(24) - mesh.V.row(24)).norm(), 0.49);
}

}  // namespace
}  // namespace pushpull::deform
