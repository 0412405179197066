#include "gvdp/sched/graph/graph_cuda.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/sp/sp.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp::detail {
namespace {

class GraphCuda final : public SpFrameCuda {
 public:
  GraphCuda(const SchedulerOptions& o, ProducerKernelsPtr producer)
      : SpFrameCuda(o, std::move(producer)),
        frame_(1),
        loop_(1),
        driver_(graphDriverFromEnvironment()),
        exec_(buildSpGraph(frame_.data(), loop_.data(), driver_, cudaProducer())) {}
  ~GraphCuda() override { cudaGraphExecDestroy(exec_); }

 private:
  void renderFrame(const FrameSetup& f, Image&, FrameStats& stats) override {
    NvtxRange range("graph frame");
    cache_.beginFrame(f);
    GraphFrame g{f, cache_.view(), cache_.pool(), buffers_.payload.data()};
    GraphLoop loop{buffers_.live.data(), buffers_.next.data(), 0, 0, 0, 0, GRAPH_DONE, 0, 0};
    writeDevice(frame_.data(), &g, sizeof g, stream());
    writeDevice(loop_.data(), &loop, sizeof loop, stream());
    do {  // once, unless the host drives the loop
      GVDP_CUDA_CHECK(cudaGraphLaunch(exec_, stream()));
      readDevice(&loop, loop_.data(), sizeof loop, stream());
    } while (driver_ == GraphDriver::Host && !loop.stop);
    stats.passes = static_cast<int>(loop.passes);
    // A budgeted frame's last claims (no ray stopped on them) are left queued: the host
    // produces them.
    if (loop.exit != GRAPH_DONE || cache_.budgeted()) finishOnHost(f, loop, stats);
    resolveCuda(f, buffers_, stream());
  }

  // What sp does between passes when the device cannot: refill the free slot list (or degrade
  // the frame), then the rest of the frame through the host-driven sp loop.
  void finishOnHost(const FrameSetup& f, const GraphLoop& loop, FrameStats& stats) {
    if (loop.live != buffers_.live.data()) std::swap(buffers_.live, buffers_.next);
    if (loop.exit == GRAPH_FAILED && cache_.refill() == 0) cache_.setDegraded(true);
    if (stats.passes >= SP_MAX_PASSES) cache_.setDegraded(true);
    runSpLoopCuda(f, cudaProducer(), cache_, buffers_, loop.liveCount, false, stats, stream());
  }

  DeviceBuffer<GraphFrame> frame_;
  DeviceBuffer<GraphLoop> loop_;
  GraphDriver driver_;
  cudaGraphExec_t exec_;
};

}  // namespace

std::unique_ptr<Scheduler> makeGraphCuda(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<GraphCuda>(o, std::move(producer));
}

}  // namespace gvdp::detail
