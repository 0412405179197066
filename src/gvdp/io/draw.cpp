#include "gvdp/io/draw.h"

#include <algorithm>

#define STB_EASY_FONT_IMPLEMENTATION
#include <stb/stb_easy_font.h>

namespace gvdp::detail {

void fillRect(Image& im, int x0, int y0, int x1, int y1, uint32_t c) {
  for (int y = std::max(0, y0); y < std::min(im.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(im.width, x1); ++x)
      im.pixels[static_cast<size_t>(y) * im.width + x] = c;
}

void drawText(Image& im, int x, int y, const std::string& text, uint32_t c, int scale) {
  static char buffer[99999];
  int quads =
      stb_easy_font_print(0, 0, const_cast<char*>(text.c_str()), nullptr, buffer, sizeof buffer);
  const float* v = reinterpret_cast<const float*>(buffer);
  for (int q = 0; q < quads; ++q) {
    const float* p = v + q * 16;  // 4 vertices of (x, y, z, colour)
    fillRect(im, x + scale * static_cast<int>(p[0]), y + scale * static_cast<int>(p[1]),
             x + scale * static_cast<int>(p[8]), y + scale * static_cast<int>(p[9]), c);
  }
}

}  // namespace gvdp::detail
