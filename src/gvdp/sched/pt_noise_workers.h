// pt's workers of the built-in noise worlds (world/scene.h: perlin, fbm) are compiled in a
// translation unit of their own (pt_noise_workers.cpp, CUDA builds): at 80 registers a thread, as
// their launch bounds ask, with gradient noise out of line (world/noise.h: GVDP_NOISE_OUT_OF_LINE),
// one copy for the brick's bound, the growth's bound and the samples instead of three inlined
// ones (perlin's worker: 17 560 -> 15 048 SASS instructions, sm_90). ptxas refuses a call from the
// 80-register worker to a function compiled with more registers, so that unit is built with
// -maxrregcount=80; sp's, dp's and graph's kernels of the same worlds (112-128 registers) stay in
// builtin_producer.cpp, which declares these instantiations extern. On an H100 (25 pt cells, 2
// rounds; BENCHMARKS.md, session 32): perlin's and fbm's cells +3 to +11% FPS, the same images;
// forest, which calls the noise too, lost 1% with it and keeps it inlined.
#pragma once

#include "gvdp/world/scene.h"

// X(World) for each built-in world whose pt worker has its noise out of line.
#define GVDP_NOISE_WORLDS(X) X(PerlinWorld) X(FbmWorld)

// The instantiations of pt's worker for world type W (sched/pt/pt_worker.cuh), with `what`
// `template` (pt_noise_workers.cpp) or `extern template` (builtin_producer.cpp).
#define GVDP_PT_WORKERS_OF(what, W) \
  what int ptWorkerBlocksOf<W>();   \
  what void launchPtWorkers<W>(const PtContext&, const BrickPool&, const W&, int, cudaStream_t);
