// app/drag_notes: the warnings a drag's readout adds (steep pull, the surface overshooting, a whole part
// moving with no border to hold it), and none of the preview-based ones before this drag's first preview.
#include "drag_notes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

namespace pushpull::app {
namespace {

bool has(const std::vector<std::string>& lines, const std::string& start) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.rfind(start, 0) == 0; });
}

deform::Snapshot preview(double pull, double max_displacement, bool region_has_border) {
  deform::Snapshot s;
  s.kind = deform::Snapshot::Kind::Preview;
  s.d = Eigen::Vector3d(0.0, 0.0, pull);
  s.max_displacement = max_displacement;
  auto region = std::make_shared<deform::RegionOfInterest>();
  region->handle = {0, 1};
  region->free = {2, 3};
  if (region_has_border) region->fixed = {4, 5};
  region->whole_parts = !region_has_border;  // a borderless region here is a grabbed part
  s.region = region;
  return s;
}

TEST(DragNotes, AnOrdinaryPullSaysNothing) {
  EXPECT_TRUE(drag_notes(0.1, 0.05, preview(0.1, 0.1, true)).empty());
}

TEST(DragNotes, ASteepPullAndAnOvershootingSurfaceAreSaid) {
  const auto lines = drag_notes(0.25, 0.05, preview(0.25, 0.5, true));
  EXPECT_TRUE(has(lines, "steep: 5x the handle radius"));
  EXPECT_TRUE(has(lines, "the surface moves 2.0x the pull"));
}

TEST(DragNotes, AGrabbedWholePartIsSaidToMoveWhole) {
  EXPECT_TRUE(has(drag_notes(0.1, 0.05, preview(0.1, 0.1, false)), "the whole part moves"));
  EXPECT_FALSE(has(drag_notes(0.1, 0.05, preview(0.1, 0.1, true)), "the whole part moves"));
}

// A region with no border that is not a whole part is the handle alone (a region too small for the
// triangles around it): said as such, not as a whole part moving.
TEST(DragNotes, AHandleAloneIsNotCalledAWholePart) {
  deform::Snapshot s = preview(0.1, 0.1, false);
  auto region = std::make_shared<deform::RegionOfInterest>(*s.region);
  region->free.clear();
  region->whole_parts = false;
  s.region = region;
  const auto lines = drag_notes(0.1, 0.05, s);
  EXPECT_TRUE(has(lines, "only the handle moves"));
  EXPECT_FALSE(has(lines, "the whole part moves"));
}

TEST(DragNotes, BeforeTheDragsFirstPreviewOnlyTheHandsPullCounts) {
  deform::Snapshot committed = preview(0.1, 0.5, false);  // the previous push/pull's commit
  committed.kind = deform::Snapshot::Kind::Committed;
  const auto lines = drag_notes(0.3, 0.05, committed);
  EXPECT_TRUE(has(lines, "steep"));  // the hand's |d| against the handle: known at once
  EXPECT_FALSE(has(lines, "the surface moves"));
  EXPECT_FALSE(has(lines, "the whole part moves"));
}

// What deform prints and a replay writes into the commit's metrics for a pull over 4 handle radii.
TEST(SteepPullWarning, APullOverFourHandleRadiiIsSteep) {
  EXPECT_FALSE(steep_pull_warning(0.2, 0.05));  // 4x: not over
  const auto steep = steep_pull_warning(0.35, 0.05);
  ASSERT_TRUE(steep);
  EXPECT_EQ(steep->rfind("steep: |d| is 7x the handle radius, a spike rather than a bulge", 0), 0u) << *steep;
  EXPECT_FALSE(steep_pull_warning(1.0, 0.0));  // no handle radius: nothing to compare with
}

}  // namespace
}  // namespace pushpull::app
