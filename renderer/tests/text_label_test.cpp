// renderer/text_label: the geometry of 3D text labels (CPU only).
#include "pushpull/renderer/text_label.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace pushpull::renderer;

TEST(TextLabel, MeshHasPanelHighlightAndGlyphSubmeshesOfTheCapacity) {
  const RenderMesh mesh = make_text_label_mesh(100, 1, 2, 3);
  EXPECT_EQ(mesh.vertex_count(), 4u * 102u);
  EXPECT_EQ(mesh.indices.size(), 6u * 102u);
  ASSERT_EQ(mesh.submeshes.size(), 3u);
  EXPECT_EQ(mesh.submeshes[0].material, 1);
  EXPECT_EQ(mesh.submeshes[2].index_count, 600u);
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
}

TEST(TextLabel, LayoutSitsAboveTheOriginCentredAndScalesWithTheLineHeight) {
  const std::vector<std::string> lines{"|d| 100.0 mm", "asan 66 it converged"};
  const TextLabelLayout a = layout_text_label(lines, 0.01f, 400);
  EXPECT_GT(a.quads, 20u);
  EXPECT_FALSE(a.truncated);
  EXPECT_GT(a.width, a.height);
  float min_x = 1e9f, max_x = -1e9f, min_y = 1e9f, max_y = -1e9f;
  for (size_t v = 8; v < 8 + 4 * size_t(a.quads); ++v) {
    min_x = std::min(min_x, a.positions[3 * v]);
    max_x = std::max(max_x, a.positions[3 * v]);
    min_y = std::min(min_y, a.positions[3 * v + 1]);
    max_y = std::max(max_y, a.positions[3 * v + 1]);
  }
  // The glyphs lie inside the panel, which starts at y = 0 and is centred on x = 0.
  EXPECT_GE(min_x, -0.5f * a.width);
  EXPECT_LE(max_x, 0.5f * a.width);
  EXPECT_GE(min_y, 0.0f);
  EXPECT_LE(max_y, a.height);
  EXPECT_NEAR(a.positions[0], -0.5f * a.width, 1e-7f);
  // Twice the line height, twice the size.
  const TextLabelLayout b = layout_text_label(lines, 0.02f, 400);
  EXPECT_NEAR(b.width, 2.0f * a.width, 1e-6f);
  EXPECT_NEAR(b.height, 2.0f * a.height, 1e-6f);
  // Unused glyph quads collapse to the origin.
  for (size_t v = 8 + 4 * size_t(a.quads); v < a.positions.size() / 3; ++v)
    EXPECT_EQ(a.positions[3 * v] * a.positions[3 * v] + a.positions[3 * v + 1] * a.positions[3 * v + 1],
              0.0f);
}

// stb_easy_font draws '|' as 'l'; the labels draw it taller, reaching below the baseline, so "|d|" does not
// read "ldl".
TEST(TextLabel, ABarIsTallerThanAnL) {
  auto extent = [](const std::string& text) {
    const std::vector<std::string> lines{text};
    const TextLabelLayout layout = layout_text_label(lines, 0.012f, 10);
    EXPECT_EQ(layout.quads, 1u) << text;
    float lo = 1e9f, hi = -1e9f;
    for (size_t v = 8; v < 12; ++v)
      lo = std::min(lo, layout.positions[3 * v + 1]), hi = std::max(hi, layout.positions[3 * v + 1]);
    return std::pair(lo, hi);
  };
  const auto [l_bottom, l_top] = extent("l");
  const auto [bar_bottom, bar_top] = extent("|");
  EXPECT_NEAR(l_top - l_bottom, 0.007f, 1e-6f);      // 7 font units of 0.001 (line height 12 units = 0.012)
  EXPECT_NEAR(bar_top - bar_bottom, 0.010f, 1e-6f);  // 10: one above the cap line, two below the baseline
  EXPECT_GT(bar_top, l_top);
  EXPECT_LT(bar_bottom, l_bottom);
}

// In a line, every bar and only the bars: "|d| 2" has the quads of '|', 'd' (4), '|' and '2' (6).
TEST(TextLabel, EveryBarOfALineAndNothingElseIsLengthened) {
  const std::vector<std::string> with_bars{"|d| 2"}, with_ls{"ldl 2"};
  const TextLabelLayout bars = layout_text_label(with_bars, 0.012f, 40),
                        ls = layout_text_label(with_ls, 0.012f, 40);
  ASSERT_EQ(bars.quads, ls.quads);
  std::vector<uint32_t> differing;
  for (uint32_t q = 0; q < bars.quads; ++q) {
    bool same = true;
    for (size_t k = 0; k < 12; ++k)
      same = same && bars.positions[3 * 8 + 12 * size_t(q) + k] == ls.positions[3 * 8 + 12 * size_t(q) + k];
    if (!same) differing.push_back(q);
  }
  EXPECT_EQ(differing, (std::vector<uint32_t>{0, 5}));  // the two bars; 'd' (1-4) and '2' (6-11) untouched
}

TEST(TextLabel, TextBeyondTheCapacityIsDroppedAndSaid) {
  const std::vector<std::string> lines{"a long line of text that needs many glyph quads"};
  const TextLabelLayout small = layout_text_label(lines, 0.01f, 10);
  EXPECT_EQ(small.quads, 10u);
  EXPECT_TRUE(small.truncated);
  EXPECT_EQ(small.positions.size(), size_t(12) * 12);
}

TEST(TextLabel, HighlightBarCoversItsLineOnly) {
  const std::vector<std::string> lines{"asan", "arap-sr", "arap-n"};
  const TextLabelLayout none = layout_text_label(lines, 0.01f, 200);
  for (size_t i = 12; i < 24; ++i) EXPECT_EQ(none.positions[i], 0.0f);  // no bar
  const TextLabelLayout second = layout_text_label(lines, 0.01f, 200, 1);
  const float bar_bottom = second.positions[12 + 1], bar_top = second.positions[12 + 7];
  EXPECT_GT(bar_top, bar_bottom);
  // Line 1 of 3: the bar is in the middle third of the panel.
  EXPECT_GT(bar_bottom, 0.15f * second.height);
  EXPECT_LT(bar_top, 0.85f * second.height);
}

TEST(TextLabel, NonPrintableCharactersBecomeQuestionMarks) {
  const std::vector<std::string> tab{"a\tb"}, question{"a?b"};
  const TextLabelLayout a = layout_text_label(tab, 0.01f, 100), b = layout_text_label(question, 0.01f, 100);
  EXPECT_EQ(a.positions, b.positions);
}

}  // namespace
