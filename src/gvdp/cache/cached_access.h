// The cached side of Algorithm 1: how a ray reads the clipmap. A resident brick is sampled from
// the pool (and its timestamp touched), a CLEAR one as a resident brick whose cells are all clear
// (zero, with no read); an EMPTY brick is skipped with the empty box its entry
// names (brick_key.h: emptyEntry), a missing one under an EMPTY coarser ancestor with that
// ancestor's; a MISSING brick is claimed with a CAS (the winner queues its production) and the ray
// stops, as on IN_PRODUCTION. In a degraded frame (no free slot left) nothing is produced: the
// ray samples the nearest resident coarser level, or passes through. Past a budgeted frame's
// deadline (BrickCache::setBudget) the ray does not stop either: it shows the nearest resident
// coarser level, and the MISSING bricks it meets are still claimed (a few), without waiting, for
// the next frames.
#pragma once

#include "gvdp/base/atomics.h"
#include "gvdp/base/bits.h"
#include "gvdp/base/clock.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/march.h"

namespace gvdp::detail {

// Bricks a march claims past its frame's deadline (CachedAccess::lateStandIn).
constexpr uint32_t MAX_LATE_CLAIMS = 8;
// A stand-in of any level above the brick (CachedAccess::standIn).
constexpr int STAND_INS_ANY = 1 << 30;

// Claims a MISSING brick for production: true for the one thread whose CAS won.
GVDP_HD GVDP_INLINE bool claimBrick(uint32_t* entry) {
  return atomicCas32(entry, ENTRY_MISSING, ENTRY_IN_PRODUCTION) == ENTRY_MISSING;
}

// sp's answer to a MISSING brick: claim it and queue it for the next production pass.
struct QueueRequest {
  GVDP_HD void operator()(const CacheView& cache, int level, Vec3i g, uint32_t* entry) const {
    if (claimBrick(entry)) requestBrick(cache, level, g, entry);
  }
  GVDP_HD void ahead(const CacheView& cache, int level, Vec3i g, uint32_t* entry) const {
    (*this)(cache, level, g, entry);
  }
};

// Adds a ray's march counts to the frame's (MarchCounter): on the GPU one atomic per counter
// and warp (the lanes that get here together), so counting costs the frame nothing visible; and,
// when the frame records them, to its pixel's (CacheView::rayCosts; pixel < 0: no ray).
GVDP_HD GVDP_INLINE void addMarchCounts(const CacheView& cache, int pixel, uint32_t samples,
                                        uint32_t lookups, uint32_t skips, uint32_t coarser) {
  if (cache.rayCosts && pixel >= 0) {
    uint32_t* mine = cache.rayCosts + size_t{RAY_COST_WORDS} * static_cast<uint32_t>(pixel);
    atomicAdd32(&mine[RAY_COST_LOOKUPS], lookups);
    atomicAdd32(&mine[RAY_COST_SAMPLES], samples);
  }
  uint64_t* c = cache.marchCounters();
#if GVDP_IS_GPU_CODE
  unsigned mask = __activemask();
  samples = __reduce_add_sync(mask, samples);
  lookups = __reduce_add_sync(mask, lookups);
  skips = __reduce_add_sync(mask, skips);
  coarser = __reduce_add_sync(mask, coarser);
  unsigned lane;
  asm("mov.u32 %0, %%laneid;" : "=r"(lane));
  if (lane != static_cast<unsigned>(lowestBit(mask))) return;
#endif
  atomicAdd64(&c[MARCH_SAMPLES], samples);
  atomicAdd64(&c[MARCH_LOOKUPS], lookups);
  atomicAdd64(&c[MARCH_SKIPS], skips);
  if (coarser) atomicAdd64(&c[MARCH_COARSER], coarser);
}

// A ray's march that ended on a brick not ready, into its pixel's stops (CacheView::rayCosts).
GVDP_HD GVDP_INLINE void noteRayStop(const CacheView& cache, int pixel) {
  if (cache.rayCosts)
    atomicAdd32(
        &cache.rayCosts[size_t{RAY_COST_WORDS} * static_cast<uint32_t>(pixel) + RAY_COST_STOPS],
        1u);
}

// Pool provides: Vec4f sample<READS>(uint32_t slot, Vec3i brickVoxelOrigin, Vec3f v, uint64_t
// occupancy), v in voxel coordinates of the brick's level (local), brickVoxelOrigin = 8 * local
// brick coordinates, zero without a read where the sample's voxels lie in a clear cell, and
// uint64_t loadOccupancy<READS>(slot) (render/brick_pool.h).
// OnMiss(cache, level, globalBrick, entry) runs when the entry was MISSING: it claims the brick
// with a CAS from MISSING (one thread wins) and the winner starts its production; the ray waits
// for it. OnMiss::ahead(cache, level, globalBrick, entry) claims a brick no ray will wait for (the
// ray went on past the frame's deadline); it may decline (the brick stays MISSING).
//
// READS says whether bricks may be published while the march's kernel runs (docs/DESIGN.md,
// "Memory model"). Every entry is first read with a relaxed load: an EMPTY, MISSING or
// in-production entry carries nothing the march reads elsewhere (an EMPTY box is in the entry's
// bits), so nothing needs ordering after it. Coherent (dp, pt): a slot published in the running
// frame (ENTRY_FRESH, brick_key.h) is read again with an acquire load before the brick is
// (resident()), which makes its samples and occupancy, written before the producer's release
// (publishBrick), visible to the reads after it; the entry of a resident brick does not change
// while a frame runs (slots are freed between frames), so the acquire reads the value the release
// wrote. A slot without the mark was published in an earlier frame, whose kernels the stream
// ordered before this one, and nothing writes its brick while this frame runs: no acquire. The
// pool is read with plain loads (through L1): ordered by the acquire or by the kernel boundary.
// (An acquire at device scope also invalidates the SM's L1: one per lookup, then one per resident
// lookup, cost pt's march 5-25% of its floor, H100.) ReadOnly (sp, graph): production runs in
// kernels of its own, ordered before the render kernel by the stream or the graph, so every
// brick the kernel can find resident was published before it began; the only entry writes during
// the kernel are claims (MISSING to IN_PRODUCTION), which publish nothing. No acquire then, and
// the pool, read-only for the kernel's life, is read through the non-coherent path.
template <class Pool, class OnMiss = QueueRequest, PoolReads READS = PoolReads::Coherent,
          bool TOUCH = true>
struct CachedAccess {
  const CacheView& cache;
  const Pool& pool;
  const Lod& lod;
  OnMiss onMiss{};
  uint32_t* stopEntry = nullptr;  // the entry the ray stopped on (dp re-reads it)
  int stopLevel = 0;              // and its brick (local coordinates)
  Vec3i stopBrick{0, 0, 0};
  uint32_t samples = 0, lookups = 0, skips = 0;  // this march's (addCounts after it)
  uint32_t coarser = 0;     // 1 once a coarser level stood in for a brick that was not ready
  uint32_t lateClaims = 0;  // bricks claimed past the deadline (lateStandIn)

