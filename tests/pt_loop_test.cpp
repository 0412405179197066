// pt's worker loop (sched/pt/pt_body.h: ptWorkerLoop) over a scripted worker: the order in which a
// worker takes its work, a helper SM's warp (pt_worker.cuh: PT_HELPER_SMS) included.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {
namespace {

constexpr uint32_t OWNER = 7;  // the open production's owner

// What is there to take, and the steps the loop took, one round of it (liveWork() reads 0 after).
struct ScriptedWorker {
  explicit ScriptedWorker(const PtContext& c) : ctx(c) {}
  const PtContext& ctx;
  bool helper = false;
  bool rendering = true, taking = true;  // renders(), takesTasks()
  uint32_t tasks = 0, rays = 0, items = 0;
  uint32_t open = NO_PRODUCTION;
  uint32_t prefetchItems = 0;
  int rounds = 1;
  std::vector<std::string> steps;

  struct Batch {
    bool relaunched = false;
  };
  uint32_t liveWork() { return rounds-- > 0 ? 1u : 0u; }
  uint32_t claim(const Ring& r, uint32_t n, uint32_t* position) {
    *position = 0;
    uint32_t& left = &r == &ctx.tasks ? tasks : rays;
    EXPECT_TRUE(&r == &ctx.tasks || &r == &ctx.rays);
    uint32_t got = std::min(left, n);
    left -= got;
    return got;
  }
  static uint32_t producing() { return NO_PRODUCTION; }
  void produce(uint32_t) { steps.push_back("produce"); }
  Batch queued(uint32_t, uint32_t) {
    steps.push_back("rays");
    return {true};
  }
  uint32_t claimFresh() { return items > 0 ? (--items, 0u) : ctx.itemCount; }
  Batch fresh(uint32_t) {
    steps.push_back("items");
    return {};
  }
  void render(const Batch&) { steps.push_back("render"); }
  uint32_t findProduction() const { return open; }
  bool helpsFirst() const { return helper; }
  bool renders() const { return rendering; }
  bool takesTasks() const { return taking; }
  void help(uint32_t owner) { steps.push_back("help " + std::to_string(owner)); }
  uint32_t claimPrefetch() { return prefetchItems > 0 ? (--prefetchItems, 0u) : ctx.prefetchItems; }
  void prefetch(uint32_t) { steps.push_back("prefetch"); }
  void idle() { steps.push_back("idle"); }
  void finish() { steps.push_back("finish"); }
};

using Steps = std::vector<std::string>;

PtContext loopContext() {
  PtContext ctx{};
  ctx.itemCount = 64;
  ctx.prefetchItems = 1;
  return ctx;
}

// The steps of a worker for which `set` scripts what there is to take.
template <class Set>
Steps run(Set set) {
  PtContext ctx = loopContext();
  ScriptedWorker w(ctx);
  set(w);
  ptWorkerLoop(ctx, w);
  return w.steps;
}

TEST(PtWorkerLoop, TakesAProductionTaskBeforeAnythingElse) {
  for (bool helper : {false, true})
    EXPECT_EQ(run([&](ScriptedWorker& w) {
                w.helper = helper;
                w.tasks = 1;
                w.rays = 32;
                w.items = 1;
                w.open = OWNER;
              }),
              (Steps{"produce", "finish"}))
        << "helper " << helper;
}

TEST(PtWorkerLoop, RendersBeforeItHelpsUnlessItIsAHelper) {
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.rays = 32;
              w.open = OWNER;
            }),
            (Steps{"rays", "render", "finish"}));
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.items = 1;
              w.open = OWNER;
            }),
            (Steps{"items", "render", "finish"}));
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.helper = true;
              w.rays = 32;
              w.items = 1;
              w.open = OWNER;
            }),
            (Steps{"help 7", "finish"}));
}

TEST(PtWorkerLoop, AHelperWithNoOpenProductionRenders) {
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.helper = true;
              w.rays = 32;
            }),
            (Steps{"rays", "render", "finish"}));
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.helper = true;
              w.items = 1;
            }),
            (Steps{"items", "render", "finish"}));
}

TEST(PtWorkerLoop, WithNothingToTakeItHelpsThenPrefetchesThenIdles) {
  for (bool helper : {false, true}) {
    EXPECT_EQ(run([&](ScriptedWorker& w) {
                w.helper = helper;
                w.open = OWNER;
              }),
              (Steps{"help 7", "finish"}));
    EXPECT_EQ(run([&](ScriptedWorker& w) {
                w.helper = helper;
                w.prefetchItems = 1;
              }),
              (Steps{"prefetch", "finish"}));
    EXPECT_EQ(run([&](ScriptedWorker& w) { w.helper = helper; }), (Steps{"idle", "finish"}));
  }
}

