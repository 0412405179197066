// pt's workers of the built-in worlds (world/scene.h) are compiled in a translation unit of their
// own (builtin_pt_workers.cpp, CUDA builds): at 80 registers a thread, as their launch bounds ask,
// with gradient noise out of line (world/noise.h: GVDP_NOISE_OUT_OF_LINE), one copy for the
// brick's bound, the growth's bound and the samples instead of three inlined ones. ptxas refuses a
// call from the 80-register worker to a function compiled with more registers, so that unit is
// built with -maxrregcount=80; sp's, dp's and graph's kernels of the same worlds (112-128
// registers) stay in builtin_producer.cpp, which declares these instantiations extern. On an
// H100 (25 pt cells, 2 rounds; BENCHMARKS.md, session 32): perlin's and fbm's cells +1 to +11% FPS,
// the others unchanged, the same images.
#pragma once

#include "gvdp/world/scene.h"

// X(World) for each of the five built-in world types.
#define GVDP_BUILTIN_WORLDS(X) \
  X(PerlinWorld) X(FbmWorld) X(ForestWorld) X(RandomSpheresWorld) X(AlignedSpheresWorld)

// The instantiations of pt's worker for world type W (sched/pt/pt_worker.cuh), with `what`
// `template` (builtin_pt_workers.cpp) or `extern template` (every other unit of the library).
#define GVDP_PT_WORKERS_OF(what, W)                                                         \
  what int ptWorkerBlocksOf<W>();                                                           \
  what void launchPtWorkers<W>(const PtContext& ctx, const BrickPool& pool, const W& producer, \
                               int blocks, cudaStream_t stream);
