// The quadtree subdivision's CPU side: the sum-mipmap build, the recursive top-down reference
// every GPU method is checked against, the passes a level-synchronous method makes, and the
// GpuQuadtree stand-ins of builds without CUDA.
#include "gvdp/tiles/quadtree.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "gvdp/base/error.h"

namespace gvdp::detail {

int quadtreeLevels(int width, int height) {
  GVDP_INPUT_CHECK(width >= 1 && height >= 1, "importance grid ", width, "x", height, " is empty");
  int side = std::max(width, height), levels = 0;
  while ((int64_t{1} << levels) < side) ++levels;
  GVDP_INPUT_CHECK(levels <= QUADTREE_MAX_LEVELS, "importance grid ", width, "x", height,
                   " is larger than ", 1 << QUADTREE_MAX_LEVELS, " blocks a side");
  return levels;
}

SumMipmap buildSumMipmap(const uint32_t* importance, int width, int height) {
  SumMipmap m;
  m.levels = quadtreeLevels(width, height);
  m.width = width;
  m.height = height;
  m.values.assign(mipmapSize(m.levels), 0);  // the padding stays zero
  uint64_t* finest = m.values.data() + mipmapDepthOffset(m.levels);
  int n = 1 << m.levels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) finest[int64_t{y} * n + x] = importance[int64_t{y} * width + x];
  for (int d = m.levels - 1; d >= 0; --d) {
    uint64_t* out = m.values.data() + mipmapDepthOffset(d);
    const uint64_t* in = m.values.data() + mipmapDepthOffset(d + 1);
    int side = 1 << d;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const uint64_t* c = in + (int64_t{2 * y} << (d + 1)) + 2 * x;
        out[int64_t{y} * side + x] = c[0] + c[1] + c[2 * side] + c[2 * side + 1];
      }
  }
  return m;
}

void checkSubdivisionParams(int width, int height, const SubdivisionParams& p) {
  GVDP_INPUT_CHECK(p.blockPixels >= 1 && p.blockPixels <= (1 << 16), "block of ", p.blockPixels,
                   " pixels: out of range 1..65536");
  GVDP_INPUT_CHECK(p.imageWidth >= 1 && p.imageHeight >= 1, "image of ", p.imageWidth, "x",
                   p.imageHeight, " pixels is empty");
  int64_t bx = (int64_t{p.imageWidth} + p.blockPixels - 1) / p.blockPixels;
  int64_t by = (int64_t{p.imageHeight} + p.blockPixels - 1) / p.blockPixels;
  GVDP_INPUT_CHECK(bx == width && by == height, "image of ", p.imageWidth, "x", p.imageHeight,
                   " pixels in blocks of ", p.blockPixels, " is ", bx, "x", by,
                   " blocks, the importance grid ", width, "x", height);
}

void checkSubdivisionParams(const SumMipmap& m, const SubdivisionParams& p) {
  GVDP_INPUT_CHECK(m.values.size() == mipmapSize(m.levels), "sum-mipmap not built");
  checkSubdivisionParams(m.width, m.height, p);
}

const char* methodName(SubdivisionMethod m) {
  switch (m) {
    case SubdivisionMethod::Cpu:
      return "cpu";
    case SubdivisionMethod::MultiPass:
      return "multipass";
    case SubdivisionMethod::Subtree:
      return "subtree";
    case SubdivisionMethod::Dynamic:
      return "dynamic";
  }
  return "?";
}

std::vector<GpuSubdivision> gpuSubdivisions() {
  std::vector<GpuSubdivision> all{{SubdivisionMethod::MultiPass, 1}};
  for (int l = 1; l <= QUADTREE_MAX_LEVELS_PER_PASS; ++l)
    all.push_back({SubdivisionMethod::Subtree, l});
  if (GVDP_CDP) all.push_back({SubdivisionMethod::Dynamic, 1});
  return all;
}

namespace {

void subdivideNode(const QuadtreeView& q, int depth, int x, int y, std::vector<Tile>& out) {
  NodeDecision n = decideNode(q, depth, x, y);
  if (n.action == NodeAction::Emit) out.push_back({depth, x, y, n.sum, n.overflows});
  if (n.action != NodeAction::Subdivide) return;
  for (int c = 0; c < 4; ++c) subdivideNode(q, depth + 1, 2 * x + (c & 1), 2 * y + (c >> 1), out);
}

}  // namespace

