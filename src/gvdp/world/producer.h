// What a world is to gvdp: a producer (paper 3.1, "producer" of voxel data), a small trivially
// copyable type that CPU and GPU both evaluate, with
//   VoxelSample voxel(Vec3d centre, float voxelSize) const    the voxel of this size centred here:
//       RGBA8 premultiplied colour and opacity (world/voxel.h: makeVoxel) and a conservative empty
//       flag: raised only when every voxel of size <= voxelSize / 2 whose centre lies within
//       voxelSize of `centre` has zero opacity (a brick whose samples are all flagged is EMPTY,
//       and skipping it must equal sampling the finer levels);
//   bool emptyBox(Vec3d lo, Vec3d hi, float voxelSize) const   a conservative emptiness bound for
//       a box: true only when voxel(c, v) would flag every centre c of [lo, hi] empty for this v,
//       so a brick whose box it clears is EMPTY without evaluating one voxel (false: no bound);
//   float voxelSize0() const    the voxel size of level 0 (the finest), in world units;
// and optionally
//   bool emptyBoxPart(Vec3d lo, Vec3d hi, float voxelSize, int part, int parts) const
//       emptyBox's bound split into `parts` parts that members of a group test at once: the box
//       is clear when every part says so, and then exactly when emptyBox says so (random-spheres:
//       the cells the box overlaps, strided). Without it, part 0 is the whole bound
//       (emptyBoxPartOf);
//   int boundSplit() const
//       a brick whose box the bound does not clear is tested again as boundSplit()^3 sub-boxes
//       (cache/produce.h: brickBoundedEmpty), EMPTY unevaluated when every one is clear. For
//       bounds that loosen with a box's size (perlin's, fbm's, forest's Taylor and distance
//       bounds: 3 clears 36-82% of the bricks evaluated only to find them EMPTY); without it, 1.
// Both member functions are GVDP_HD (__host__ __device__). The renderer is a template on the
// producer, instantiated where the type is known (include/gvdp/make_renderer.h).
#pragma once

#include <concepts>
#include <type_traits>

#include "gvdp/world/voxel.h"

namespace gvdp::detail {

template <class P>
concept Producer = std::is_trivially_copyable_v<P> &&
    requires(const P& p, Vec3d x, float voxelSize) {
  { p.voxel(x, voxelSize) } -> std::same_as<VoxelSample>;
  { p.emptyBox(x, x, voxelSize) } -> std::same_as<bool>;
  { p.voxelSize0() } -> std::convertible_to<float>;
};

template <class P>
concept SplitBoxBound = requires(const P& p, Vec3d x, float voxelSize, int k) {
  { p.emptyBoxPart(x, x, voxelSize, k, k) } -> std::same_as<bool>;
};

template <class P>
concept RefinedBoxBound = requires(const P& p) {
  { p.boundSplit() } -> std::convertible_to<int>;
};

// The sub-boxes per axis a producer's bound is refined in (above; 1: none).
template <Producer P>
GVDP_HD GVDP_INLINE int boundSplitOf(const P& p) {
  if constexpr (RefinedBoxBound<P>)
    return p.boundSplit();
  else
    return 1;
}

// Part `part` of `parts` of a producer's box bound (above).
template <Producer P>
GVDP_HD GVDP_INLINE bool emptyBoxPartOf(const P& p, Vec3d lo, Vec3d hi, float voxelSize, int part,
                                        int parts) {
  if constexpr (SplitBoxBound<P>)
    return p.emptyBoxPart(lo, hi, voxelSize, part, parts);
  else
    return part != 0 || p.emptyBox(lo, hi, voxelSize);
}

}  // namespace gvdp::detail
