// app/progress_bar: the bar's text line (what a terminal shows during `pushpull replay`).
#include "progress_bar.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace {

using pushpull::app::progress_line;

TEST(ProgressLine, FillsCellsInProportionAndPrintsThePercentageAndText) {
  EXPECT_EQ(progress_line(0.5, "replaying", 10), "[#####-----]   50%  replaying");
  EXPECT_EQ(progress_line(0.0, "", 4), "[----]    0%");
  EXPECT_EQ(progress_line(1.0, "done", 4), "[####]  100%  done");
  EXPECT_EQ(progress_line(0.999, "", 10), "[#########-]   99%");  // never full before the end
}

TEST(ProgressLine, ClampsOutOfRangeAndNonFiniteFractions) {
  EXPECT_EQ(progress_line(-3.0, "", 4), "[----]    0%");
  EXPECT_EQ(progress_line(7.0, "", 4), "[####]  100%");
  EXPECT_EQ(progress_line(std::numeric_limits<double>::quiet_NaN(), "", 4), "[----]    0%");
}

}  // namespace
