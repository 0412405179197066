// The memory estimate that sizes are checked against before anything is allocated: it must
// agree with what the schedulers hold, and renderSequence must refuse what the host cannot hold.
#include <gtest/gtest.h>

#include <algorithm>

#include "gvdp/base/error.h"
#include "gvdp/base/host_memory.h"
#include "gvdp/cache/brick_key.h"
#include "gvdp/sched/memory_estimate.h"
#include "test_util.h"

namespace gvdp::detail {

TEST(MemoryEstimate, MatchesWhatTheCpuSchedulersHold) {
  SequenceOptions o;
  o.width = 40;
  o.height = 24;
  for (SchedulerKind kind : {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt}) {
    o.scheduler = {Backend::Cpu, kind, 2000, 1000};
    FrameSetup frame = frameOf(o, 0);
    MemoryReport estimate = memoryEstimate(o.scheduler, frame);
    std::unique_ptr<Scheduler> s = test::schedulerFor(o);
    Image image;
    s->render(frame, image);
    for (const MemoryItem& held : s->memory()) {
      auto e = std::find_if(estimate.begin(), estimate.end(),
                            [&](const MemoryItem& i) { return i.name == held.name; });
      ASSERT_NE(e, estimate.end()) << schedulerName(kind) << " " << held.name;
      EXPECT_EQ(e->bytes, held.bytes) << schedulerName(kind) << " " << held.name;
    }
  }
}

TEST(MemoryEstimate, RenderSequenceRefusesAPoolLargerThanTheHost) {
  std::optional<uint64_t> available = hostAvailableMemoryBytes();
  ASSERT_TRUE(available.has_value());
  uint64_t bricks = *available / (BRICK_SAMPLE_COUNT * sizeof(Rgba8)) + 1;
  if (bricks >= SLOT_LIMIT) GTEST_SKIP() << "the host holds more than the largest pool";
  SequenceOptions o;
  o.width = 32;
  o.height = 20;
  o.frames = 1;
  o.scheduler.poolBricks = static_cast<uint32_t>(bricks);
  bool rendered = false;
  EXPECT_THROW(renderSequence(o, [&](const Image&, const FrameStats&) { rendered = true; }),
               InputError);
  EXPECT_FALSE(rendered);
}

}  // namespace gvdp::detail
