// Region growing, explicit regions, selections, near-boundary warnings and precondition errors.
#include <gtest/gtest.h>

#include <algorithm>

#include "pushpull/deform/roi.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

int vertex(int i, int j) {
  return j * 21 + i;
}  // 20 x 20 sheet

TEST(RoiBuild, GrowsFromHandleUpToFixed) {
  const Mesh mesh = solver_testing::sheet(20, 20, 1, 1);
  std::vector<int> fixed;
  for (int j = 0; j <= 20; ++j) fixed.push_back(vertex(5, j));  // a wall at i = 5
  const RegionOfInterest roi = build_roi(mesh, std::vector<int>{vertex(15, 10)}, fixed);
  EXPECT_EQ(roi.handle, std::vector<int>{vertex(15, 10)});
  EXPECT_EQ(roi.fixed, fixed);
  for (int j = 0; j <= 20; ++j) {
    EXPECT_FALSE(roi.contains(vertex(4, j)));  // beyond the wall
    EXPECT_EQ(roi.role[static_cast<std::size_t>(vertex(10, j))], VertexRole::Free);
  }
  EXPECT_EQ(roi.size(), 21u * 16u);
}

TEST(RoiBuild, MaxDistanceIsGeodesicAlongEdgesAndBoundaryIsFixed) {
  const Mesh mesh = solver_testing::sheet(20, 20, 1, 1);  // edge length 0.05
  const RegionOfInterest roi = build_roi(mesh, std::vector<int>{vertex(10, 10)}, {}, 0.2);
  EXPECT_TRUE(roi.contains(vertex(14, 10)));                                         // 4 edges = 0.2
  EXPECT_FALSE(roi.contains(vertex(15, 10)));                                        // 0.25
  EXPECT_EQ(roi.role[static_cast<std::size_t>(vertex(14, 10))], VertexRole::Fixed);  // next to outside
  EXPECT_EQ(roi.role[static_cast<std::size_t>(vertex(12, 10))], VertexRole::Free);
  // Every fixed vertex has an outside neighbour here (no user fixed set).
  EXPECT_FALSE(roi.fixed.empty());
  // Unlimited distance on a closed-off sheet: everything, no boundary.
  const RegionOfInterest all = build_roi(mesh, std::vector<int>{vertex(10, 10)}, {});
  EXPECT_EQ(all.size(), mesh.V.rows());
  EXPECT_TRUE(all.fixed.empty());
  EXPECT_TRUE(all.whole_parts);  // the whole sheet: it moves as one piece
  EXPECT_FALSE(roi.whole_parts);
  // Distance 0: the handle alone, no border (handles stay handles) and not a whole part: torn out.
  const RegionOfInterest alone = build_roi(mesh, std::vector<int>{vertex(10, 10), vertex(11, 10)}, {}, 0.0);
  EXPECT_EQ(alone.size(), 2u);
  EXPECT_TRUE(alone.fixed.empty());
  EXPECT_FALSE(alone.whole_parts);
}

TEST(RoiBuild, WarnsWhenHandleIsNearTheFixedBoundary) {
  const Mesh mesh = solver_testing::sheet(20, 20, 1, 1);
  std::vector<int> fixed;
  for (int j = 0; j <= 20; ++j) fixed.push_back(vertex(0, j));
  const RegionOfInterest near = build_roi(mesh, std::vector<int>{vertex(2, 10)}, fixed);
  ASSERT_EQ(near.warnings.size(), 1u);
  EXPECT_NE(near.warnings[0].find("2 rings"), std::string::npos) << near.warnings[0];
  const RegionOfInterest far = build_roi(mesh, std::vector<int>{vertex(10, 10)}, fixed);
  EXPECT_TRUE(far.warnings.empty());
}

TEST(RoiBuild, ExplicitRegionAndSelection) {
  const Mesh mesh = solver_testing::sheet(20, 20, 1, 1);
  std::vector<int> region;
  for (int j = 5; j <= 15; ++j) {
    for (int i = 5; i <= 15; ++i) region.push_back(vertex(i, j));
  }
  const RegionOfInterest roi = make_roi(mesh, std::vector<int>{vertex(10, 10)}, {}, region);
  EXPECT_EQ(roi.size(), 121u);
  EXPECT_EQ(roi.fixed.size(), 40u);  // the ring of the square
  std::vector<int> selection(static_cast<std::size_t>(mesh.V.rows()), -1);
  for (int v : region) selection[static_cast<std::size_t>(v)] = 1;
  selection[static_cast<std::size_t>(vertex(10, 10))] = 2;
  const RegionOfInterest from_sel = roi_from_selection(mesh, selection);
  EXPECT_EQ(from_sel.handle, roi.handle);
  EXPECT_EQ(from_sel.fixed, roi.fixed);
  EXPECT_EQ(from_sel.free, roi.free);
}

TEST(RoiBuild, PreconditionErrors) {
  const Mesh mesh = solver_testing::sheet(4, 4, 1, 1);
  EXPECT_THROW((void)build_roi(mesh, std::vector<int>{}, {}), std::invalid_argument);
  EXPECT_THROW((void)build_roi(mesh, std::vector<int>{99}, {}), std::invalid_argument);
  EXPECT_THROW((void)build_roi(mesh, std::vector<int>{3}, std::vector<int>{3}), std::invalid_argument);
  EXPECT_THROW((void)build_roi(mesh, std::vector<int>{3}, {}, -1.0), std::invalid_argument);
  EXPECT_THROW((void)roi_from_selection(mesh, std::vector<int>{1, 2}), std::invalid_argument);
  try {
    (void)build_roi(mesh, std::vector<int>{1}, std::vector<int>{-5});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fixed vertex -5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pushpull::deform
