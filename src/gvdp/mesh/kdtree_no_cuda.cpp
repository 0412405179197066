// The GPU kd-tree builder's stand-in in builds without CUDA (GVDP_CUDA=OFF).
#include "gvdp/base/error.h"
#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {

KdTree buildKdTreeCuda(const Mesh&, KdBuildPhases*) {
  throw InputError("the GPU kd-tree builder is unavailable: this gvdp was built without CUDA");
}

}  // namespace gvdp::detail
