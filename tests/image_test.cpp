#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "gvdp/base/error.h"
#include "gvdp/io/png.h"
#include "test_util.h"

namespace gvdp::detail {

TEST(Image, PngRoundTripIsExact) {
  Image a(37, 21);
  for (size_t i = 0; i < a.pixels.size(); ++i)
    a.pixels[i] = static_cast<uint32_t>(i * 2654435761u) | 0xff000000u;
  std::string path = test::tempDir("png") + ".png";
  writePng(a, path);
  Image b = readPng(path);
  ASSERT_EQ(b.width, 37);
  ASSERT_EQ(b.height, 21);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_TRUE(std::isinf(psnr(a, b)));
  std::filesystem::remove(path);
}

TEST(Image, PsnrOfAKnownError) {
  Image a(10, 10), b(10, 10);
  for (auto& p : b.pixels) p = 0x000a0a0au;  // every channel off by 10
  EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / 100.0), 1e-9);
}

TEST(Image, UnreadableOrUnwritableFilesAreInputErrors) {
  EXPECT_THROW(readPng("/nonexistent/x.png"), InputError);
  EXPECT_THROW(writePng(Image(4, 4), "/nonexistent/dir/x.png"), InputError);
}

}  // namespace gvdp::detail
