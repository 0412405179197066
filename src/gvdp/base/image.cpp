#include "gvdp/base/image.h"

#include <cmath>
#include <limits>

#include "gvdp/base/error.h"

namespace gvdp::detail {

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

}  // namespace gvdp::detail
