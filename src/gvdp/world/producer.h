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
//   float voxelSize0() const    the voxel size of level 0 (the finest), in world units.
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

}  // namespace gvdp::detail