  // An ancestor's entry, null outside its window (never read: it would alias another brick).
  GVDP_HD uint32_t* entryOf(int level, Vec3i localBrick) const {
    uint32_t i = cache.clipmap.windowEntryOfLocal(level, localBrick);
    return i == Clipmap::NOT_IN_WINDOW ? nullptr : &cache.entries[i];
  }

  // An entry's value, relaxed (above); MISSING for a null entry.
  GVDP_HD static uint32_t peek(const uint32_t* entry) {
    return entry ? loadRelaxed32(entry) : ENTRY_MISSING;
  }

  // A resident brick (`e`, a slot entry `entry` holds), its timestamp set to this frame: on the GPU
  // by a plain store (the warp's stores to one slot coalesce, and nothing waits on them), on the
  // CPU only when it changes (a store per lookup would bounce the cache line between threads).
  GVDP_HD BrickLookup resident(const uint32_t* entry, uint32_t e, int level, Vec3i brick) const {
    if (READS == PoolReads::Coherent && isFresh(e)) loadAcquire32(entry);  // reads `e` (above)
    uint32_t slot = slotOf(e);
    if constexpr (TOUCH) {
#if GVDP_IS_GPU_CODE
      storeRelaxed32(&cache.timestamps[slot], cache.frame);
#else
      if (loadRelaxed32(&cache.timestamps[slot]) != cache.frame)
        storeRelaxed32(&cache.timestamps[slot], cache.frame);
#endif
    }
    // Written before the entry was published: in an earlier frame, or before the release.
    return {BrickState::Resident, slot, level, brick, pool.template loadOccupancy<READS>(slot)};
  }

