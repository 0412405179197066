// PNG files: written here with zlib, strips of rows filtered and deflated in parallel on the
// thread pool (pigz's scheme: each strip a raw deflate stream ended by a sync flush, the last
// by the final block; one zlib header, the Adler-32s combined), read with stb. stb's writer,
// single-threaded with its own deflate, took 31 s for a 16384x16384 still (BENCHMARKS.md).
#include "gvdp/io/png.h"

#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "gvdp/base/error.h"
#include "gvdp/base/parallel.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace gvdp::detail {

namespace {

constexpr int BYTES_PER_PIXEL = 4;
constexpr int64_t STRIP_BYTES = 4 << 20;  // raw bytes a strip deflates (about 10 ms each)
constexpr int PNG_LEVEL = 3;  // zlib: 3.0x faster than 6, files 9% larger (a forest frame)

int paethPredictor(int a, int b, int c) {
  int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// One row filtered with the filter type of the least sum of absolute differences (the PNG
// specification's heuristic): out = type byte + the row.
void filterRow(const uint8_t* row, const uint8_t* above, int bytes, uint8_t* out,
               std::vector<uint8_t>& trial) {
  trial.resize(static_cast<size_t>(bytes));
  uint64_t best = ~uint64_t{0};
  for (int type = 0; type < 5; ++type) {
    uint64_t cost = 0;
    for (int i = 0; i < bytes; ++i) {
      int a = i >= BYTES_PER_PIXEL ? row[i - BYTES_PER_PIXEL] : 0;
      int b = above ? above[i] : 0;
      int c = above && i >= BYTES_PER_PIXEL ? above[i - BYTES_PER_PIXEL] : 0;
      int pred = type == 0   ? 0
                 : type == 1 ? a
                 : type == 2 ? b
                 : type == 3 ? (a + b) / 2
                             : paethPredictor(a, b, c);
      auto v = static_cast<uint8_t>(row[i] - pred);
      trial[static_cast<size_t>(i)] = v;
      cost += static_cast<uint64_t>(v < 128 ? v : 256 - v);
    }
    if (cost < best) {
      best = cost;
      out[0] = static_cast<uint8_t>(type);
      std::memcpy(out + 1, trial.data(), static_cast<size_t>(bytes));
    }
  }
}

struct Strip {
  std::vector<uint8_t> deflated;
  uLong adler = 1;
  uLong rawBytes = 0;
};

Strip deflateStrip(const Image& image, int y0, int y1, bool last) {
  int bytes = image.width * BYTES_PER_PIXEL;
  auto* pixels = reinterpret_cast<const uint8_t*>(image.pixels.data());
  std::vector<uint8_t> raw(static_cast<size_t>(y1 - y0) * (bytes + 1)), trial;
  for (int y = y0; y < y1; ++y)
    filterRow(pixels + static_cast<size_t>(y) * bytes,
              y > 0 ? pixels + static_cast<size_t>(y - 1) * bytes : nullptr, bytes,
              raw.data() + static_cast<size_t>(y - y0) * (bytes + 1), trial);
  Strip s;
  s.rawBytes = static_cast<uLong>(raw.size());
  s.adler = adler32(1, raw.data(), static_cast<uInt>(raw.size()));
  z_stream z{};
  GVDP_CHECK(deflateInit2(&z, PNG_LEVEL, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK,
             "deflateInit2 failed");
  s.deflated.resize(deflateBound(&z, static_cast<uLong>(raw.size())) + 16);
  z.next_in = raw.data();
  z.avail_in = static_cast<uInt>(raw.size());
  z.next_out = s.deflated.data();
  z.avail_out = static_cast<uInt>(s.deflated.size());
  int rc = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  GVDP_CHECK(rc == (last ? Z_STREAM_END : Z_OK) && z.avail_in == 0, "deflate failed: ", rc);
  s.deflated.resize(s.deflated.size() - z.avail_out);
  deflateEnd(&z);
  return s;
}

void putU32(std::string& out, uint32_t v) {
  const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 8), static_cast<char>(v)};
  out.append(b, 4);
}

void putChunk(std::string& out, const char* type, const uint8_t* data, size_t size) {
  putU32(out, static_cast<uint32_t>(size));
  size_t at = out.size();
  out.append(type, 4);
  out.append(reinterpret_cast<const char*>(data), size);
  uLong crc = crc32(0, reinterpret_cast<const Bytef*>(out.data() + at), 4);
  if (size > 0) crc = crc32(crc, data, static_cast<uInt>(size));  // (a null buffer resets it)
  putU32(out, static_cast<uint32_t>(crc));
}

}  // namespace

std::string encodePng(const Image& image) {
  GVDP_CHECK(image.width > 0 && image.height > 0, "empty image");
  int64_t rowBytes = int64_t{image.width} * BYTES_PER_PIXEL + 1;
  int rowsPerStrip = static_cast<int>(std::max<int64_t>(1, STRIP_BYTES / rowBytes));
  int strips = (image.height + rowsPerStrip - 1) / rowsPerStrip;
  std::vector<Strip> parts(static_cast<size_t>(strips));
  parallelFor(strips, [&](int64_t i) {
    int y0 = static_cast<int>(i) * rowsPerStrip;
    int y1 = std::min(image.height, y0 + rowsPerStrip);
    parts[static_cast<size_t>(i)] = deflateStrip(image, y0, y1, i == strips - 1);
  });
  std::string out("\x89PNG\r\n\x1a\n", 8);
  uint8_t header[13] = {};
  for (int i = 0; i < 4; ++i) {
    header[i] = static_cast<uint8_t>(image.width >> (24 - 8 * i));
    header[4 + i] = static_cast<uint8_t>(image.height >> (24 - 8 * i));
  }
  header[8] = 8;  // bits per channel
  header[9] = 6;  // RGBA
  putChunk(out, "IHDR", header, sizeof header);
  // The zlib stream: header, the strips' deflate streams, the Adler-32 of all raw bytes. Each
  // strip is its own IDAT chunk (a decoder concatenates them).
  uLong adler = 1;
  for (const Strip& s : parts) adler = adler32_combine(adler, s.adler, s.rawBytes);
  const uint8_t zlibHeader[2] = {0x78, 0x5e};  // deflate, 32K window, level 2-5, check bits
  putChunk(out, "IDAT", zlibHeader, 2);
  for (const Strip& s : parts) putChunk(out, "IDAT", s.deflated.data(), s.deflated.size());
  const uint8_t trailer[4] = {static_cast<uint8_t>(adler >> 24), static_cast<uint8_t>(adler >> 16),
                              static_cast<uint8_t>(adler >> 8), static_cast<uint8_t>(adler)};
  putChunk(out, "IDAT", trailer, 4);
  putChunk(out, "IEND", nullptr, 0);
  return out;
}

void writePng(const Image& image, const std::string& path) {
  std::string bytes = encodePng(image);
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
  GVDP_INPUT_CHECK(f != nullptr, "cannot write '", path, "'");
  bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f.get()) == bytes.size();
  ok = std::fclose(f.release()) == 0 && ok;
  GVDP_INPUT_CHECK(ok, "cannot write '", path, "'");
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
