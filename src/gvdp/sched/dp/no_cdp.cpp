// dp on the CUDA backend in a build without CUDA Dynamic Parallelism (GVDP_CDP=OFF, the build
// compute-sanitizer's racecheck accepts).
#include "gvdp/base/error.h"
#include "gvdp/sched/dp/dp.h"

namespace gvdp {

std::unique_ptr<Scheduler> makeDpCuda(const SchedulerOptions&) {
  throw InputError(
      "scheduler 'dp' on cuda needs CUDA Dynamic Parallelism: this gvdp was built "
      "with GVDP_CDP=OFF");
}

}  // namespace gvdp
