#include "gvdp/serve/jpeg.h"

#include <turbojpeg.h>

#include "gvdp/base/error.h"

namespace gvdp::detail {

JpegEncoder::JpegEncoder() : handle_(tjInitCompress()) {
  GVDP_CHECK(handle_ != nullptr, "tjInitCompress failed");
}

JpegEncoder::~JpegEncoder() {
  tjDestroy(handle_);
}

std::string JpegEncoder::encode(const Image& image, int quality) {
  GVDP_CHECK(image.pixels.size() == static_cast<size_t>(image.width) * image.height, "bad image");
  return encode(image.pixels.data(), image.width, image.height, quality);
}

std::string JpegEncoder::encode(const uint32_t* pixels, int width, int height, int quality) {
  GVDP_CHECK(width > 0 && height > 0, "empty image");
  GVDP_CHECK(quality >= 1 && quality <= 100, "bad JPEG quality ", quality);
  unsigned char* data = nullptr;
  unsigned long size = 0;
  int rc = tjCompress2(handle_, reinterpret_cast<const unsigned char*>(pixels), width, 0, height,
                       TJPF_RGBX, &data, &size, TJSAMP_420, quality, TJFLAG_FASTDCT);
  if (rc != 0) {
    tjFree(data);
    throw Error(concat("JPEG encoding failed: ", tjGetErrorStr2(handle_)));
  }
  std::string bytes(reinterpret_cast<const char*>(data), size);
  tjFree(data);
  return bytes;
}

Image decodeJpeg(const std::string& bytes) {
  tjhandle handle = tjInitDecompress();
  GVDP_CHECK(handle != nullptr, "tjInitDecompress failed");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  int rc =
      tjDecompressHeader3(handle, data, bytes.size(), &width, &height, &subsampling, &colorspace);
  Image image;
  if (rc == 0 && width > 0 && height > 0 && width <= 65535 && height <= 65535) {
    image = Image(width, height);
    rc = tjDecompress2(handle, data, bytes.size(),
                       reinterpret_cast<unsigned char*>(image.pixels.data()), width, 0, height,
                       TJPF_RGBA, 0);
  } else {
    rc = -1;
  }
  std::string why = rc == 0 ? "" : tjGetErrorStr2(handle);
  tjDestroy(handle);
  GVDP_INPUT_CHECK(rc == 0, "not a JPEG image (", why, ")");
  return image;
}

}  // namespace gvdp::detail
