// Drawing on RGBA8 images for the pictures gvdp writes (timelines, ray-cost maps): filled
// rectangles and one-line text (stb_easy_font).
#pragma once

#include <cstdint>
#include <string>

#include "gvdp/base/image.h"

namespace gvdp::detail {

constexpr uint32_t rgb(int r, int g, int b) {
  return 0xff000000u | static_cast<uint32_t>(b) << 16 | static_cast<uint32_t>(g) << 8 |
         static_cast<uint32_t>(r);
}

// Fills [x0, x1) x [y0, y1), clipped to the image.
void fillRect(Image& im, int x0, int y0, int x1, int y1, uint32_t c);
// `text` with its top left at (x, y), about 6 pixels a character and 7 high, times `scale`.
void drawText(Image& im, int x, int y, const std::string& text, uint32_t c, int scale = 1);

}  // namespace gvdp::detail
