#include "gvdp/sched/mesh_scene.h"

#include <chrono>
#include <cmath>

#include "gvdp/base/error.h"
#include "gvdp/base/parallel.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/render/mesh_reference.h"
#include "gvdp/sched/producer_kernels_of.h"

#if GVDP_HAS_CUDA
#include "gvdp/base/cuda_util.h"
#endif

namespace gvdp::detail {

#if GVDP_HAS_CUDA
struct MeshScene::Device {
  DeviceBuffer<Vec3f> vertices, vertexNormals, edgeNormals;
  DeviceBuffer<uint32_t> indices, leafTriangles, bvhTriangles;
  DeviceBuffer<KdNode> nodes;
  DeviceBuffer<MeshBvhNode> bvhNodes;
};

namespace {
template <class T>
DeviceBuffer<T> upload(const std::vector<T>& host) {
  DeviceBuffer<T> d(host.size());
  if (!host.empty())
    GVDP_CUDA_CHECK(cudaMemcpy(d.data(), host.data(), d.bytes(), cudaMemcpyHostToDevice));
  return d;
}
}  // namespace
#else
struct MeshScene::Device {};
#endif

MeshScene::~MeshScene() = default;

void validateLattice(float lattice) {
  GVDP_INPUT_CHECK(lattice == 0.0f || (lattice >= MESH_LATTICE_MIN && lattice <= MESH_LATTICE_MAX),
                   "bad --lattice ", lattice, " (0 for one model, or ", MESH_LATTICE_MIN, "..",
                   MESH_LATTICE_MAX, " world units between copies; a model is ", MESH_PLACED_SIZE,
                   " long)");
}

std::shared_ptr<const MeshScene> MeshScene::load(const std::string& path, float lattice,
                                                 Backend backend) {
  validateLattice(lattice);
  requireBackend(backend);
  std::shared_ptr<MeshScene> s(new MeshScene());
  s->mesh_ = readMesh(path);
  placeMesh(s->mesh_);
  s->lattice_ = lattice;
  s->backend_ = backend;
  auto t0 = std::chrono::steady_clock::now();
  s->tree_ = backend == Backend::Cuda ? buildKdTreeCuda(s->mesh_) : buildKdTreeSequential(s->mesh_);
  s->buildMs_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  s->normals_ = meshNormals(s->mesh_);
  s->bvh_ = buildMeshBvh(s->mesh_);
#if GVDP_HAS_CUDA
  if (backend == Backend::Cuda) {
    s->device_ = std::make_unique<Device>();
    Device& d = *s->device_;
    d.vertices = upload(s->mesh_.vertices);
    d.indices = upload(s->mesh_.indices);
    d.nodes = upload(s->tree_.nodes);
    d.leafTriangles = upload(s->tree_.leafTriangles);
    d.vertexNormals = upload(s->normals_.vertex);
    d.edgeNormals = upload(s->normals_.edge);
    d.bvhNodes = upload(s->bvh_.nodes);
    d.bvhTriangles = upload(s->bvh_.triangles);
  }
#endif
  return s;
}

MeshWorld MeshScene::hostWorld() const {
  SurfaceView surface{
      {mesh_.vertices.data(), mesh_.indices.data(), static_cast<uint32_t>(mesh_.triangleCount())},
      tree_.view(),
      normals_.vertex.data(),
      normals_.edge.data(),
      bvh_.view()};
  return {surface, MESH_VOXEL_SIZE0, lattice_};
}

ProducerKernelsPtr MeshScene::kernels() const {
  MeshWorld world = hostWorld();
#if GVDP_HAS_CUDA
  if (backend_ == Backend::Cuda) {
    const Device& d = *device_;
    world.surface = {{d.vertices.data(), d.indices.data(), world.surface.mesh.triangles},
                     {d.nodes.data(), d.leafTriangles.data(), tree_.bounds},
                     d.vertexNormals.data(),
                     d.edgeNormals.data(),
                     {d.bvhNodes.data(), d.bvhTriangles.data()}};
  }
#endif
  // The kernels share ownership of this scene, whose memory their producer points into.
  struct Owner {
    ProducerKernelsPtr kernels;
    std::shared_ptr<const MeshScene> scene;
  };
  auto owner = std::make_shared<Owner>(Owner{makeProducerKernels(world), shared_from_this()});
  return ProducerKernelsPtr(owner, owner->kernels.get());
}

void MeshScene::renderReference(const FrameSetup& frame, Image& out) const {
  out = Image(frame.width, frame.height);
  MeshWorld world = hostWorld();
  parallelFor(
      frame.pixelCount(),
      [&](int64_t i) { out.pixels[i] = meshReferencePixel(frame, world, static_cast<int>(i)); },
      16);
}

}  // namespace gvdp::detail
