// The march of a warp's 32 rays with their samples shared out (GPU; sp's and graph's render
// passes, pt's worker). Each round, the lanes whose ray has no sample due seek its next run
// (render/march.h: Marcher::seek, one brick decision, lanes deciding together); then the warp's due
// samples are shared out - every lane reads up to two, whatever ray they belong to - and each ray's
// lane composites its own in order. The reads, most of a march's instructions, then run on most
// lanes rather than on the few whose rays happen to be sampling at a step (ncu, forest's
// walkthrough: 10.0 -> 16.9 lanes per instruction, BENCHMARKS.md). Each sample is the same
// arithmetic on the same values as in march(), composited in the same order: the same image, bit
// for bit. A lane reads bricks another lane looked up. Where the pool cannot change while the
// kernel runs (sp, graph: PoolReads::ReadOnly) there is no acquire to pass on. In pt's worker,
// which publishes bricks as it runs (PoolReads::Coherent), the lane that looked a fresh brick up
// read its entry with an acquire load (CachedAccess::resident), and the warp's barrier (__syncwarp,
// after the round's runs are written and before they are read) orders that acquire before every
// lane's reads of the brick: the release-acquire pair and the barrier compose (causality order), so
// each lane reads the samples the producer wrote before publishing. pt's warp marches only until
// its first ray stops (WarpMarchEnd::FirstStop), so that the stopped ray claims its brick, looks
// ahead and parks at once rather than after its warp's other rays (sched/pt/pt_worker.cuh).
#pragma once

#include "gvdp/render/march.h"

namespace gvdp::detail {

constexpr unsigned FULL_WARP = 0xffffffffu;
constexpr int WARP_SIZE = 32;
// Samples read a round at most: two per lane (one per lane: sp's floors x1.07, H100).
constexpr int WARP_CHUNK = 2 * WARP_SIZE;
// What a lane needs to read a sample of another lane's run.
struct SharedRun {
  float start, voxelSize;  // the run's level lattice (LevelSpan::sampleT)
  int step;                // the run's first sample due
  BrickLookup brick;
};

// A warp's shared memory for marchWarp.
struct WarpMarchShared {
  Ray rays[WARP_SIZE];
  SharedRun runs[WARP_SIZE];  // per lane, while its run is read
  Vec4f samples[WARP_CHUNK];  // the samples read, in the order of the runs
  int owner[WARP_CHUNK];      // the lane whose samples start at each position
};

__device__ inline int inclusiveWarpSum(int v, int lane) {
  for (int d = 1; d < WARP_SIZE; d <<= 1) {
    int u = __shfl_up_sync(FULL_WARP, v, d);
    if (lane >= d) v += u;
  }
  return v;
}

// How long marchWarp marches: until every ray of the warp has finished or stopped (sp, graph),
// or until the first of them stops (pt): then the rays neither finished nor stopped return
// Paused, their state at a step march() resumes from (a seek there looks the brick up again).
enum class WarpMarchEnd : uint8_t { AllDone, FirstStop };

// Every lane of the warp calls it; an inactive lane has no ray and only reads others' samples.
// Access provides, besides march()'s: Vec4f read(const BrickLookup&, Vec3f p) const (sample()
// without counting) and countSamples(n).
template <WarpMarchEnd END = WarpMarchEnd::AllDone, class Access>
__device__ MarchResult marchWarp(const Ray& ray, const Lod& lod, RayState& s, Access& access,
                                 bool active, WarpMarchShared& shared) {
  using Seek = typename Marcher<Access>::Seek;
  Marcher<Access> m(ray, lod, s, access);
  int lane = static_cast<int>(threadIdx.x) & (WARP_SIZE - 1);
  shared.rays[lane] = ray;
  MarchResult result = MarchResult::Finished;
  bool done = !active, due = false;
  for (;;) {
    bool stopped = false;
    if (!done && !due) {
      Seek k = m.seek();
      due = k == Seek::Due;
      stopped = k == Seek::Stopped;
      done = k == Seek::Finished || stopped;
      if (stopped) result = MarchResult::Stopped;
    }
    if constexpr (END == WarpMarchEnd::FirstStop) {
      if (__any_sync(FULL_WARP, stopped)) return done ? result : MarchResult::Paused;
    }
    int count = due ? m.runLength() : 0;
    unsigned dueLanes = __ballot_sync(FULL_WARP, due);
    if (!dueLanes) {
      if (!__any_sync(FULL_WARP, !done)) return result;
      continue;
    }
    // Each due lane's share: up to `cap` samples, so that the round reads at most WARP_CHUNK and
    // due lanes go on together (and seek together after).
    int cap = WARP_CHUNK >> (32 - __clz(__popc(dueLanes) - 1));
    int take = min(count, cap);
    int end = inclusiveWarpSum(take, lane), first = end - take;
    int served = __shfl_sync(FULL_WARP, end, WARP_SIZE - 1);
    if (take > 0) {
      shared.owner[first] = lane;
      shared.runs[lane] = {m.span.start, m.span.voxelSize, s.step, m.resident};
    }
    unsigned startsLow = __reduce_or_sync(FULL_WARP, take > 0 && first < 32 ? 1u << first : 0u);
    unsigned startsHigh =
        __reduce_or_sync(FULL_WARP, take > 0 && first >= 32 ? 1u << (first - 32) : 0u);
    uint64_t starts = uint64_t{startsHigh} << 32 | startsLow;
    __syncwarp();
    for (int j = lane; j < served; j += WARP_SIZE) {
      int from = 63 - __clzll(static_cast<long long>(starts & (~uint64_t{0} >> (63 - j))));
      int owner = shared.owner[from];
      const SharedRun& r = shared.runs[owner];
      const Ray& q = shared.rays[owner];
      LevelSpan span{r.voxelSize, r.start, 0.0f, 0.0f};
      Vec3f p = q.o + q.d * span.sampleT(r.step + j - from);
      shared.samples[j] = access.read(r.brick, p);
    }
    __syncwarp();
    if (take > 0) {
      int k = 0;
      for (; k < take && !s.finished(lod); ++k) m.composite(shared.samples[first + k]);
      access.countSamples(static_cast<uint32_t>(k));
      due = take < count && !s.finished(lod);
    }
    __syncwarp();
  }
}

}  // namespace gvdp::detail
