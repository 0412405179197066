#include "gvdp/io/png.h"

#include <cstring>

#include "gvdp/base/error.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace gvdp::detail {

void writePng(const Image& image, const std::string& path) {
  GVDP_CHECK(image.width > 0 && image.height > 0, "empty image");
  int ok = stbi_write_png(path.c_str(), image.width, image.height, 4, image.pixels.data(),
                          image.width * 4);
  GVDP_INPUT_CHECK(ok != 0, "cannot write '", path, "'");
}

std::string encodePng(const Image& image) {
  GVDP_CHECK(image.width > 0 && image.height > 0, "empty image");
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  int ok = stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.pixels.data(),
                                  image.width * 4);
  GVDP_CHECK(ok != 0, "PNG encoding failed");
  return bytes;
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

}  // namespace gvdp::detail
