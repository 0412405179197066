// RGBA8 images on the host, what every renderer delivers, and PSNR for comparing renders
// (files: io/png.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gvdp::detail {

struct Image {
  int width = 0, height = 0;
  std::vector<uint32_t> pixels;  // RGBA8, bytes r, g, b, a in memory order

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, 0u) {}
};

// Peak signal-to-noise ratio over the RGB channels, in dB (infinity when identical).
double psnr(const Image& a, const Image& b);

}  // namespace gvdp::detail
