// Text as geometry, for labels placed in the 3D scene (the review's readout by the hand, its menu panel):
// lines of ASCII text (stb_easy_font's glyph quads) on a dark panel, with an optional highlight bar behind one
// line. A label mesh has a fixed capacity, so its text changes by streaming new positions
// (Renderer::update_vertices) into the same mesh, never by creating meshes during a frame loop.
//
// Label frame: x right, y up, z towards the reader; metres (or whatever the caller's scene uses); the panel's
// bottom edge is centred on the origin, so a label placed at an anchor sits above it. The panel faces +z (draw
// with a transform whose +z points at the viewer; materials are double-sided anyway).
// Vertex layout of a label mesh: 4 panel vertices, 4 highlight vertices, then 4 per glyph quad; unused quads
// collapse to the origin (zero area, nothing drawn). Submeshes: 0 panel, 1 highlight, 2 glyphs (the caller
// assigns their materials: typically unlit dark, unlit accent, unlit white).
// Thread-safety: pure functions.
#pragma once

#include "pushpull/renderer/types.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pushpull::renderer {

struct TextLabelLayout {
  std::vector<float> positions;  // #V * 3 of make_text_label_mesh(max_quads)
  float width = 0.0f;            // panel size in label units
  float height = 0.0f;
  uint32_t quads = 0;            // glyph quads used (<= max_quads; text beyond the capacity is dropped)
  bool truncated = false;        // some glyphs did not fit
};

// The mesh of a label with room for max_quads glyph quads (about 4 per character), all collapsed; normals +z.
[[nodiscard]] RenderMesh make_text_label_mesh(uint32_t max_quads, int panel_material, int highlight_material,
                                              int glyph_material);

// Positions for `lines` in a mesh of make_text_label_mesh(max_quads): line_height is the distance between
// baselines (a capital letter is about 0.6 of it); highlight_line = index of the line with the bar behind it,
// -1 for none. Non-printable characters are drawn as '?'.
[[nodiscard]] TextLabelLayout layout_text_label(std::span<const std::string> lines, float line_height,
                                                uint32_t max_quads, int highlight_line = -1);

}  // namespace pushpull::renderer
