// The order of a first pass's blocks of tiles (sched/tile_order.h): every pixel once in any order,
// the last frame's costs moved with the camera's turn, and the CUDA sort most costly first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "gvdp/sched/tile_order.h"
#include "test_util.h"
#if GVDP_HAS_CUDA
#include "gvdp/sched/tile_order_cuda.h"
#endif

namespace gvdp::detail {
namespace {

FrameSetup frameOfSize(int width, int height) {
  SequenceOptions o;
  o.width = width;
  o.height = height;
  return frameOf(o, 3);
}

// Every pixel of the frame exactly once over the items, whatever the order.
void expectEveryPixelOnce(const FrameSetup& f, const TileOrder& t) {
  std::vector<int> seen(static_cast<size_t>(f.pixelCount()), 0);
  for (int i = 0; i < orderedItemCount(f); ++i) {
    int p = orderedPixel(f, t, i);
    if (p < 0) continue;
    ASSERT_LT(p, f.pixelCount());
    ++seen[static_cast<size_t>(p)];
    EXPECT_EQ(blockOfPixel(f, p), orderedBlock(t, i)) << "item " << i;
  }
  for (size_t p = 0; p < seen.size(); ++p) ASSERT_EQ(seen[p], 1) << "pixel " << p;
  EXPECT_EQ(orderedPixel(f, t, orderedItemCount(f)), -1);
  EXPECT_EQ(orderedPixel(f, t, -1), -1);
}

TEST(TileOrder, EveryPixelOnceRowMajorOrPermuted) {
  for (auto [w, h] : {std::pair{75, 41}, {1, 1}, {32, 32}, {33, 64}, {150, 100}}) {
    FrameSetup f = frameOfSize(w, h);
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    expectEveryPixelOnce(f, {});
    std::vector<uint32_t> order(static_cast<size_t>(orderBlockCount(f)));
    std::iota(order.begin(), order.end(), 0u);
    std::reverse(order.begin(), order.end());
    std::rotate(order.begin(), order.begin() + static_cast<long>(order.size() / 3), order.end());
    expectEveryPixelOnce(f, {order.data(), nullptr});
  }
}

TEST(TileOrder, CostKeysRiseEightStepsAnOctave) {
  EXPECT_EQ(blockCostKey(0), 0u);
  EXPECT_EQ(blockCostKey(1), 0u);
  uint32_t last = 0;
  for (uint64_t c = 1; c <= 0xffffffffu; c = c * 3 / 2 + 1) {
    uint32_t k = blockCostKey(static_cast<uint32_t>(c));
    EXPECT_GE(k, last) << c;
    last = k;
  }
  EXPECT_EQ(blockCostKey(1u << 20), 160u);
  EXPECT_EQ(blockCostKey(1u << 21), 168u);
  EXPECT_EQ(blockCostKey(0xffffffffu), 255u);
}

TEST(TileOrder, ANeighbourhoodsCostIsItsLargest) {
  FrameSetup f = frameOfSize(150, 100);  // 5 x 4 blocks
  ASSERT_EQ(orderBlocksX(f), 5);
  ASSERT_EQ(orderBlockCount(f), 20);
  std::vector<uint32_t> cost(20, 1);
  cost[7] = 50;  // (2, 1)
  cost[19] = 9;  // (4, 3), a corner
  for (int b = 0; b < 20; ++b) {
    int x = b % 5, y = b / 5;
    uint32_t want = std::abs(x - 2) <= 1 && std::abs(y - 1) <= 1 ? 50 : x >= 3 && y >= 2 ? 9 : 1;
    EXPECT_EQ(neighbourhoodCost(cost.data(), f, b), want) << b;
  }
}

float angleBetween(Vec3f a, Vec3f b) {
  return std::acos(std::min(1.0f, dot(a, b)));
}

Vec3f rotateAboutY(Vec3f v, float a) {
  return {v.x * std::cos(a) + v.z * std::sin(a), v.y, -v.x * std::sin(a) + v.z * std::cos(a)};
}

TEST(TileOrder, ReprojectedBlocksFollowTheCamerasTurn) {
  FrameSetup before = frameOfSize(300, 200);
  const int n = orderBlockCount(before), side = TILE * ORDER_BLOCK;
  for (int b = 0; b < n; ++b) EXPECT_EQ(reprojectedBlock(before, before, b), b);
  // Turned by about two blocks: a block that `before` saw, seen at the same direction within a
  // block's angle; one now outside its view maps to its edge.
  const float blockAngle = 2.0f * before.tanHalfFov * side / static_cast<float>(before.width);
  FrameSetup now = before;
  now.basis = {rotateAboutY(before.basis.forward, 2 * blockAngle),
               rotateAboutY(before.basis.right, 2 * blockAngle),
               rotateAboutY(before.basis.up, 2 * blockAngle)};
  auto centre = [&](const FrameSetup& f, int b) {
    int x = std::min(b % orderBlocksX(f) * side + side / 2, f.width - 1);
    int y = std::min(b / orderBlocksX(f) * side + side / 2, f.height - 1);
    return f.primaryRay(x, y).d;
  };
  int moved = 0;
  for (int b = 0; b < n; ++b) {
    int r = reprojectedBlock(now, before, b);
    ASSERT_GE(r, 0);
    ASSERT_LT(r, n);
    moved += r != b;
    if (b % orderBlocksX(now) >= 2 && b % orderBlocksX(now) < orderBlocksX(now) - 2) {
      EXPECT_LT(angleBetween(centre(now, b), centre(before, r)), 1.5f * blockAngle) << b;
    }
  }
  EXPECT_GT(moved, n / 2);
}

#if GVDP_HAS_CUDA
TEST(TileOrderCuda, SortsTheLastFramesBlocksMostCostlyFirst) {
  GVDP_REQUIRE_GPU();
  FrameSetup f = frameOfSize(300, 200);
  const size_t n = static_cast<size_t>(orderBlockCount(f));
  OwnedGpuStream stream(createGpuStream());
  TileOrderCuda orders;
  TileOrder first = orders.next(f, stream.get());
  EXPECT_EQ(first.order, nullptr);  // nothing measured yet: row-major
  ASSERT_NE(first.cost, nullptr);
  std::vector<uint32_t> cost(n);
  for (size_t b = 0; b < n; ++b) cost[b] = static_cast<uint32_t>(1000 + (b * 7919) % 5000) << 8;
  ASSERT_EQ(orderBlocksX(f), 10);
  const int quiet = 3 * 10 + 5;  // a block no ray measured, nor any around it
  for (int y = 2; y <= 4; ++y)
    for (int x = 4; x <= 6; ++x) cost[static_cast<size_t>(y * 10 + x)] = 0;
  writeDevice(first.cost, cost.data(), n * sizeof(uint32_t), stream.get());
  TileOrder second = orders.next(f, stream.get());
  ASSERT_NE(second.order, nullptr);
  std::vector<uint32_t> order(n), fresh(n);
  readDevice(order.data(), second.order, n * sizeof(uint32_t), stream.get());
  readDevice(fresh.data(), second.cost, n * sizeof(uint32_t), stream.get());
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);  // a permutation
  for (size_t i = 1; i < n; ++i) {
    auto key = [&](uint32_t block) {  // the same frame again: no turn to follow
      return blockCostKey(neighbourhoodCost(cost.data(), f, static_cast<int>(block)));
    };
    uint32_t a = key(order[i - 1]), b = key(order[i]);
    ASSERT_GE(a, b) << i;
    if (a == b) {
      EXPECT_LT(order[i - 1], order[i]) << i;  // stable: row-major among equals
    }
  }
  EXPECT_EQ(order.back(), static_cast<uint32_t>(quiet));
  EXPECT_TRUE(std::all_of(fresh.begin(), fresh.end(), [](uint32_t c) { return c == 0; }));
  // Another size: row-major again.
  EXPECT_EQ(orders.next(frameOfSize(200, 300), stream.get()).order, nullptr);
}

// The order of the bench's frame and of larger ones: each of the sort's 32 warps takes runs of
// more than 32 blocks, and most keys are shared by many blocks.
TEST(TileOrderCuda, OrdersLargeFramesAsAStableSortDoes) {
  GVDP_REQUIRE_GPU();
  OwnedGpuStream stream(createGpuStream());
  for (auto [w, h] : {std::pair{1500, 1000}, std::pair{3000, 2000}, std::pair{7680, 4320}}) {
    FrameSetup f = frameOfSize(w, h);
    const size_t n = static_cast<size_t>(orderBlockCount(f));
    TileOrderCuda orders;
    TileOrder first = orders.next(f, stream.get());
    std::vector<uint32_t> cost(n);
    for (size_t b = 0; b < n; ++b) cost[b] = b % 11 == 0 ? 0u : 1u << (b * 2654435761u % 29u);
    writeDevice(first.cost, cost.data(), n * sizeof(uint32_t), stream.get());
    TileOrder second = orders.next(f, stream.get());
    ASSERT_NE(second.order, nullptr);
    std::vector<uint32_t> order(n), expected(n);
    readDevice(order.data(), second.order, n * sizeof(uint32_t), stream.get());
    std::vector<uint32_t> key(n);
    for (size_t b = 0; b < n; ++b)
      key[b] = blockCostKey(neighbourhoodCost(cost.data(), f, static_cast<int>(b)));
    std::iota(expected.begin(), expected.end(), 0u);
    std::stable_sort(expected.begin(), expected.end(),
                     [&](uint32_t a, uint32_t b) { return key[a] > key[b]; });
    EXPECT_EQ(order, expected) << w << "x" << h << ", " << n << " blocks";
  }
}
#endif

}  // namespace
}  // namespace gvdp::detail
