// pt's workers of the built-in noise worlds, apart from their other kernels (pt_noise_workers.h).
#define GVDP_NOISE_OUT_OF_LINE 1

#include "gvdp/sched/pt_noise_workers.h"

#include "gvdp/sched/pt/pt_worker.cuh"

namespace gvdp::detail {

#define GVDP_INSTANTIATE(W) GVDP_PT_WORKERS_OF(template, W)
GVDP_NOISE_WORLDS(GVDP_INSTANTIATE)
#undef GVDP_INSTANTIATE

}  // namespace gvdp::detail
