// app/review_menu: the headset's method and colour-map panel (stick steps, trigger applies, both must be let go
// after opening), independent of OpenXR and the renderer.
#include "review_menu.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using pushpull::app::MenuChoice;
using pushpull::app::ReviewColour;
using pushpull::app::ReviewMenu;
namespace deform = pushpull::deform;

int row_of(deform::Method m) {
  return int(std::find(deform::kAllMethods.begin(), deform::kAllMethods.end(), m) - deform::kAllMethods.begin());
}

TEST(ReviewMenu, OpensOnTheCurrentMethodAndClosesOnTheSecondToggle) {
  ReviewMenu menu;
  EXPECT_FALSE(menu.is_open());
  menu.toggle(deform::Method::ArapSR);
  EXPECT_TRUE(menu.is_open());
  EXPECT_EQ(menu.selected_row(), row_of(deform::Method::ArapSR));
  const auto lines = menu.lines(deform::Method::ArapSR, ReviewColour::Displacement);
  EXPECT_EQ(lines.at(size_t(menu.selected_line())), "* arap-sr");
  EXPECT_NE(std::find(lines.begin(), lines.end(), "* displacement"), lines.end());
  menu.toggle(deform::Method::ArapSR);
  EXPECT_FALSE(menu.is_open());
  EXPECT_FALSE(menu.update(-1.0f, 1.0f).method);  // closed: nothing happens
}

TEST(ReviewMenu, StickStepsOneRowPerPushAndWrapsAround) {
  ReviewMenu menu;
  menu.toggle(deform::kAllMethods.front());
  menu.update(0.0f, 0.0f);                        // centred: armed
  for (int frame = 0; frame < 10; ++frame) menu.update(-1.0f, 0.0f);  // held down: one step
  EXPECT_EQ(menu.selected_row(), 1);
  menu.update(0.0f, 0.0f);
  menu.update(-0.9f, 0.0f);
  EXPECT_EQ(menu.selected_row(), 2);
  menu.update(0.45f, 0.0f);  // between the dead zone and the step threshold: neither re-arms nor steps
  menu.update(1.0f, 0.0f);   // still not re-armed (never back under 0.3)
  EXPECT_EQ(menu.selected_row(), 2);
  menu.update(0.1f, 0.0f);
  menu.update(1.0f, 0.0f);  // up
  EXPECT_EQ(menu.selected_row(), 1);
  menu.update(0.0f, 0.0f);
  menu.update(1.0f, 0.0f);
  menu.update(0.0f, 0.0f);
  menu.update(1.0f, 0.0f);  // above the first row: the last (the last colour map)
  const int rows = int(deform::kAllMethods.size()) + 3;
  EXPECT_EQ(menu.selected_row(), rows - 1);
}

TEST(ReviewMenu, TriggerAppliesTheSelectedRowOncePerPress) {
  ReviewMenu menu;
  menu.toggle(deform::Method::Asan);
  // The trigger held while opening does nothing until it is let go.
  EXPECT_FALSE(menu.update(0.0f, 1.0f).method);
  EXPECT_FALSE(menu.update(0.0f, 0.1f).method);
  const MenuChoice applied = menu.update(0.0f, 0.9f);
  ASSERT_TRUE(applied.method);
  EXPECT_EQ(*applied.method, deform::Method::Asan);
  EXPECT_FALSE(menu.update(0.0f, 1.0f).method);  // held: once
  // Down past the methods to the colour maps.
  menu.update(0.0f, 0.0f);
  const int to_material = int(deform::kAllMethods.size()) - row_of(deform::Method::Asan);
  for (int k = 0; k < to_material; ++k) {
    menu.update(-1.0f, 0.0f);
    menu.update(0.0f, 0.0f);
  }
  const MenuChoice colour = menu.update(0.0f, 1.0f);
  EXPECT_FALSE(colour.method);
  ASSERT_TRUE(colour.colour);
  EXPECT_EQ(*colour.colour, ReviewColour::Material);
}

}  // namespace
