// The brick pool as seen by the ray march and by production, on both backends: slots of 10^3
// RGBA8 samples (8^3 voxels and a one-voxel border, so that filtering is seamless across brick
// edges), slot-major, read through the shared software trilinear().
//
// Why not a 3D texture with hardware filtering (paper 3.2): under dp and pt, bricks are written
// while other grids or blocks of the same frame read the pool, and the texture cache is coherent
// only at grid boundaries; a plain array read with plain loads after an acquire of the brick's
// entry (or of an earlier frame's: cache/cached_access.h) follows the memory model, and every
// scheduler - and the CPU - then interpolates with the same arithmetic, bit for bit. Where the
// pool cannot change while the reading kernel runs (sp, graph: PoolReads::ReadOnly), the same
// array is read through the non-coherent path (ld.global.nc).
#pragma once

#include "gvdp/render/trilinear.h"

namespace gvdp::detail {

// A resident brick's occupancy: 4^3 cells of 2^3 voxels, bit x + 4 y + 16 z set when some sample
// that trilinear() may read for a position in the cell (the cell's voxels and one more on each
// side: sample indices 2c..2c+3 per axis) is not zero. A position in a clear cell samples zero
// exactly, so the march need not read the brick there (cache/cached_access.h).
constexpr int OCCUPANCY_CELLS = 4;  // per axis

// The cell, along one axis, of a position a in voxel units from the brick's origin, clamped: a
// position on a face (a = 0 or 8, within rounding) reads samples of the cell it is clamped to.
GVDP_HD GVDP_INLINE int occupancyCell(float a) {
  int c = static_cast<int>(floorf(a * 0.5f));
  return c < 0 ? 0 : c > OCCUPANCY_CELLS - 1 ? OCCUPANCY_CELLS - 1 : c;
}

// Cells lo..hi along one axis, as a 4-bit mask.
GVDP_HD GVDP_INLINE uint32_t occupancyAxisRange(int lo, int hi) {
  return (2u << hi) - (1u << lo);
}

// The cells of a box, from a 4-bit mask per axis: the outer product of the three (x in a row of
// 4 bits, y rows 4 bits apart, z planes 16 apart), two products, since the spread fields never
// overlap.
GVDP_HD GVDP_INLINE uint64_t occupancyBox(uint32_t x, uint32_t y, uint32_t z) {
  uint32_t ySpread = (y & 1u) | (y & 2u) << 3 | (y & 4u) << 6 | (y & 8u) << 9;
  uint64_t zSpread =
      uint64_t{z & 1u} | uint64_t{z & 2u} << 15 | uint64_t{z & 4u} << 30 | uint64_t{z & 8u} << 45;
  return uint64_t{x * ySpread} * zSpread;
}

// The cell whose samples hold the 2x2x2 block trilinear() reads from sample index j on (0..8 per
// axis, of the 10^3 with the border): cell c holds samples 2c..2c+3, so min(j, 7) / 2 holds j and
// j + 1. A sample whose block lies in a clear cell is zero, wherever its position lies in the
// cell; the test reuses the index the read needs anyway (BrickPool::sample).
GVDP_HD GVDP_INLINE uint64_t occupancyBitOfBlock(Vec3i j) {
  auto cell = [](int i) { return (i < 7 ? i : 7) >> 1; };
  return uint64_t{1} << (cell(j.x) + OCCUPANCY_CELLS * (cell(j.y) + OCCUPANCY_CELLS * cell(j.z)));
}

// The cells of the box from the cell of a to the cell of b (positions in voxel units from the
// brick's origin, cells by occupancyCell): it holds the cell of every position on the segment
// between them, the cell being monotone in each coordinate; (a, a) is a's cell alone. The
// clear-brick test (render/march.h); a sample tests its block's cell (occupancyBitOfBlock).
GVDP_HD GVDP_INLINE uint64_t occupancyCellsBetween(Vec3f a, Vec3f b) {
  auto axis = [](float p, float q) {
    int cp = occupancyCell(p), cq = occupancyCell(q);
    return cp < cq ? occupancyAxisRange(cp, cq) : occupancyAxisRange(cq, cp);
  };
  return occupancyBox(axis(a.x, b.x), axis(a.y, b.y), axis(a.z, b.z));
}

// The cells whose reads include sample (x, y, z) (indices 0..9 of the 10^3 with the border):
// along an axis, cells max(0, (i - 2) / 2) to min(3, i / 2). No branch: production ORs this for
// every nonzero sample, lanes of a warp at different indices.
GVDP_HD GVDP_INLINE uint32_t occupancyAxisCells(int i) {
  return occupancyAxisRange(i < 2 ? 0 : (i - 2) >> 1, i > 7 ? OCCUPANCY_CELLS - 1 : i >> 1);
}
GVDP_HD GVDP_INLINE uint64_t occupancyCellsOf(Vec3i i) {
  return occupancyBox(occupancyAxisCells(i.x), occupancyAxisCells(i.y), occupancyAxisCells(i.z));
}

// How a kernel may read the pool (and the entries that lead to it, cache/cached_access.h).
enum class PoolReads : uint8_t {
  Coherent,  // bricks are published while the kernel runs (dp, pt): plain loads
  ReadOnly,  // every brick it can find was written before it began (sp, graph): ld.global.nc
};

struct BrickPool {
  Rgba8* texels;        // slot * BRICK_SAMPLE_COUNT + (z * 10 + y) * 10 + x
  uint64_t* occupancy;  // per slot (cells, above), written with the samples, before the entry

  template <PoolReads READS, class T>
  GVDP_HD static T load(const T* p) {
#if GVDP_IS_GPU_CODE
    if constexpr (READS == PoolReads::ReadOnly) return __ldg(p);
#endif
    return *p;
  }

  // v: voxel coordinates of the brick's level (local); origin = 8 * local brick coordinates. A
  // sample whose block lies in a clear cell of `cells` (the slot's occupancy) is zero without a
  // read (the eight samples are), tested with the block's own index. One address for the eight
  // voxels, read at constant offsets from it: the loads carry the offsets. An address per voxel
  // (64-bit arithmetic each) took 45 of the 213 instructions of a sample in sp's render kernel;
  // without them, forest's floor fell 8% (BENCHMARKS.md, session 15).
  template <PoolReads READS = PoolReads::Coherent>
  GVDP_HD Vec4f sample(uint32_t slot, Vec3i origin, Vec3f v, uint64_t cells = ~uint64_t{0}) const {
    TrilinearSite s = trilinearSite(v);
    Vec3i j{s.first.x - origin.x + 1, s.first.y - origin.y + 1, s.first.z - origin.z + 1};
    if (!(cells & occupancyBitOfBlock(j))) return {0.0f, 0.0f, 0.0f, 0.0f};
    const Rgba8* first = texels + static_cast<size_t>(slot) * BRICK_SAMPLE_COUNT +
                         (j.z * BRICK_SAMPLES + j.y) * BRICK_SAMPLES + j.x;
    return interpolate(s, [first](int dx, int dy, int dz) {
      return load<READS>(first + (dz * BRICK_SAMPLES + dy) * BRICK_SAMPLES + dx);
    });
  }

  template <PoolReads READS = PoolReads::Coherent>
  GVDP_HD uint64_t loadOccupancy(uint32_t slot) const {
    return load<READS>(reinterpret_cast<const unsigned long long*>(occupancy + slot));
  }

  GVDP_HD void write(uint32_t slot, int sample, Rgba8 value) const {
    texels[static_cast<size_t>(slot) * BRICK_SAMPLE_COUNT + sample] = value;
  }
};

}  // namespace gvdp::detail
