// The displacement legend: ticks at round numbers placed at their value, and a title that is never
// clipped (CPU only: the legend is rasterised on the CPU).
#include "pushpull/renderer/geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pushpull::renderer {
namespace {

TEST(Legend, RoundTicks) {
  EXPECT_EQ(round_ticks(102.0), (std::vector<double>{0, 25, 50, 75, 100}));
  EXPECT_EQ(round_ticks(25.0), (std::vector<double>{0, 5, 10, 15, 20, 25}));
  const std::vector<double> unit = round_ticks(1.0);
  ASSERT_EQ(unit.size(), 6u);
  for (std::size_t k = 0; k < unit.size(); ++k) EXPECT_NEAR(unit[k], 0.2 * double(k), 1e-12);
  EXPECT_EQ(round_ticks(7.3), (std::vector<double>{0, 2, 4, 6}));
  EXPECT_EQ(round_ticks(0.0), std::vector<double>{});
  for (double max : {0.37, 3.0, 12.0, 48.0, 99.0, 250.0, 1234.0}) {
    const std::vector<double> ticks = round_ticks(max);
    EXPECT_GE(ticks.size(), 3u) << max;
    EXPECT_LE(ticks.size(), 6u) << max;
    EXPECT_LE(ticks.back(), max * (1 + 1e-9)) << max;
  }
}

struct Rgb {
  int r, g, b;
  bool operator==(const Rgb&) const = default;
};

Rgb at(const TextureRGBA8& image, int x, int y) {
  const std::size_t i = (std::size_t(y) * image.width + std::size_t(x)) * 4;
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

bool is_text(const Rgb& c) {
  return c.r > 230 && c.g > 230 && c.b > 230;
}

// Reads the tick marks off the picture: rows of text colour just right of the colour bar, as values of
// the scale (bar bottom = 0, bar top = max).
std::vector<double> drawn_tick_values(const TextureRGBA8& legend, double max) {
  const Rgb panel = at(legend, 0, 0);
  const int middle = int(legend.height) / 2;
  int bar_x0 = 0;
  while (bar_x0 < int(legend.width) &&
         (at(legend, bar_x0, middle) == panel || is_text(at(legend, bar_x0, middle))))
    ++bar_x0;
  int bar_x1 = bar_x0;
  while (bar_x1 < int(legend.width) && !(at(legend, bar_x1, middle) == panel) &&
         !is_text(at(legend, bar_x1, middle)))
    ++bar_x1;
  int bar_top = middle, bar_bottom = middle;
  while (bar_top > 0 && !(at(legend, bar_x0, bar_top - 1) == panel)) --bar_top;
  while (bar_bottom + 1 < int(legend.height) && !(at(legend, bar_x0, bar_bottom + 1) == panel)) ++bar_bottom;
  std::vector<double> values;
  for (int y = 0; y < int(legend.height);) {
    if (!is_text(at(legend, bar_x1, y))) {
      ++y;
      continue;
    }
    int end = y;
    while (end < int(legend.height) && is_text(at(legend, bar_x1, end))) ++end;
    const double centre = 0.5 * (y + end - 1);
    values.push_back(max * (bar_bottom - centre) / (bar_bottom - bar_top));
    y = end;
  }
  return values;
}

TEST(Legend, TicksSitAtRoundValues) {
  const TextureRGBA8 legend = make_displacement_legend(102.0f, "|d| mm", 160, 440);
  std::vector<double> values = drawn_tick_values(legend, 102.0);
  std::sort(values.begin(), values.end());
  ASSERT_EQ(values.size(), 5u);
  for (std::size_t k = 0; k < values.size(); ++k) EXPECT_NEAR(values[k], 25.0 * double(k), 0.6) << k;
}

TEST(Legend, LongTitleIsNotClipped) {
  for (const char* title : {"|d| mm", "|d| model units", "|d| millimetres at life size"}) {
    const TextureRGBA8 legend = make_displacement_legend(102.0f, title, 60, 110);
    int title_pixels = 0, edge_pixels = 0;
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < int(legend.width); ++x)
        if (is_text(at(legend, x, y))) {
          ++title_pixels;
          if (x >= int(legend.width) - 2) ++edge_pixels;
        }
    EXPECT_GT(title_pixels, 20) << title;
    EXPECT_EQ(edge_pixels, 0) << title << ": the title runs into the right edge";
  }
}

}  // namespace
}  // namespace pushpull::renderer
