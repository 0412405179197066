// Host/device attributes and project-wide constants.
// GVDP_HD marks the one source shared by the CPU backend (thread pool) and the CUDA backend
// (kernels in .cu files); it expands to nothing when the translation unit is not compiled by nvcc.
#pragma once

#include <cstdint>

#if defined(__CUDACC__)
#define GVDP_HD __host__ __device__
#define GVDP_DEVICE __device__
#define GVDP_INLINE __forceinline__
// Before a host-device template that calls the functor it is given: host code may pass a
// host-only one (nvcc checks the call only where device code instantiates it).
#define GVDP_HD_CALLS_FUNCTOR _Pragma("nv_exec_check_disable")
#else
#define GVDP_HD
#define GVDP_DEVICE
#define GVDP_INLINE inline
#define GVDP_HD_CALLS_FUNCTOR
#endif

#if defined(__CUDA_ARCH__)
#define GVDP_IS_GPU_CODE 1
#define GVDP_UNROLL _Pragma("unroll")  // device code only: the host compiler warns on it
#else
#define GVDP_IS_GPU_CODE 0
#define GVDP_UNROLL
#endif

namespace gvdp::detail {

// Paper 3.2: bricks of 8^3 voxels, stored with a one-voxel border (10^3 samples) so that
// trilinear filtering is seamless across brick edges.
constexpr int BRICK_WIDTH = 8;
constexpr int BRICK_SAMPLES = BRICK_WIDTH + 2;
constexpr int BRICK_SAMPLE_COUNT = BRICK_SAMPLES * BRICK_SAMPLES * BRICK_SAMPLES;
constexpr int MAX_LEVELS = 16;
constexpr int DEFAULT_LEVELS = 8;

}  // namespace gvdp::detail