  // A CLEAR brick (brick_key.h): a resident one whose cells are all clear, with no slot to read or
  // stamp (MAX_SLOTS: a read past the pool, should one ever skip the cells' test); it samples
  // zero at its level, and stands in (as zero) for finer bricks like any.
  GVDP_HD static BrickLookup clear(int level, Vec3i brick) {
    return {BrickState::Resident, MAX_SLOTS, level, brick, uint64_t{0}};
  }

  // A brick that can be sampled, resident or CLEAR: as resident() or clear().
  GVDP_HD static bool shown(uint32_t e) {
    return isSlot(e) || isClearEntry(e);
  }
  GVDP_HD BrickLookup shownBrick(const uint32_t* entry, uint32_t e, int level, Vec3i brick) const {
    return isSlot(e) ? resident(entry, e, level, brick) : clear(level, brick);
  }

  // An EMPTY brick, with the box its entry names; for a ray of its level a CLEAR one too, whose
  // box is zero at that level (the march leaves an own-level box only within its level).
  GVDP_HD static BrickLookup empty(int level, Vec3i brick, uint32_t entry) {
    return {BrickState::Empty, 0u, level, brick, ~uint64_t{0}, entry & EMPTY_CODES_MASK};
  }

  GVDP_HD bool degraded() const {
    return cache.degraded ||
           (cache.degradeOnFailure && loadRelaxed32(&cache.counters[COUNTER_FAILED]));
  }

  // Past a budgeted frame's deadline: a brick that is not ready is no longer waited for. Read
  // only where a ray would stop; the time only grows, so a ray that stood in once never stops
  // again in the frame (and counts once in MARCH_COARSER).
  GVDP_HD bool late() const {
    return cache.budgeted && clockNanoseconds() >= *cache.deadline();
  }

  GVDP_HD BrickLookup showCoarser(BrickLookup b) {
    coarser = 1;
    if (b.state == BrickState::Resident) b.state = BrickState::StandIn;
    return b;
  }

  // The counts of the march so far into the frame's and pixel's (< 0: none); once per march.
  GVDP_HD void addCounts(int pixel) const {
    addMarchCounts(cache, pixel, samples, lookups, skips, coarser);
  }

  GVDP_HD BrickLookup lookup(int level, Vec3i brick) {
    ++lookups;
    BrickLookup b = find(level, brick);
    skips += b.state == BrickState::Empty ? 1u : 0u;
    return b;
  }

  GVDP_HD BrickLookup find(int level, Vec3i brick) {
    // The clipmap width covers every sample of a level (lod_test checks the formula); a brick
    // outside its window could only alias another one, so it is never read.
    uint32_t index = cache.clipmap.windowEntryOfLocal(level, brick);
    if (index == Clipmap::NOT_IN_WINDOW) return {BrickState::Empty, 0u, level, brick};
    uint32_t* entry = &cache.entries[index];
    uint32_t e = loadRelaxed32(entry);
    if (isSlot(e)) return resident(entry, e, level, brick);
    if (isEmptyEntry(e) || isClearEntry(e)) return empty(level, brick, e);
    // Missing or in production: an EMPTY ancestor lets the ray skip it, with no production. The
    // frame's degraded state is read only where it decides (a resident ancestor, or none EMPTY):
    // most such lookups end at an EMPTY ancestor, and a load of the counter per lookup stalled
    // pt's march (14% of its warps' samples on perlin's floor frame, ncu, H100).
    bool known = false, fell = false;
    auto fellBack = [&] {
      if (!known) {
        fell = degraded();
        known = true;
      }
      return fell;
    };
    Vec3i a = brick;
    for (int up = level + 1; up < lod.levels; ++up) {
      a = halfFloor(a);
      uint32_t* at = entryOf(up, a);
      uint32_t ea = peek(at);
      if (isEmptyEntry(ea)) return empty(up, a, ea);
      if (shown(ea) && fellBack()) return showCoarser(shownBrick(at, ea, up, a));
    }
    if (fellBack()) return showCoarser({BrickState::Empty, 0u, level, brick});  // nothing
    if (late()) return showCoarser(lateStandIn(level, brick, e, entry));
    if (e == ENTRY_MISSING) onMiss(cache, level, cache.clipmap.globalBrick(level, brick), entry);
    stopEntry = entry;
    stopLevel = level;
    stopBrick = brick;
    return {BrickState::Stop, 0u, level, brick};
  }

