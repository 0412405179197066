// What you write to bring your own world (the contract: gvdp/world/producer.h): a trivially
// copyable type with voxel(), emptyBox() and voxelSize0() (and optionally emptyBoxPart() and
// boundSplit()), GVDP_HD so that both backends run it, built from the helpers here (vectors,
// RGBA8 voxels with baked shading, coverage).
#pragma once

#include "gvdp/base/defs.h"
#include "gvdp/base/vecmath.h"
#include "gvdp/world/producer.h"
#include "gvdp/world/voxel.h"

namespace gvdp {

// What a producer is made of; operators on the vectors are found by argument-dependent lookup.
using detail::bakeShading;
using detail::clamp01;
using detail::coverage;
using detail::cross;
using detail::dot;
using detail::EMPTY_MARGIN_VOXELS;
using detail::length;
using detail::lerp;
using detail::makeVoxel;
using detail::normalize;
using detail::packRgba8;
using detail::PI;
using detail::Producer;
using detail::Rgba8;
using detail::smoothstep;
using detail::toDouble;
using detail::toFloat;
using detail::Vec3d;
using detail::Vec3f;
using detail::Vec3i;
using detail::VoxelSample;

}  // namespace gvdp
