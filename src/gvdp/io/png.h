// PNG files of images: written with zlib in parallel strips, read with stb.
#pragma once

#include <string>

#include "gvdp/base/image.h"

namespace gvdp::detail {

void writePng(const Image& image, const std::string& path);  // throws InputError if unwritable
Image readPng(const std::string& path);                      // throws InputError
std::string encodePng(const Image& image);                   // the bytes of a PNG file

}  // namespace gvdp::detail
