#include "gvdp/sched/importance_map.h"

#include <chrono>

#include "gvdp/base/error.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

namespace {

constexpr uint64_t MIN_TABLE_ENTRIES = uint64_t{1} << 16;

int ceilDiv(int a, int b) {
  return (a + b - 1) / b;
}

}  // namespace

ImportanceMap importanceShape(const FrameSetup& frame, const ImportanceOptions& o) {
  GVDP_INPUT_CHECK(o.stride >= 1 && o.stride <= 64, "pre-pass stride ", o.stride,
                   " out of range 1..64");
  GVDP_INPUT_CHECK(
      o.blockPixels >= o.stride && o.blockPixels <= 4096 && o.blockPixels % o.stride == 0,
      "importance block of ", o.blockPixels, " pixels: not a multiple of the stride ", o.stride,
      " up to 4096");
  GVDP_INPUT_CHECK(
      o.firstTableEntries == 0 ||
          (o.firstTableEntries >= 16 && (o.firstTableEntries & (o.firstTableEntries - 1)) == 0),
      "importance table of ", o.firstTableEntries, " entries: not a power of two >= 16");
  ImportanceMap m;
  m.stride = o.stride;
  m.blockPixels = o.blockPixels;
  for (;;) {
    m.blocksX = ceilDiv(frame.width, m.blockPixels);
    m.blocksY = ceilDiv(frame.height, m.blockPixels);
    m.levels = 0;
    while ((1 << m.levels) < std::max(m.blocksX, m.blocksY)) ++m.levels;
    if (m.levels <= IMPORTANCE_MAX_LEVELS) return m;
    m.blockPixels *= 2;
  }
}

ImportanceSetup importanceSetup(const ImportanceMap& m, const FrameSetup& frame,
                                uint64_t tableEntries) {
  ImportanceSetup s{};
  s.blockPixels = m.blockPixels;
  s.stride = m.stride;
  s.levels = m.levels;
  s.raysX = ceilDiv(frame.width, m.stride);
  s.raysY = ceilDiv(frame.height, m.stride);
  s.tableMask = tableEntries - 1;
  s.maxEntries = static_cast<uint32_t>(std::min<uint64_t>(tableEntries / 4 * 3, 0xffffffffu));
  return s;
}

ImportanceStatus countBricksOnHost(const ProducerKernels& producer, const FrameSetup& frame,
                                   uint64_t tableEntries, ImportanceMap& m) {
  std::vector<uint64_t> table(tableEntries, IMPORTANCE_FREE);
  std::vector<uint8_t> occupied(tableEntries, 0);
  std::vector<uint64_t> bricks(tableEntries);
  m.counts.assign(mipmapSize(m.levels), 0);
  ImportanceStatus status{};
  ImportanceSetup s = importanceSetup(m, frame, tableEntries);
  s.table = table.data();
  s.occupied = occupied.data();
  s.bricks = bricks.data();
  s.counts = m.counts.data();
  s.status = status.data();
  producer.countBricks(frame, s);
  return status;
}

ImportanceMap Scheduler::importance(const FrameSetup& frame, const ImportanceOptions& o) const {
  ImportanceMap m = importanceShape(frame, o);
  auto start = std::chrono::steady_clock::now();
  uint64_t first = o.firstTableEntries;
  if (first == 0) {
    uint64_t keys = uint64_t{importanceSetup(m, frame, 16).rays()} * 8 * (m.levels + 2);
    first = MIN_TABLE_ENTRIES;
    while (first < keys && first * sizeof(uint64_t) < o.maxTableBytes) first *= 2;
  }
  for (uint64_t entries = first;; entries *= 4) {
    if (entries * sizeof(uint64_t) > o.maxTableBytes) {
      m.failure = "the hash table would pass its limit";
      break;
    }
    ++m.attempts;
    ImportanceStatus status = backend_ == Backend::Cpu
                                  ? countBricksOnHost(*producer_, frame, entries, m)
                                  : countBricksOnDevice(*producer_, frame, entries, stream(), m);
    if (status[IMPORTANCE_RANGE]) {
      m.failure = "a brick beyond the keys' reach";
      break;
    }
    if (!status[IMPORTANCE_FULL]) {
      m.entries = status[IMPORTANCE_ENTRIES];
      m.tableBytes = entries * sizeof(uint64_t);
      break;
    }
  }
  if (m.failure) m.counts.clear();
  m.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return m;
}

}  // namespace gvdp::detail
