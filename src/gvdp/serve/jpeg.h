// JPEG files of images, through libjpeg-turbo's TurboJPEG API: what `gvdp serve` streams.
#pragma once

#include <string>

#include "gvdp/base/image.h"

namespace gvdp::detail {

// An encoder holds libjpeg-turbo's state between images; one per thread.
class JpegEncoder {
 public:
  JpegEncoder();
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;
  ~JpegEncoder();
  // The bytes of a baseline JPEG, 4:2:0 chroma, quality 1..100.
  std::string encode(const Image& image, int quality);
  // The same of width x height RGBA8 pixels (rows packed).
  std::string encode(const uint32_t* pixels, int width, int height, int quality);

 private:
  void* handle_;
};

// Decodes a JPEG into RGBA8 (alpha 255); throws InputError for bytes that are not one.
Image decodeJpeg(const std::string& bytes);

}  // namespace gvdp::detail
