// app/error_gist: the readouts' and HUD's short form of a solver error (the desktop readout cut the whole
// message mid-word at the window's edge: "error: deformer: arap-s: the energy went negati").
#include "error_gist.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pushpull::app {
namespace {

TEST(ErrorGist, KeepsTheFirstClauseWithoutTheDeformerAndMethodPrefixes) {
  EXPECT_EQ(
      error_gist("deformer: arap-s: the energy went negative, -0.419323 (from -0.081278 at the start), on "
                 "a region of 18 vertices"),
      "the energy went negative");
  EXPECT_EQ(error_gist("deformer: asan: the global matrix could not be factored (pivot 12)"),
            "the global matrix could not be factored");
  EXPECT_EQ(error_gist("stale request"), "stale request");
}

TEST(ErrorGist, IsShortAndNeverEmpty) {
  const std::string gist = error_gist(std::string(200, 'x'));
  EXPECT_EQ(gist.size(), 48u);
  EXPECT_EQ(gist.substr(45), "...");
  EXPECT_EQ(error_gist(""), "see the terminal");
  EXPECT_EQ(error_gist("deformer: asan: , nothing before the comma"), "see the terminal");
}

}  // namespace
}  // namespace pushpull::app
