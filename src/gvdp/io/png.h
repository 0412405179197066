// PNG files of images (stb).
#pragma once

#include <string>

#include "gvdp/base/image.h"

namespace gvdp::detail {

void writePng(const Image& image, const std::string& path);  // throws InputError if unwritable
Image readPng(const std::string& path);                      // throws InputError

}  // namespace gvdp::detail
