#include <gtest/gtest.h>
#include <zlib.h>

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

// Several strips deflated in parallel (4 MB of raw rows each), every filter type chosen by some
// row (gradients, flat runs, noise): the stream stb decodes is the image, bit for bit.
TEST(Image, PngOfManyStripsRoundTripsExactly) {
  Image a(1500, 1100);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      uint32_t v = y % 3 == 0   ? static_cast<uint32_t>(x * 7 + y)
                   : y % 3 == 1 ? 0x80402010u
                                : static_cast<uint32_t>((x * 2654435761u) ^ (y * 40503u));
      a.pixels[static_cast<size_t>(y) * a.width + x] = v;
    }
  std::string png = encodePng(a);
  EXPECT_LT(png.size(), a.pixels.size() * 4);
  // Every chunk's CRC (stb does not check them): length, type, data, CRC of type + data.
  auto u32 = [&](size_t at) {
    auto b = [&](size_t k) { return static_cast<uint32_t>(static_cast<uint8_t>(png[at + k])); };
    return b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
  };
  int chunks = 0;
  for (size_t at = 8; at < png.size(); ++chunks) {
    uint32_t n = u32(at);
    ASSERT_LE(at + 12 + n, png.size());
    uLong crc = crc32(0, reinterpret_cast<const Bytef*>(png.data() + at + 4), n + 4);
    EXPECT_EQ(crc, u32(at + 8 + n)) << "chunk " << png.substr(at + 4, 4);
    at += 12 + n;
  }
  EXPECT_GE(chunks, 5);  // IHDR, the zlib header, two strips, the checksum, IEND
  std::string path = test::tempDir("png-strips") + ".png";
  writePng(a, path);
  Image b = readPng(path);
  ASSERT_EQ(b.width, a.width);
  ASSERT_EQ(b.height, a.height);
  EXPECT_EQ(a.pixels, b.pixels);
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