  // Past the deadline: the nearest resident coarser ancestor stands in, and the bricks are claimed
  // for the next frames, up to MAX_LATE_CLAIMS per march (the chain the ray would have waited on
  // one brick after the other): the brick if it is MISSING, and its parent if no ancestor is
  // resident and the parent is MISSING, so that the next frame has a stand-in for its neighbours
  // too. Measured on an H100 (pt walkthroughs, --budget-ms 8; BENCHMARKS.md "Frame-time budget"):
  // without a cap, random-spheres produced 3.6x the bricks of exact frames; claiming only before
  // the first stand-in left chains one brick per frame and 20-37% of fbm's pixels coarser.
  GVDP_HD BrickLookup lateStandIn(int level, Vec3i brick, uint32_t e, uint32_t* entry) {
    BrickLookup b = standIn(level, brick);
    if (e == ENTRY_MISSING && lateClaims < MAX_LATE_CLAIMS) {
      ++lateClaims;
      onMiss.ahead(cache, level, cache.clipmap.globalBrick(level, brick), entry);
    }
    if (b.state != BrickState::Empty) return b;
    Vec3i parent = halfFloor(brick);
    uint32_t index = level + 1 < lod.levels ? cache.clipmap.windowEntryOfLocal(level + 1, parent)
                                            : Clipmap::NOT_IN_WINDOW;
    if (index != Clipmap::NOT_IN_WINDOW && lateClaims < MAX_LATE_CLAIMS &&
        peek(&cache.entries[index]) == ENTRY_MISSING) {
      ++lateClaims;
      onMiss.ahead(cache, level + 1, cache.clipmap.globalBrick(level + 1, parent),
                   &cache.entries[index]);
    }
    // Nothing to show: the ray passes through while it may still claim (the chain it would have
    // waited on), then ends rather than march on to the scene's end through bricks that are not
    // there (what lies behind them is not what the exact ray would show either).
    if (lateClaims >= MAX_LATE_CLAIMS) b.state = BrickState::End;
    return b;
  }

  // The nearest resident coarser ancestor of a brick, at most `levels` above it, or the brick
  // itself as an empty one when none is: what stands in for a brick that is not resident.
  GVDP_HD BrickLookup standIn(int level, Vec3i brick, int levels = STAND_INS_ANY) const {
    Vec3i a = brick;
    const int top = levels < lod.levels - level ? level + 1 + levels : lod.levels;
    for (int up = level + 1; up < top; ++up) {
      a = halfFloor(a);
      uint32_t* at = entryOf(up, a);
      uint32_t ea = peek(at);
      if (shown(ea)) return shownBrick(at, ea, up, a);
    }
    return {BrickState::Empty, 0u, level, brick};
  }

  // A sample in a clear cell is zero without a read (the pool tests it).
  GVDP_HD Vec4f read(const BrickLookup& b, Vec3f p) const {
    Vec3i origin{b.brick.x * BRICK_WIDTH, b.brick.y * BRICK_WIDTH, b.brick.z * BRICK_WIDTH};
    return pool.template sample<READS>(b.slot, origin, lod.inVoxels(p, b.level), b.occupancy);
  }

  GVDP_HD Vec4f sample(const BrickLookup& b, Vec3f p) {
    ++samples;
    return read(b, p);
  }

  // Samples read by other lanes for this march (render/march_warp.cuh).
  GVDP_HD void countSamples(uint32_t n) {
    samples += n;
  }
};

}  // namespace gvdp::detail
