// The `graph` scheduler: the sp loop (render pass -> production -> stopped rays -> repeat)
// captured once as a CUDA graph whose passes repeat under a conditional WHILE node (CUDA 12.4+),
// so that a frame needs no host synchronisation inside it. Images equal sp's bit for bit.
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

// Who repeats the loop's body. Device: the graph's conditional WHILE node (the scheduler).
// Host: the graph is the body alone, launched again while loop.stop is 0 (one read-back per
// pass, as sp): the same kernels and protocol, for the tools that cannot check the kernels of a
// conditional node's body (compute-sanitizer 2025.3's racecheck crashes in its own library on
// this graph, its synccheck reports barrier divergence in a trivially correct kernel there:
// scripts/probe/graph_probe.cu). GVDP_GRAPH_LOOP=host selects it (scripts/gpu_check.sh).
enum class GraphDriver { Device, Host };

// GVDP_GRAPH_LOOP: "device" (default) or "host"; throws InputError naming any other value.
GraphDriver graphDriverFromEnvironment();

std::unique_ptr<Scheduler> makeGraphCuda(const SchedulerOptions& options,
                                         ProducerKernelsPtr producer);

}  // namespace gvdp::detail
