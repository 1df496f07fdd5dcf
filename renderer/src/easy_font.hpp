// stb_easy_font (Debian's libstb-dev), the bitmap font of the legends and the 3D text labels, included
// without its warnings (unused static functions, missing initialisers, sign compares) tripping -Werror. Every
// function is static: each source file that includes this gets its own copy.
#pragma once

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace pushpull::renderer::detail {

// stb_easy_font draws '|' exactly as 'l' (one stroke from the cap line to the baseline), so "|d|" reads
// "ldl". After stb_easy_font_print(x, y, text, ..) wrote `quads` quads (4 vertices of `stride` bytes, x and y
// the first two floats) into vertex_buffer, this lengthens every '|' stroke from one font unit above the cap
// line down to the descender line (that of 'g'), which tells it apart. Text as stb_easy_font reads it: '\n'
// starts a line, the other characters must be printable ASCII (32-126).
inline void lengthen_bars(const char* text, float y, void* vertex_buffer, int quads, int stride = 16) {
  float line_y = y;
  int q = 0;
  for (const char* c = text; *c != '\0' && q < quads; ++c) {
    if (*c == '\n') {
      line_y += 12.0f;  // stb_easy_font's line advance
      continue;
    }
    // The quads stb_easy_font_print drew for this character: its segments of non-zero length.
    const int i = *c - 32;
    int count = 0;
    for (int k = stb_easy_font_charinfo[i].h_seg; k < stb_easy_font_charinfo[i + 1].h_seg; ++k)
      count += (stb_easy_font_hseg[k] & 7) != 0;
    for (int k = stb_easy_font_charinfo[i].v_seg; k < stb_easy_font_charinfo[i + 1].v_seg; ++k)
      count += (stb_easy_font_vseg[k] & 7) != 0;
    if (*c == '|' && count == 1) {
      char* quad = static_cast<char*>(vertex_buffer) + 4 * q * stride;
      for (int k = 0; k < 4; ++k) {
        float* vertex_y = reinterpret_cast<float*>(quad + k * stride) + 1;
        *vertex_y = k < 2 ? line_y - 1.0f : line_y + 9.0f;  // vertices 0, 1 on top, 2, 3 at the bottom
      }
    }
    q += count;
  }
}

}  // namespace pushpull::renderer::detail