// A producer SM's warp (pt_worker.cuh: roleNow) takes no rays, items or prefetch rays.
TEST(PtWorkerLoop, AProducerOnlyProducesAndHelps) {
  auto producer = [](ScriptedWorker& w) {
    w.rendering = false;
    w.helper = true;
    w.rays = 32;
    w.items = 1;
    w.prefetchItems = 1;
  };
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              producer(w);
              w.tasks = 1;
            }),
            (Steps{"produce", "finish"}));
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              producer(w);
              w.open = OWNER;
            }),
            (Steps{"help 7", "finish"}));
  EXPECT_EQ(run(producer), (Steps{"idle", "finish"}));
}

// The other warps (LeavesTasks) leave tasks and productions to the producer SMs.
TEST(PtWorkerLoop, AWorkerThatLeavesTasksNeverProducesOrHelps) {
  auto leaves = [](ScriptedWorker& w) {
    w.taking = false;
    w.tasks = 1;
    w.open = OWNER;
  };
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              leaves(w);
              w.rays = 32;
            }),
            (Steps{"rays", "render", "finish"}));
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              leaves(w);
              w.prefetchItems = 1;
            }),
            (Steps{"prefetch", "finish"}));
  EXPECT_EQ(run(leaves), (Steps{"idle", "finish"}));
}

TEST(PtWorkerLoop, RunsUntilNoWorkIsLive) {
  EXPECT_EQ(run([&](ScriptedWorker& w) {
              w.rays = 64;
              w.rounds = 3;
            }),
            (Steps{"rays", "render", "rays", "render", "idle", "finish"}));
}

// A warp's role (ptRole) with producer SMs, share 2 on 132 SMs (spike backlog 528, 82 spike
// producers): SMs below ceil(backlog / 2) produce, the others leave tasks to them; in a spike the
// SMs below 82 produce and the others render; every warp takes any work once a warp has left the
// loop (those that would leave tasks), while tasks wait with none in flight, or without producer
// SMs.
constexpr uint32_t SPIKE_PRODUCERS = 132 * 5 / 8;

TEST(PtRole, ProducerSmsFollowTheBacklogThenSplitTheSmsInASpike) {
  constexpr uint32_t S = 2, SPIKE = 2 * S * 132, P = SPIKE_PRODUCERS;
  // A backlog of productions in flight (none queued), unless `ready` says otherwise.
  auto role = [](uint32_t backlog, uint32_t sm, bool exited = false, bool spike = false,
                 uint32_t ready = 0, uint32_t producers = SPIKE_PRODUCERS) {
    return ptRole(S, SPIKE, producers, spike, ready, backlog - ready, sm, exited);
  };
  EXPECT_EQ(role(0, 0), PtRole::LeavesTasks);  // no backlog: every SM renders
  EXPECT_EQ(role(5, 2), PtRole::Producer);     // ceil(5 / 2) = 3 SMs produce
  EXPECT_EQ(role(5, 3), PtRole::LeavesTasks);
  EXPECT_EQ(role(SPIKE - 1, 131), PtRole::Producer);     // every SM
  EXPECT_EQ(role(SPIKE, P - 1), PtRole::Producer);       // a spike: the first 82 SMs produce
  EXPECT_EQ(role(SPIKE, P), PtRole::LeavesTasks);        // and the others render
  EXPECT_EQ(role(5, 0, false, true), PtRole::Producer);  // for the rest of the frame
  EXPECT_EQ(role(5, 131, false, true), PtRole::LeavesTasks);
  EXPECT_EQ(role(5, 131, true, true), PtRole::Any);
  EXPECT_EQ(role(SPIKE, 131, false, false, 0, 0), PtRole::Any);  // no spike producers: any work
  EXPECT_EQ(role(5, 3, true), PtRole::Any);  // a warp left: the last takes any task
  EXPECT_EQ(role(5, 0, true), PtRole::Producer);
  EXPECT_EQ(role(5, 2, false, false, 3), PtRole::Producer);  // 3 queued and 2 in flight
  EXPECT_EQ(role(5, 3, false, false, 3), PtRole::LeavesTasks);
  EXPECT_EQ(role(1, 5, false, false, 1), PtRole::Any);  // a task waits, none in flight
  EXPECT_EQ(role(1, 0, false, false, 1), PtRole::Any);
  EXPECT_EQ(role(SPIKE, 0, false, true, SPIKE), PtRole::Any);      // so in a spike too
  EXPECT_EQ(ptRole(0, 0, 0, false, 0, 5, 0, false), PtRole::Any);  // without producer SMs
}

}  // namespace
}  // namespace gvdp::detail
