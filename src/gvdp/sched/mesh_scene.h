// A mesh world ready to render (world/mesh_world.h): the file read and placed, its kd-tree built
// (on the GPU for the cuda backend, Wald and Havran's sequential builder on the CPU), its
// pseudonormals and its distance hierarchy (mesh_bvh.h), and for the cuda backend all of it on
// the device; the producer kernels of its MeshWorld (instantiated in mesh_scene.cpp, an nvcc
// translation unit in CUDA builds) keep the scene alive as long as a renderer holds them.
#pragma once

#include <memory>
#include <string>

#include "gvdp/base/image.h"
#include "gvdp/mesh/kdtree_build.h"
#include "gvdp/mesh/mesh_bvh.h"
#include "gvdp/mesh/mesh_normals.h"
#include "gvdp/render/frame.h"
#include "gvdp/sched/producer_kernels.h"
#include "gvdp/sched/scheduler.h"
#include "gvdp/world/mesh_world.h"

namespace gvdp::detail {

class MeshScene : public std::enable_shared_from_this<MeshScene> {
 public:
  // Throws InputError naming the file (missing, malformed) or a bad lattice.
  static std::shared_ptr<const MeshScene> load(const std::string& path, float lattice,
                                               Backend backend);
  ~MeshScene();

  // The world over host memory (the CPU backend's, and the reference's).
  MeshWorld hostWorld() const;
  // The producer kernels of the backend it was loaded for.
  ProducerKernelsPtr kernels() const;
  // The reference image of a frame: the ray cast of meshReferencePixel on the CPU thread pool.
  void renderReference(const FrameSetup& frame, Image& out) const;

  const Mesh& mesh() const { return mesh_; }
  const KdTree& tree() const { return tree_; }
  double buildMs() const { return buildMs_; }

  struct Device;  // the cuda backend's copies (mesh_scene.cpp)

 private:
  MeshScene() = default;

  Mesh mesh_;
  KdTree tree_;
  MeshNormals normals_;
  MeshBvh bvh_;
  float lattice_ = 0.0f;
  Backend backend_ = Backend::Cpu;
  double buildMs_ = 0.0;
  std::unique_ptr<Device> device_;
};

void validateLattice(float lattice);  // throws InputError naming the value

}  // namespace gvdp::detail
