// pt's workers of the built-in worlds, apart from their other kernels (builtin_pt_workers.h).
#define GVDP_NOISE_OUT_OF_LINE 1

#include "gvdp/sched/builtin_pt_workers.h"

#include "gvdp/sched/pt/pt_worker.cuh"

namespace gvdp::detail {

#define GVDP_INSTANTIATE(W) GVDP_PT_WORKERS_OF(template, W)
GVDP_BUILTIN_WORLDS(GVDP_INSTANTIATE)
#undef GVDP_INSTANTIATE

}  // namespace gvdp::detail
