// What you write to bring your own world (the contract: gvdp/world/producer.h): a trivially
// copyable type with voxel(), emptyBox() and voxelSize0(), GVDP_HD so that both backends run
// it, built from the helpers here (vectors, RGBA8 voxels with baked shading, coverage).
#pragma once

#include "gvdp/base/defs.h"
#include "gvdp/base/vecmath.h"
#include "gvdp/world/producer.h"
#include "gvdp/world/voxel.h"
