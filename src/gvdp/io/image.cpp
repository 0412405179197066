#include "gvdp/io/image.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "gvdp/base/error.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace gvdp {

void writePng(const Image& image, const std::string& path) {
  GVDP_CHECK(image.width > 0 && image.height > 0, "empty image");
  int ok = stbi_write_png(path.c_str(), image.width, image.height, 4, image.pixels.data(),
                          image.width * 4);
  GVDP_INPUT_CHECK(ok != 0, "cannot write '", path, "'");
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  GVDP_INPUT_CHECK(data != nullptr, "cannot read PNG '", path, "': ", stbi_failure_reason());
  Image image(w, h);
  std::memcpy(image.pixels.data(), data, static_cast<size_t>(w) * h * 4);
  stbi_image_free(data);
  return image;
}

double psnr(const Image& a, const Image& b) {
  GVDP_CHECK(a.width == b.width && a.height == b.height, "image sizes differ");
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double d = static_cast<double>((a.pixels[i] >> (8 * c)) & 255u) -
                 static_cast<double>((b.pixels[i] >> (8 * c)) & 255u);
      sum += d * d;
    }
  if (sum == 0.0) return std::numeric_limits<double>::infinity();
  double mse = sum / (3.0 * static_cast<double>(a.pixels.size()));
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace gvdp