std::vector<Tile> subdivide(const SumMipmap& m, const SubdivisionParams& p,
                            SubdivisionMethod method, int levelsPerPass) {
  checkSubdivisionParams(m, p);
  if (method != SubdivisionMethod::Cpu) {
    GpuQuadtree gpu;
    gpu.uploadMipmap(m, nullptr);
    return gpu.subdivide(p, method, levelsPerPass, nullptr);
  }
  std::vector<Tile> tiles;
  subdivideNode(m.view(p), 0, 0, 0, tiles);
  return tiles;
}

SubdivisionStats plannedPasses(const SumMipmap& m, const SubdivisionParams& p,
                               SubdivisionMethod method, int levelsPerPass) {
  checkSubdivisionParams(m, p);
  if (method == SubdivisionMethod::MultiPass) levelsPerPass = 1;
  GVDP_INPUT_CHECK(levelsPerPass >= 1 && levelsPerPass <= QUADTREE_MAX_LEVELS_PER_PASS,
                   "levels per pass ", levelsPerPass, ": out of range 1..",
                   QUADTREE_MAX_LEVELS_PER_PASS);
  QuadtreeView q = m.view(p);
  SubdivisionStats s;
  // Level by level, the valid nodes whose ancestors all subdivided: the active nodes of a pass
  // that starts at this depth.
  std::vector<std::pair<int, int>> active{{0, 0}}, next;
  for (int depth = 0; !active.empty(); ++depth) {
    // MultiPass decides a level per pass. Subtree starts a pass every L levels, but a pass that
    // reaches depth K decides it too (single blocks never subdivide): none starts at K.
    bool starts = method == SubdivisionMethod::MultiPass ||
                  (method == SubdivisionMethod::Subtree && depth % levelsPerPass == 0 &&
                   (depth < m.levels || depth == 0)) ||
                  (method == SubdivisionMethod::Dynamic && depth == 0);
    if (starts) {
      ++s.passes;
      s.activeNodes.push_back(active.size());
    }
    next.clear();
    for (auto [x, y] : active) {
      if (decideNode(q, depth, x, y).action != NodeAction::Subdivide) continue;
      if (method == SubdivisionMethod::Dynamic) ++s.deviceLaunches;  // one per subdivided node
      for (int c = 0; c < 4; ++c) {
        int cx = 2 * x + (c & 1), cy = 2 * y + (c >> 1);
        if (nodeIsValid(q, depth + 1, cx, cy)) next.emplace_back(cx, cy);
      }
    }
    std::swap(active, next);
  }
  return s;
}

void sortCanonical(std::vector<Tile>& tiles, int levels) {
  // Pixel origins are block origins times blockPixels: the same order.
  auto key = [levels](const Tile& t) {
    int shift = levels - t.depth;
    return std::pair<int64_t, int64_t>{int64_t{t.y} << shift, int64_t{t.x} << shift};
  };
  std::sort(tiles.begin(), tiles.end(),
            [&](const Tile& a, const Tile& b) { return key(a) < key(b); });
}

TileRect tileRect(const Tile& t, int levels, const SubdivisionParams& p) {
  return nodePixelRect(levels, p, t.depth, t.x, t.y);
}

#if !GVDP_HAS_CUDA
// Builds without CUDA: the class exists so that callers compile, and refuses to run.
struct GpuQuadtree::Impl {};
GpuQuadtree::GpuQuadtree() = default;
GpuQuadtree::~GpuQuadtree() = default;
namespace {
[[noreturn]] void noCuda() {
  throw InputError("GPU quadtree subdivision unavailable: this gvdp was built without CUDA");
}
}  // namespace
void GpuQuadtree::upload(const uint32_t*, int, int, GpuStream) {
  noCuda();
}
void GpuQuadtree::buildMipmap(GpuStream) {
  noCuda();
}
void GpuQuadtree::uploadMipmap(const SumMipmap&, GpuStream) {
  noCuda();
}
SumMipmap GpuQuadtree::downloadMipmap(GpuStream) const {
  noCuda();
}
uint64_t GpuQuadtree::run(const SubdivisionParams&, SubdivisionMethod, int, GpuStream,
                          SubdivisionStats*) {
  noCuda();
}
std::vector<Tile> GpuQuadtree::tiles(GpuStream) const {
  noCuda();
}
#endif

}  // namespace gvdp::detail
