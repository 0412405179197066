#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <barrier>
#include <bit>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "gvdp/cache/brick_cache_cpu.h"
#include "gvdp/cache/cached_access.h"
#include "gvdp/cache/produce.h"
#include "gvdp/cache/table_boxes.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {

namespace {

// Algorithm 2 for one brick of perlin on this thread.
void produce(BrickCacheCpu& cache, const CacheView& view, const BrickKey& key) {
  produceBrick<BRICK_SAMPLE_COUNT>(ThreadScope{}, findScene("perlin").world, view, cache.pool(),
                                   key);
}

FrameSetup frameAt(Vec3d position, int index) {
  const SceneInfo& scene = findScene("perlin");
  return makeFrame({position, 0.3f, 0.0f}, scene.world.voxelSize0(), 64, 40, 5, index);
}

// Marches a ray of frame f from the eye, producing on this thread the bricks it asks for (then
// onProduced(key) for each), until it finishes: its state, the colour the march gave while the
// cache filled.
template <class World, class OnProduced>
RayState marchFilling(const Ray& ray, const FrameSetup& f, BrickCacheCpu& cache, const World& world,
                      OnProduced onProduced) {
  CacheView v = cache.view();
  BrickPool pool = cache.pool();
  RayState s = initialRayState();
  for (;;) {
    CachedAccess<BrickPool> access{v, pool, f.lod};
    if (march(ray, f.lod, s, access) == MarchResult::Finished) return s;
    for (uint32_t r = 0; r < v.counters[COUNTER_REQUESTS]; ++r) {
      BrickKey key = cache.requests()[r];
      produceBrick<BRICK_SAMPLE_COUNT>(ThreadScope{}, world, v, pool, key);
      onProduced(key);
    }
    cache.clearRequests();
  }
}

// Every resident slot is mapped by exactly one in-window entry and maps back to it; nothing is
// left in production. At a frame's start (`settled`) no entry is marked fresh.
void expectConsistent(const BrickCacheCpu& c, bool settled) {
  const Clipmap& m = c.clipmap();
  std::set<uint32_t> seen;
  for (size_t i = 0; i < c.entries().size(); ++i) {
    uint32_t entry = c.entries()[i];
    ASSERT_NE(entry, ENTRY_IN_PRODUCTION) << "entry " << i;
    if (!isSlot(entry)) continue;
    if (settled) {
      ASSERT_FALSE(isFresh(entry)) << "entry " << i << " still fresh after the frame's end";
    }
    uint32_t e = slotOf(entry);
    ASSERT_LT(e, c.poolBricks());
    ASSERT_TRUE(seen.insert(e).second) << "slot " << e << " mapped twice";
    const BrickKey& k = c.inverse()[e];
    ASSERT_NE(k.level, NO_LEVEL) << "slot " << e << " mapped but unowned";
    EXPECT_EQ(m.entryIndex(k.level, k.brick), i);
    EXPECT_TRUE(m.inWindow(k.level, k.brick)) << "resident brick outside its window";
  }
  for (uint32_t s = 0; s < c.poolBricks(); ++s) {
    if (c.inverse()[s].level != NO_LEVEL) {
      EXPECT_TRUE(seen.count(s)) << "slot " << s << " owned but unmapped";
    }
  }
}

// Requests and produces the bricks under random samples around the eye, as rays would.
void touchRandomBricks(BrickCacheCpu& c, const FrameSetup& f, std::mt19937& rng, int n) {
  CacheView v = c.view();
  BrickPool pool = c.pool();
  CachedAccess<BrickPool> access{v, pool, f.lod};
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < n; ++i) {
    int level = static_cast<int>(rng() % static_cast<unsigned>(f.lod.levels));
    float reach = f.lod.levelEnd(level) * 0.9f;
    Vec3f p = f.eye + Vec3f{u(rng), u(rng), u(rng)} * reach;
    access.lookup(level, floorToInt(p / f.lod.voxelSize(level) * (1.0f / BRICK_WIDTH)));
    // The queue holds one request per ray of a pass: produce in batches below that.
    if (v.counters[COUNTER_REQUESTS] + 1 >= v.requestCapacity || i + 1 == n) {
      uint32_t requests = v.counters[COUNTER_REQUESTS];
      for (uint32_t r = 0; r < requests; ++r) produce(c, v, c.requests()[r]);
      c.clearRequests();
    }
  }
}

}  // namespace

TEST(Cache, InvariantsHoldOverRandomCameraSequences) {
  std::mt19937 rng(17);
  BrickCacheCpu cache(300);  // small: forces LRU evictions
  Vec3d eye{10.5, 8.0, 0.5};
  std::uniform_real_distribution<double> step(-3.0, 3.0);
  uint64_t evicted = 0, produced = 0;
  for (int frame = 0; frame < 40; ++frame) {
    eye = eye + Vec3d{step(rng), step(rng) * 0.2, step(rng)} * (frame % 7 == 6 ? 30.0 : 1.0);
    FrameSetup f = frameAt(eye, frame);
    cache.beginFrame(f);
    expectConsistent(cache, true);
    touchRandomBricks(cache, f, rng, 400);
    expectConsistent(cache, false);
    evicted += cache.frameStats().evicted;
    produced += cache.frameStats().produced;
  }
  EXPECT_GT(produced, 300u) << "the test must overflow the pool";
  EXPECT_GT(evicted, 0u);
}

TEST(Cache, SlabsLeavingTheWindowAreResetAndTheirSlotsFreed) {
  BrickCacheCpu cache(4096);
  // The eye one unit above perlin's ground: level-0 bricks around it hold the surface.
  Vec3d eye = findScene("perlin").start.position - Vec3d{0.0, 4.0, 0.0};
  FrameSetup f0 = frameAt(eye, 0);
  cache.beginFrame(f0);
  CacheView v = cache.view();
  const Clipmap& m = cache.clipmap();
  Vec3i centre = floorToInt(f0.eye / (f0.lod.voxelSize(0) * BRICK_WIDTH));
  for (int z = -4; z <= 4; ++z)
    for (int y = -4; y <= 4; ++y)
      for (int x = -4; x <= 4; ++x)
        produce(cache, v, {m.globalBrick(0, centre + Vec3i{x, y, z}), 0});
  std::vector<BrickKey> level0;
  for (uint32_t s = 0; s < cache.poolBricks(); ++s)
    if (cache.inverse()[s].level == 0) level0.push_back(cache.inverse()[s]);
  ASSERT_FALSE(level0.empty());
  // Move far along x: every level-0 brick leaves the level-0 window.
  double far = 2.0 * cache.clipmap().width * BRICK_WIDTH * f0.lod.voxelSize(0);
  FrameSetup f1 = frameAt(eye + Vec3d{far, 0.0, 0.0}, 1);
  cache.beginFrame(f1);
  expectConsistent(cache, true);
  for (const BrickKey& k : level0) {
    EXPECT_FALSE(cache.clipmap().inWindow(0, k.brick));
    EXPECT_EQ(cache.entries()[cache.clipmap().entryIndex(0, k.brick)], ENTRY_MISSING);
  }
  for (uint32_t s = 0; s < cache.poolBricks(); ++s) EXPECT_NE(cache.inverse()[s].level, 0);
  EXPECT_GE(cache.frameStats().evicted, level0.size());
}

// A brick published in a frame is marked fresh until the frame ends (brick_key.h: ENTRY_FRESH;
// readers that run while bricks are published acquire only those), then holds its plain slot:
// the next beginFrame and a mid-frame refill settle the marks of every slot taken from the free
// list, and no other entry changes. A lookup reads the same brick through a fresh entry or a
// settled one, coherent or read-only.
TEST(Cache, FreshMarksLastTheFrameThatPublished) {
  BrickCacheCpu cache(4096);
  Vec3d eye = findScene("perlin").start.position - Vec3d{0.0, 4.0, 0.0};
  FrameSetup f = frameAt(eye, 0);
  cache.beginFrame(f);
  const Clipmap& m = cache.clipmap();
  Vec3i centre = floorToInt(f.eye / (f.lod.voxelSize(0) * BRICK_WIDTH));
  std::vector<Vec3i> locals;  // level-0 bricks around the eye, local coordinates
  for (int z = -2; z <= 2; ++z)
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) locals.push_back(centre + Vec3i{x, y, z});
  auto keyOf = [&](Vec3i local) { return BrickKey{m.globalBrick(0, local), 0}; };
  auto entryOf = [&](Vec3i local) { return cache.entries()[m.entryIndex(0, keyOf(local).brick)]; };
  // The slot a lookup finds, and its sample at the brick's centre, read as READS reads.
  auto read = [&]<PoolReads READS>(Vec3i local) {
    CacheView view = cache.view();
    BrickPool pool = cache.pool();
    CachedAccess<BrickPool, QueueRequest, READS, false> access{view, pool, f.lod};
    BrickLookup b = access.find(0, local);
    EXPECT_EQ(b.state, BrickState::Resident);
    Vec3f centreVoxel{local.x * 8.0f + 4.0f, local.y * 8.0f + 4.0f, local.z * 8.0f + 4.0f};
    return std::pair{b.slot, access.sample(b, centreVoxel * f.lod.voxelSize(0)).w};
  };
  size_t half = locals.size() / 2;
  CacheView v = cache.view();
  for (size_t i = 0; i < half; ++i) produce(cache, v, keyOf(locals[i]));
  std::map<size_t, std::pair<uint32_t, float>> resident;  // brick -> slot, sample
  for (size_t i = 0; i < half; ++i) {
    uint32_t e = entryOf(locals[i]);
    if (!isSlot(e)) continue;
    EXPECT_TRUE(isFresh(e)) << "a brick published in the running frame is fresh";
    auto coherent = read.template operator()<PoolReads::Coherent>(locals[i]);
    EXPECT_EQ(coherent.first, slotOf(e));
    EXPECT_EQ(read.template operator()<PoolReads::ReadOnly>(locals[i]), coherent);
    resident[i] = coherent;
  }
  ASSERT_GT(resident.size(), 10u) << "perlin's surface bricks around the eye";
  std::vector<uint32_t> before = cache.entries();

  // The next frame, same eye: every mark settled, every slot kept, EMPTY and CLEAR bricks still
  // EMPTY and CLEAR (with their boxes: table_boxes.h), nothing else changed; the lookups read the
  // same bricks.
  cache.beginFrame(frameAt(eye, 1));
  for (size_t i = 0; i < cache.entries().size(); ++i) {
    uint32_t was = before[i], now = cache.entries()[i];
    if (isSlot(was)) {
      EXPECT_EQ(now, slotOf(was)) << "entry " << i;
    } else if (was == ENTRY_CLEAR) {
      EXPECT_TRUE(isClearEntry(now)) << "entry " << i;
    } else if (isEmptyEntry(was)) {
      EXPECT_TRUE(isEmptyEntry(now)) << "entry " << i;
    } else {
      EXPECT_EQ(now, was) << "entry " << i;
    }
  }
  for (const auto& [i, slotSample] : resident) {
    EXPECT_EQ(read.template operator()<PoolReads::Coherent>(locals[i]), slotSample);
  }
  // Bricks published now are fresh, the earlier ones not; a mid-frame refill settles them.
  v = cache.view();
  for (size_t i = half; i < locals.size(); ++i) produce(cache, v, keyOf(locals[i]));
  int fresh = 0;
  for (size_t i = half; i < locals.size(); ++i) fresh += isFresh(entryOf(locals[i])) ? 1 : 0;
  EXPECT_GT(fresh, 10);
  for (const auto& [i, slotSample] : resident) EXPECT_EQ(entryOf(locals[i]), slotSample.first);
  cache.refill();
  for (Vec3i local : locals) EXPECT_FALSE(isSlot(entryOf(local)) && isFresh(entryOf(local)));
}

// A frame's end reads the slots' marks: a brick produced in it and never sampled is
// over-production; one prefetched for the next frame is counted as such and kept (the LRU sees
// the next frame); one prefetched for this frame and never sampled is over-production too, and
// one a ray stamped is neither. markPrefetched leaves a brick a ray sampled as sampled.
TEST(Cache, PrefetchedBricksAreCountedUsedOrUnusedByTheNextFrame) {
  constexpr uint32_t F = 7;
  uint32_t ts[6] = {
      F | TIMESTAMP_UNSAMPLED, (F + 1) | TIMESTAMP_MARKS, F | TIMESTAMP_MARKS, F, 3, 0};
  uint32_t counters[COUNTER_COUNT] = {};
  HostCacheOps::countUnsampled(ts, 6, F, counters);
  EXPECT_EQ(counters[COUNTER_UNSAMPLED], 2u);
  EXPECT_EQ(counters[COUNTER_PREFETCH_UNUSED], 1u);
  EXPECT_EQ(counters[COUNTER_PREFETCHED], 1u);
  const uint32_t after[6] = {F, (F + 1) | TIMESTAMP_MARKS, F, F, 3, 0};
  for (int s = 0; s < 6; ++s) EXPECT_EQ(ts[s], after[s]) << "slot " << s;
  EXPECT_EQ(lastUsedFrame(ts[1]), F + 1) << "the LRU keeps a prefetched brick through its frame";

  // markPrefetched on a published brick: only while no ray of the frame has stamped it.
  Clipmap clip = clipmapOf(makeFrame({{0.0, 0.0, 0.0}, 0.0f, 0.0f}, 0.01f, 64, 48, 4, 0));
  std::vector<uint32_t> entries(clip.entryCount(), ENTRY_MISSING), stamps = {0u, 0u};
  CacheView view{};
  view.clipmap = clip;
  view.entries = entries.data();
  view.timestamps = stamps.data();
  view.frame = F;
  BrickKey key{clip.windowOrigin[1] + Vec3i{1, 2, 3}, 1}, sampled{clip.windowOrigin[1], 1};
  entries[clip.entryIndex(key.level, key.brick)] = 0;
  entries[clip.entryIndex(sampled.level, sampled.brick)] = 1;
  stamps = {F | TIMESTAMP_UNSAMPLED, F};
  markPrefetched(view, key);
  markPrefetched(view, sampled);
  EXPECT_EQ(stamps[0], (F + 1) | TIMESTAMP_MARKS);
  EXPECT_EQ(stamps[1], F);
}

TEST(Cache, BrickBordersAreSeamless) {
  // Two neighbouring bricks, sampled exactly on their shared face, give the same value.
  BrickCacheCpu cache(1024);
  FrameSetup f = frameAt({10.5, 8.0, 0.5}, 0);
  cache.beginFrame(f);
  CacheView v = cache.view();
  const Clipmap& m = cache.clipmap();
  int level = 1, bothResident = 0, besideClear = 0;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 8.0f);
  for (int z = -3; z <= 3; ++z)
    for (int y = -12; y <= 3; ++y)
      for (int x = -3; x <= 3; ++x) {
        Vec3i a{x, y, z}, b{x + 1, y, z};
        BrickKey ka{m.globalBrick(level, a), level}, kb{m.globalBrick(level, b), level};
        produce(cache, v, ka);
        produce(cache, v, kb);
        uint32_t ea = cache.entries()[m.entryIndex(level, ka.brick)];
        uint32_t eb = cache.entries()[m.entryIndex(level, kb.brick)];
        // A CLEAR brick samples zero (brick_key.h): its resident neighbour must too, on the face.
        if (!(isSlot(ea) || isClearEntry(ea)) || !(isSlot(eb) || isClearEntry(eb))) continue;
        if (isClearEntry(ea) && isClearEntry(eb)) continue;
        (isSlot(ea) && isSlot(eb) ? bothResident : besideClear) += 20;
        BrickPool pool = cache.pool();
        auto sampleOf = [&](uint32_t e, Vec3i brick, Vec3f p) {
          return isClearEntry(e)
                     ? Vec4f{0, 0, 0, 0}
                     : pool.sample(slotOf(e), {8 * brick.x, 8 * brick.y, 8 * brick.z}, p);
        };
        for (int k = 0; k < 20; ++k) {
          Vec3f p{8.0f * (x + 1), 8.0f * y + u(rng), 8.0f * z + u(rng)};  // on the face, voxels
          Vec4f ca = sampleOf(ea, a, p);
          Vec4f cb = sampleOf(eb, b, p);
          EXPECT_EQ(ca.x, cb.x);
          EXPECT_EQ(ca.w, cb.w);
        }
      }
  EXPECT_GT(bothResident, 50) << "no pair of resident neighbours found";
  EXPECT_GT(besideClear, 50) << "no resident brick beside a CLEAR one";
}

TEST(Cache, EmptyEntriesAreDistinctAndDecode) {
  std::mt19937 rng(4);
  for (int i = 0; i < 2000; ++i) {
    EmptyReachCodes c{};
    for (int& f : c.face) f = static_cast<int>(rng() % (MAX_EMPTY_REACH_CODE + 1u));
    if (i == 1) c = {{15, 15, 15, 15, 15, 15}};
    uint32_t e = emptyEntry(c);
    ASSERT_TRUE(isEmptyEntry(e)) << e;
    EXPECT_FALSE(isSlot(e));
    EXPECT_EQ(productionTaskOf(e), -1);
    EXPECT_NE(e, ENTRY_MISSING);
    EXPECT_NE(e, ENTRY_IN_PRODUCTION);
    EmptyReach r = emptyReach(e);
    int reach[6] = {r.below.x, r.below.y, r.below.z, r.above.x, r.above.y, r.above.z};
    for (int f = 0; f < 6; ++f) EXPECT_EQ(reach[f], emptyReachOfCode(c.face[f])) << f;
  }
  // The codes' reaches grow, by at most 1.5x from 2 on, up to 192 bricks.
  for (int c = 1; c <= MAX_EMPTY_REACH_CODE; ++c) {
    int lo = emptyReachOfCode(c - 1), hi = emptyReachOfCode(c);
    EXPECT_GT(hi, lo) << c;
    if (lo >= 2) {
      EXPECT_LE(2 * hi, 3 * lo) << c;
    }
  }
  EXPECT_EQ(emptyReachOfCode(MAX_EMPTY_REACH_CODE), 192);
  EXPECT_EQ(emptyEntry(EmptyReachCodes{}), ENTRY_EMPTY);
  for (uint32_t e : {ENTRY_MISSING, ENTRY_IN_PRODUCTION, ENTRY_EMPTY - 1u, 0u, MAX_SLOTS - 1u,
                     ENTRY_PRODUCTION_TASK + MAX_PRODUCTION_TASKS - 1u, ENTRY_EMPTY + 0x1000000u})
    EXPECT_FALSE(isEmptyEntry(e)) << e;
  EXPECT_EQ(clearEntry(EmptyReachCodes{}), ENTRY_CLEAR);
  for (uint32_t e : {ENTRY_MISSING, ENTRY_IN_PRODUCTION, ENTRY_EMPTY,
                     ENTRY_EMPTY | EMPTY_CODES_MASK, 0u, MAX_SLOTS - 1u,
                     ENTRY_PRODUCTION_TASK + MAX_PRODUCTION_TASKS - 1u, ENTRY_CLEAR + 0x1000000u})
    EXPECT_FALSE(isClearEntry(e)) << e;
  EXPECT_TRUE(isClearEntry(ENTRY_CLEAR | EMPTY_CODES_MASK));
}

// The bricks of the box EMPTY entry `entry` of brick `key` names that do not evaluate empty: of
// its two opposite corners and `inside` bricks drawn in it, every `stride`-th sample must be empty
// and transparent (`zeroOnly`, a CLEAR entry's box: transparent). "" when all are; else the
// first failing sample.
std::string nonEmptyInBox(const BuiltinScene& world, const BrickKey& key, uint32_t entry,
                          std::mt19937& rng, int inside, int stride, bool zeroOnly = false) {
  EmptyReach r = emptyReach(entry);
  auto in = [&](int below, int above) {
    return -below + static_cast<int>(rng() % (below + above + 1));
  };
  for (int k = 0; k < 2 + inside; ++k) {
    Vec3i d = k == 0   ? Vec3i{-r.below.x, -r.below.y, -r.below.z}
              : k == 1 ? r.above
                       : Vec3i{in(r.below.x, r.above.x), in(r.below.y, r.above.y),
                               in(r.below.z, r.above.z)};
    BrickKey brick{key.brick + d, key.level};
    for (int s = 0; s < BRICK_SAMPLE_COUNT; s += stride) {
      VoxelSample v = produceBrickSample(world, brick, s);
      if ((!zeroOnly && !v.empty) || v.rgba != 0u)
        return "level " + std::to_string(key.level) + " offset (" + std::to_string(d.x) + ", " +
               std::to_string(d.y) + ", " + std::to_string(d.z) + ") sample " + std::to_string(s);
    }
  }
  return "";
}

// The box an EMPTY entry names is empty: every brick in it, evaluated sample by sample, would be
// EMPTY (all samples flagged empty and transparent), for each scene with a box bound; and the
// boxes stretch (some face reaches further than the one across from it). Bricks empty by their
// samples only (near the surface, where the bound does not clear the brick itself) grow boxes
// too: growth tests only the slabs it adds. A box grows only through faces a ray from the eye
// can leave it by (produce.h: exitFacesFrom).
TEST(Cache, EmptyBoxesNameEmptyBricks) {
  std::mt19937 rng(5);
  const Clipmap clipmap = clipmapOf(frameAt({0.3, 3.0, 0.3}, 0));
  auto emptyBySamples = [](const BuiltinScene& world, BrickKey key) {
    for (int s = 0; s < BRICK_SAMPLE_COUNT; ++s) {
      VoxelSample v = produceBrickSample(world, key, s);
      if (!v.empty || v.rgba != 0u) return false;
    }
    return true;
  };
  for (const char* name : {"perlin", "fbm", "forest", "random-spheres"}) {
    const BuiltinScene& world = findScene(name).world;
    int boxes = 0, bigger = 0, stretched = 0, bySamples = 0;
    for (int i = 0; i < 600 && boxes < 80; ++i) {
      int level = static_cast<int>(rng() % 8u);
      auto coord = [&](int lo, int hi) { return lo + static_cast<int>(rng() % (hi - lo)); };
      // Every other key near the ground (y from -4 to 12 bricks at level 0), the others above.
      int y = i % 2 ? coord(-4, 400) >> level : coord(-4, 12) >> level;
      BrickKey key{{coord(-40, 40), y, coord(-40, 40)}, level};
      bool bounded = brickBoundedEmpty(world, key);
      if (!bounded && !emptyBySamples(world, key)) continue;
      uint32_t entry = 0;
      growEmptyBoxes(ThreadScope{}, world, key, clipmap, [&](const BrickKey&, uint32_t e) {
        entry = e;
        return false;
      });
      EmptyReach r = emptyReach(entry);
      Vec3i fromEye = key.brick - clipmap.eyeBrick(level);
      ASSERT_TRUE((fromEye.x <= 0 || r.below.x == 0) && (fromEye.x >= 0 || r.above.x == 0) &&
                  (fromEye.y <= 0 || r.below.y == 0) && (fromEye.y >= 0 || r.above.y == 0) &&
                  (fromEye.z <= 0 || r.below.z == 0) && (fromEye.z >= 0 || r.above.z == 0))
          << name << ": a box grew toward the eye, level " << level;
      if (r.below == Vec3i{0, 0, 0} && r.above == Vec3i{0, 0, 0}) continue;
      ++boxes;
      bySamples += !bounded;
      bigger += r.below.x + r.above.x + r.below.y + r.above.y + r.below.z + r.above.z > 6;
      stretched += !(r.below == r.above);
      ASSERT_EQ(nonEmptyInBox(world, key, entry, rng, 2, 1), "") << name;
    }
    EXPECT_GE(boxes, 20) << name << ": too few empty boxes found";
    if (std::string(name) == "perlin") {
      EXPECT_GT(bySamples, 0) << "no box grown from the samples";
    }
    EXPECT_GT(bigger, 0) << name << ": no box beyond one brick per face";
    EXPECT_GT(stretched, 0) << name << ": no box reaching further on one side";
  }
}

// An empty brick's commit marks the MISSING bricks of its box within BOX_MEMBER_REACH of it EMPTY
// (produce.h: markBoxMembers), each with a box inside the brick's that names empty bricks only
// (corners and a brick inside evaluated sample by sample); a brick claimed before keeps its
// state, and the bricks just past the box or the reach stay MISSING. COUNTER_MARKED counts them.
TEST(Cache, EmptyBricksMarkTheMembersOfTheirBoxEmpty) {
  std::mt19937 rng(7);
  for (const char* name : {"perlin", "fbm", "forest", "random-spheres"}) {
    const SceneInfo& info = findScene(name);
    FrameSetup f = makeFrame(info.start, info.world.voxelSize0(), 64, 40, 5, 0);
    int boxes = 0, marked = 0, clamped = 0;
    for (int i = 0; i < 400 && boxes < 12; ++i) {
      BrickCacheCpu cache(64);
      cache.beginFrame(f);
      CacheView v = cache.view();
      int level = static_cast<int>(rng() % static_cast<unsigned>(f.lod.levels));
      Vec3i eye = v.clipmap.eyeBrick(level);
      auto near = [&] { return static_cast<int>(rng() % 9u) - 4; };
      BrickKey key{eye + Vec3i{near(), near(), near()}, level};
      if (v.clipmap.windowEntry(level, key.brick) == Clipmap::NOT_IN_WINDOW) continue;
      auto flagged = [&] {
        for (int s = 0; s < BRICK_SAMPLE_COUNT; ++s)
          if (!produceBrickSample(info.world, key, s).empty) return false;
        return true;
      };
      if (!brickBoundedEmpty(info.world, key) && !flagged()) continue;
      uint32_t own = 0;
      growEmptyBoxes(ThreadScope{}, info.world, key, v.clipmap, [&](const BrickKey&, uint32_t e) {
        own = e;
        return false;
      });
      EmptyReach r = emptyReach(own);
      auto lim = [](int reach) { return std::min(reach, BOX_MEMBER_REACH); };
      Vec3i lo{-lim(r.below.x), -lim(r.below.y), -lim(r.below.z)};
      Vec3i hi{lim(r.above.x), lim(r.above.y), lim(r.above.z)};
      if (lo == Vec3i{0, 0, 0} && hi == Vec3i{0, 0, 0}) continue;
      ++boxes;
      clamped += !(hi == r.above) || !(lo == Vec3i{-r.below.x, -r.below.y, -r.below.z});
      Vec3i claimed = hi.x != 0   ? Vec3i{hi.x, 0, 0}
                      : hi.y != 0 ? Vec3i{0, hi.y, 0}
                      : hi.z != 0 ? Vec3i{0, 0, hi.z}
                                  : lo;
      auto entryAt = [&](Vec3i o) -> uint32_t* {
        uint32_t index = v.clipmap.windowEntry(level, key.brick + o);
        return index == Clipmap::NOT_IN_WINDOW ? nullptr : &v.entries[index];
      };
      if (uint32_t* e = entryAt(claimed)) *e = ENTRY_IN_PRODUCTION;
      uint32_t before = v.counters[COUNTER_MARKED];
      publishEmpty(ThreadScope{}, info.world, v, key);
      ASSERT_EQ(cache.entries()[v.clipmap.entryIndex(level, key.brick)], own) << name;
      int here = 0;
      for (int z = lo.z - 1; z <= hi.z + 1; ++z)
        for (int y = lo.y - 1; y <= hi.y + 1; ++y)
          for (int x = lo.x - 1; x <= hi.x + 1; ++x) {
            Vec3i o{x, y, z};
            uint32_t* e = entryAt(o);
            if (e == nullptr || o == Vec3i{0, 0, 0}) continue;
            bool inside =
                x >= lo.x && x <= hi.x && y >= lo.y && y <= hi.y && z >= lo.z && z <= hi.z;
            if (o == claimed) {
              ASSERT_EQ(*e, ENTRY_IN_PRODUCTION) << name << ": a claimed brick marked";
            } else if (!inside) {
              ASSERT_EQ(*e, ENTRY_MISSING) << name << ": a brick past the box or reach marked";
            } else {
              ASSERT_TRUE(isEmptyEntry(*e)) << name << ": a member left unmarked";
              EmptyReach m = emptyReach(*e);
              ASSERT_TRUE(x - m.below.x >= -r.below.x && x + m.above.x <= r.above.x &&
                          y - m.below.y >= -r.below.y && y + m.above.y <= r.above.y &&
                          z - m.below.z >= -r.below.z && z + m.above.z <= r.above.z)
                  << name << ": a member's box leaves the brick's";
              ASSERT_EQ(nonEmptyInBox(info.world, {key.brick + o, level}, *e, rng, 1, 7), "")
                  << name;
              ++here;
            }
          }
      EXPECT_EQ(v.counters[COUNTER_MARKED] - before, static_cast<uint32_t>(here)) << name;
      marked += here;
    }
    EXPECT_GE(boxes, 4) << name << ": too few empty boxes with members found";
    EXPECT_GT(marked, 0) << name;
    if (std::string(name) == "perlin") {
      EXPECT_GT(clamped, 0) << "no box past the members' reach";
    }
  }
}

// N CPU threads as one cooperation scope in lockstep (base/cooperation.h), for the algorithms a
// GPU warp or block runs as a group: any() meets at barriers. It counts the group's rounds (any).
struct LockstepShared {
  explicit LockstepShared(int n) : barrier(n) {}
  std::barrier<> barrier;
  std::atomic<uint32_t> word{0};
  int rounds = 0;
};

struct LockstepScope {
  int member, members;
  LockstepShared* shared;
  int rank() const { return member; }
  int size() const { return members; }
  uint32_t any(uint32_t bits) const {
    shared->barrier.arrive_and_wait();  // every member has read the last answer
    if (member == 0) {
      shared->word = 0u;
      ++shared->rounds;
    }
    shared->barrier.arrive_and_wait();
    shared->word.fetch_or(bits);
    shared->barrier.arrive_and_wait();
    return shared->word;
  }
  bool all(bool v) const { return any(v ? 0u : 1u) == 0u; }
  void sync() const { shared->barrier.arrive_and_wait(); }
};

// Runs f(scope) on n threads as one group; returns the group's rounds.
template <class F>
int runLockstep(int n, F f) {
  LockstepShared shared(n);
  std::vector<std::thread> threads;
  for (int i = 0; i < n; ++i) threads.emplace_back([&, i] { f(LockstepScope{i, n, &shared}); });
  for (std::thread& t : threads) t.join();
  return shared.rounds;
}

// A warp's 32 members grow EMPTY boxes ahead (produce.h: GROW_AHEAD_MEMBERS): each box and each
// ancestor's box it marks names empty bricks only (corners and bricks inside it evaluated sample
// by sample), as a lone member's do, in fewer rounds.
TEST(Cache, GroupsGrowEmptyBoxesAheadInFewerRounds) {
  std::mt19937 rng(11);
  const Clipmap clipmap = clipmapOf(frameAt({0.3, 3.0, 0.3}, 0));
  for (const char* name : {"perlin", "fbm", "forest", "random-spheres"}) {
    const BuiltinScene& world = findScene(name).world;
    int rounds[2] = {0, 0}, grown = 0, ancestors = 0;
    long reach[2] = {0, 0};
    for (int i = 0; i < 200 && grown < 24; ++i) {
      int level = static_cast<int>(rng() % 6u);
      auto coord = [&](int lo, int hi) { return lo + static_cast<int>(rng() % (hi - lo)); };
      int y = i % 2 ? coord(-4, 400) >> level : coord(-4, 12) >> level;
      BrickKey key{{coord(-40, 40), y, coord(-40, 40)}, level};
      if (!brickBoundedEmpty(world, key)) continue;
      ++grown;
      for (int g = 0; g < 2; ++g) {
        std::vector<std::pair<BrickKey, uint32_t>> boxes;
        rounds[g] += runLockstep(g ? 32 : 1, [&](const LockstepScope& group) {
          growEmptyBoxes(group, world, key, clipmap, [&](const BrickKey& k, uint32_t e) {
            if (group.rank() == 0) boxes.push_back({k, e});
            return k.level + 1 < clipmap.levels;
          });
        });
        ancestors += static_cast<int>(boxes.size()) - 1;
        for (const auto& [k, e] : boxes) {
          EmptyReach r = emptyReach(e);
          reach[g] += r.below.x + r.above.x + r.below.y + r.above.y + r.below.z + r.above.z;
          ASSERT_EQ(nonEmptyInBox(world, k, e, rng, 1, 7), "")
              << name << (g ? " (32 members)" : " (1 member)");
        }
      }
    }
    EXPECT_GE(grown, 12) << name;
    EXPECT_GT(ancestors, 0) << name << ": no ancestor marked";
    EXPECT_LT(rounds[1] * 4, rounds[0] * 3)
        << name << ": rounds " << rounds[1] << " vs " << rounds[0];
    EXPECT_GT(reach[1] * 10, reach[0] * 9) << name << ": reach " << reach[1] << " vs " << reach[0];
    std::printf("%s: %d boxes, rounds %d (32 members) vs %d (1), reach %ld vs %ld\n", name, grown,
                rounds[1], rounds[0], reach[1], reach[0]);
  }
}

// The march's division-free lookup agrees with entryIndex inside the window and refuses
// everything outside it, for windows at negative and positive coordinates.
TEST(Cache, WindowEntryIsEntryIndexInsideTheWindow) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5000.0, 5000.0);
  int inside = 0, outside = 0;
  for (int frame = 0; frame < 6; ++frame) {
    Clipmap m = clipmapOf(frameAt({u(rng), u(rng) * 0.01, u(rng)}, frame));
    for (int i = 0; i < 4000; ++i) {
      int level = static_cast<int>(rng() % static_cast<unsigned>(m.levels));
      Vec3i d{static_cast<int>(rng() % (m.width + 4u)) - 2,
              static_cast<int>(rng() % (m.width + 4u)) - 2,
              static_cast<int>(rng() % (m.width + 4u)) - 2};
      Vec3i g = m.windowOrigin[level] + d;
      uint32_t e = m.windowEntry(level, g);
      ASSERT_EQ(e, m.windowEntryOfLocal(level, g - m.localOriginBrick[level]));
      if (m.inWindow(level, g)) {
        ++inside;
        ASSERT_EQ(e, m.entryIndex(level, g)) << "level " << level;
      } else {
        ++outside;
        ASSERT_EQ(e, Clipmap::NOT_IN_WINDOW);
      }
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 100);
}

// A sample's cells are those whose reads (sample indices 2c..2c+3 per axis) include it.
TEST(Cache, OccupancyCellsOfASampleAreItsDefinition) {
  for (int s = 0; s < BRICK_SAMPLE_COUNT; ++s) {
    Vec3i i = brickSampleIndex(s);
    uint64_t expected = 0;
    for (int c = 0; c < 64; ++c) {
      Vec3i cell{c % 4, (c / 4) % 4, c / 16};
      auto reads = [](int index, int at) { return index >= 2 * at && index <= 2 * at + 3; };
      if (reads(i.x, cell.x) && reads(i.y, cell.y) && reads(i.z, cell.z))
        expected |= uint64_t{1} << c;
    }
    ASSERT_EQ(occupancyCellsOf(i), expected) << s;
  }
}

// Production's occupancy is exact per cell: a clear cell has only zero samples in its reads, a
// set one at least one nonzero; and a position in a clear cell samples zero.
TEST(Cache, OccupancyCellsAreExact) {
  BrickCacheCpu cache(256);
  FrameSetup f = frameAt({10.5, 8.0, 0.5}, 0);
  cache.beginFrame(f);
  CacheView v = cache.view();
  const Clipmap& m = cache.clipmap();
  BrickPool pool = cache.pool();
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 8.0f);
  int bricks = 0, clear = 0, set = 0;
  for (int level = 0; level < 3; ++level)
    for (int y = -6; y <= 2; ++y)
      for (int x = -3; x <= 3; ++x) {
        Vec3i local{x, y, 1};
        BrickKey key{m.globalBrick(level, local), level};
        produce(cache, v, key);
        uint32_t entry = cache.entries()[m.entryIndex(level, key.brick)];
        if (!isSlot(entry)) continue;
        uint32_t slot = slotOf(entry);
        ++bricks;
        uint64_t occupancy = pool.occupancy[slot];
        const Rgba8* samples = pool.texels + size_t{slot} * BRICK_SAMPLE_COUNT;
        for (int c = 0; c < 64; ++c) {
          Vec3i cell{c % 4, (c / 4) % 4, c / 16};
          bool nonzero = false;
          for (int k = 0; k < 64; ++k) {
            Vec3i i{2 * cell.x + k % 4, 2 * cell.y + (k / 4) % 4, 2 * cell.z + k / 16};
            nonzero = nonzero || samples[(i.z * BRICK_SAMPLES + i.y) * BRICK_SAMPLES + i.x] != 0u;
          }
          ASSERT_EQ(nonzero, ((occupancy >> c) & 1u) != 0) << "slot " << slot << " cell " << c;
          (nonzero ? set : clear)++;
        }
        Vec3i origin{8 * local.x, 8 * local.y, 8 * local.z};
        // A sample told the occupancy is the read one, bit for bit (zero where it skips the read),
        // on the faces too.
        std::uniform_real_distribution<float> face(-0.01f, 8.01f);
        for (int k = 0; k < 400; ++k) {
          Vec3f at{origin.x + face(rng), origin.y + face(rng), origin.z + face(rng)};
          Vec4f read = pool.sample(slot, origin, at),
                told = pool.sample(slot, origin, at, occupancy);
          ASSERT_EQ(std::memcmp(&read, &told, sizeof read), 0) << "slot " << slot << " k " << k;
        }
        for (int k = 0; k < 200; ++k) {
          Vec3f p{u(rng), u(rng), u(rng)};
          if (occupancy & occupancyCellsBetween(p, p)) continue;
          Vec4f c =
              pool.sample(slot, origin, Vec3f{origin.x + p.x, origin.y + p.y, origin.z + p.z});
          ASSERT_EQ(c.w, 0.0f);
          ASSERT_EQ(c.x + c.y + c.z, 0.0f);
        }
      }
  EXPECT_GT(bricks, 5) << "no resident brick near the surface";
  EXPECT_GT(clear, 0);
  EXPECT_GT(set, 0);
}

// The cell a sample tests is the cell of the block it reads: it holds the two samples read along
// each axis, for every block index a position in the brick can give (0..8 with the border).
TEST(Cache, OccupancyBitOfBlockHoldsTheBlock) {
  for (int j = 0; j <= 8; ++j) {
    uint64_t bit = occupancyBitOfBlock({j, j, j});
    int c = std::countr_zero(bit) % OCCUPANCY_CELLS;
    EXPECT_LE(2 * c, j) << j;          // cell c holds samples 2c..2c+3
    EXPECT_LE(j + 1, 2 * c + 3) << j;  // the block's second sample too
    EXPECT_EQ(bit, occupancyBitOfBlock({j, 0, 0}) << (c * (OCCUPANCY_CELLS + 16)));
  }
}

// The cells between two positions hold the cell of every position on the segment between them
// (what lets the march leave a brick whose samples ahead all lie in clear cells), and are the box
// of cells between the two ends.
TEST(Cache, OccupancyCellsBetweenHoldTheSegment) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.25f, 8.25f);
  for (int k = 0; k < 20000; ++k) {
    Vec3f a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)};
    uint64_t between = occupancyCellsBetween(a, b);
    ASSERT_EQ(between, occupancyCellsBetween(b, a));
    ASSERT_EQ(std::popcount(occupancyCellsBetween(a, a)), 1) << k;  // a's cell alone
    ASSERT_EQ(between & occupancyCellsBetween(a, a), occupancyCellsBetween(a, a));
    ASSERT_EQ(between & occupancyCellsBetween(b, b), occupancyCellsBetween(b, b));
    uint64_t swept = 0;
    for (int i = 0; i <= 64; ++i) {
      Vec3f at = a + (b - a) * (static_cast<float>(i) / 64);
      swept |= occupancyCellsBetween(at, at);
    }
    ASSERT_EQ(between & swept, swept) << k;
    int span = 1;
    for (int axis = 0; axis < 3; ++axis) {
      float p = axis == 0   ? a.x
                : axis == 1 ? a.y
                            : a.z,
            q = axis == 0   ? b.x
                : axis == 1 ? b.y
                            : b.z;
      span *= std::abs(occupancyCell(p) - occupancyCell(q)) + 1;
    }
    ASSERT_EQ(std::popcount(between), span) << k;
  }
}

namespace {

// CachedAccess as if every cell of every resident brick were occupied: the march then reads every
// sample (no clear cell, no clear brick left early). A CLEAR brick has no samples to read: it stays
// as it is (its samples are zero: AllZeroBricksAreClearAndHoldNoSlot).
struct EveryCellOccupied : CachedAccess<BrickPool> {
  BrickLookup lookup(int level, Vec3i brick) {
    BrickLookup b = CachedAccess<BrickPool>::lookup(level, brick);
    if (b.slot != MAX_SLOTS) b.occupancy = ~uint64_t{0};
    return b;
  }
};

// CachedAccess whose resident bricks serve no run (render/march.h): a StandIn of the ray's own
// level is found again per sample, brick by brick, as the march did before runs.
struct NoRuns : CachedAccess<BrickPool> {
  BrickLookup lookup(int level, Vec3i brick) {
    BrickLookup b = CachedAccess<BrickPool>::lookup(level, brick);
    if (b.state == BrickState::Resident) b.state = BrickState::StandIn;
    return b;
  }
};

// CachedAccess as before CLEAR boxes: a CLEAR brick of the ray's level is a resident one whose
// cells are all clear, left alone (brick_key.h: ENTRY_CLEAR).
struct ClearBricksAlone : CachedAccess<BrickPool> {
  BrickLookup lookup(int level, Vec3i brick) {
    BrickLookup b = CachedAccess<BrickPool>::lookup(level, brick);
    if (b.state == BrickState::Empty && b.level == level &&
        isClearEntry(peek(entryOf(level, brick))))
      return clear(level, brick);
    return b;
  }
};

// CachedAccess as it is (expectSameMarches' makeA, makeB).
CachedAccess<BrickPool> plainAccess(const CacheView& v, const BrickPool& pool, const Lod& lod) {
  return {v, pool, lod};
}

// Fills the cache with what the rays of frame f ask for, then marches every ray twice from the
// full cache, with `a` and with `b` (accesses built from the view): the colours, bit for bit.
struct MarchOf {
  template <class Access>
  MarchResult operator()(const Ray& ray, const Lod& lod, RayState& s, Access& access) const {
    return march(ray, lod, s, access);
  }
};

// A CPU cache that has begun frame 0 at a scene's start, 96x60 with 6 levels: where the marches
// below are compared.
struct StartFrame {
  const SceneInfo& info;
  BrickCacheCpu cache;
  FrameSetup f;
  StartFrame(const char* scene, uint32_t poolBricks)
      : info(findScene(scene)),
        cache(poolBricks),
        f(makeFrame(info.start, info.world.voxelSize0(), 96, 60, 6, 0)) {
    cache.beginFrame(f);
  }
};

// ... and `marchB` marches b's (march() unless given); `sameCounts`: the samples and lookups too.
template <class A, class B, class MarchB = MarchOf>
void expectSameMarches(const char* scene, A makeA, B makeB, MarchB marchB = {},
                       bool sameCounts = false) {
  StartFrame start(scene, 30000);
  auto& [info, cache, f] = start;
  CacheView v = cache.view();
  BrickPool pool = cache.pool();
  for (int pixel = 0; pixel < f.width * f.height; ++pixel) {
    Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
    marchFilling(ray, f, cache, info.world, [](const BrickKey&) {});
    RayState sa = initialRayState(), sb = initialRayState();
    auto a = makeA(v, pool, f.lod);
    auto b = makeB(v, pool, f.lod);
    ASSERT_EQ(march(ray, f.lod, sa, a), MarchResult::Finished) << scene << " " << pixel;
    ASSERT_EQ(marchB(ray, f.lod, sb, b), MarchResult::Finished) << scene << " " << pixel;
    ASSERT_EQ(std::memcmp(&sa.colour, &sb.colour, sizeof(Vec4f)), 0) << scene << " " << pixel;
    if (!sameCounts) continue;
    ASSERT_EQ(a.samples, b.samples) << scene << " " << pixel;
    ASSERT_EQ(a.lookups, b.lookups) << scene << " " << pixel;
  }
}

}  // namespace

// A brick that is not resident stands in by its nearest shown ancestor (a slot or CLEAR), and
// only within the levels asked: the lookahead's prediction of where a ray becomes opaque
// (cache/lookahead.h), which pt's prefetch trusts one level up only.
TEST(Cache, StandInsAreTheNearestShownAncestorWithinTheLevelsAsked) {
  BrickCacheCpu cache(1000);
  FrameSetup f = frameAt(findScene("perlin").start.position, 0);
  cache.beginFrame(f);
  CacheView v = cache.view();
  CachedAccess<BrickPool> access{v, cache.pool(), f.lod};
  const Clipmap& m = v.clipmap;
  const Vec3i brick = m.eyeBrick(0) - m.globalBrick(0, {0, 0, 0});  // local, level 0
  const Vec3i parent = halfFloor(brick), grandparent = halfFloor(parent);
  auto show = [&](int level, Vec3i local) {
    uint32_t i = m.windowEntryOfLocal(level, local);
    ASSERT_NE(i, Clipmap::NOT_IN_WINDOW);
    v.entries[i] = ENTRY_CLEAR;
  };
  auto standInLevel = [&](int levels) {
    BrickLookup b = access.standIn(0, brick, levels);
    return b.level;
  };
  EXPECT_EQ(access.standIn(0, brick).state, BrickState::Empty) << "nothing shown: passed";
  show(2, grandparent);
  BrickLookup any = access.standIn(0, brick);
  EXPECT_EQ(any.level, 2);
  EXPECT_TRUE(any.brick == grandparent);
  EXPECT_EQ(standInLevel(STAND_INS_ANY), 2);
  EXPECT_EQ(standInLevel(2), 2);
  EXPECT_EQ(standInLevel(1), 0) << "the grandparent is two levels up";
  EXPECT_EQ(access.standIn(0, brick, 1).state, BrickState::Empty);
  EXPECT_EQ(standInLevel(0), 0);
  show(1, parent);
  EXPECT_EQ(standInLevel(1), 1);
  EXPECT_EQ(standInLevel(STAND_INS_ANY), 1) << "the nearest";
  EXPECT_EQ(standInLevel(0), 0);
}

// A brick produced with every sample zero but not flagged empty is published CLEAR: no slot taken,
// nothing written; one with a nonzero sample gets a slot and its cells. Every ray of a frame
// marches the same colour from the full cache as it did while the cache filled.
TEST(Cache, AllZeroBricksAreClearAndHoldNoSlot) {
  const SceneInfo& info = findScene("perlin");
  BrickCacheCpu cache(30000);
  FrameSetup f = frameAt(info.start.position, 0);
  cache.beginFrame(f);
  CacheView v = cache.view();
  BrickPool pool = cache.pool();
  int clear = 0, resident = 0;
  for (int pixel = 0; pixel < f.width * f.height; ++pixel) {
    Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
    RayState filling = marchFilling(ray, f, cache, info.world, [&](const BrickKey& key) {
      uint32_t e = cache.entries()[v.clipmap.entryIndex(key.level, key.brick)];
      if (isEmptyEntry(e)) return;
      bool zero = true, flagged = true;
      for (int s = 0; s < BRICK_SAMPLE_COUNT; ++s) {
        VoxelSample x = produceBrickSample(info.world, key, s);
        zero = zero && x.rgba == 0u;
        flagged = flagged && x.empty;
      }
      ASSERT_FALSE(flagged) << "an empty brick not published EMPTY";
      if (isClearEntry(e)) {
        ASSERT_TRUE(zero) << "a CLEAR brick with a nonzero sample, level " << key.level;
        ++clear;
      } else {
        ASSERT_TRUE(isSlot(e));
        ASSERT_FALSE(zero) << "an all-zero brick given slot " << slotOf(e);
        ASSERT_NE(pool.occupancy[slotOf(e)], 0u);
        ++resident;
      }
    });
    RayState again = initialRayState();
    CachedAccess<BrickPool> access{v, pool, f.lod};
    ASSERT_EQ(march(ray, f.lod, again, access), MarchResult::Finished) << pixel;
    ASSERT_EQ(std::memcmp(&again.colour, &filling.colour, sizeof(Vec4f)), 0) << pixel;
  }
  EXPECT_GT(clear, 0);
  EXPECT_GT(resident, 0);
  EXPECT_EQ(v.counters[COUNTER_CLEAR], static_cast<uint32_t>(clear));
  EXPECT_EQ(v.counters[COUNTER_PRODUCED], static_cast<uint32_t>(resident));
  // Only the resident bricks took a slot.
  EXPECT_EQ(v.counters[COUNTER_FREE_NEXT], static_cast<uint32_t>(resident));
}

// The EMPTY and CLEAR bricks of a frame grow boxes in the next frame, after its start, from the
// bricks the table knows (table_boxes.h). Every CLEAR box names bricks zero at its level, every
// EMPTY box bricks empty at every level: each brick of it, evaluated sample by sample (its corners
// and two inside), is all zero, and flagged empty for an EMPTY box. A ray leaves a box with one
// lookup: every ray marches the same colour, bit for bit, as it did while the cache filled, as it
// did from the full cache before the boxes grew, and as it does when it leaves each CLEAR brick
// alone, in fewer lookups than both.
TEST(Cache, TableBoxesNameZeroOrEmptyBricksAndCutLookupsNotColours) {
  std::mt19937 rng(6);
  for (const char* scene : {"perlin", "fbm"}) {
    StartFrame start(scene, 60000);
    auto& [info, cache, f] = start;
    CacheView v = cache.view();
    BrickPool pool = cache.pool();
    std::vector<Vec4f> filled;
    for (int pixel = 0; pixel < f.width * f.height; ++pixel)
      filled.push_back(marchFilling(f.primaryRay(pixel % f.width, pixel / f.width), f, cache,
                                    info.world, [](const BrickKey&) {})
                           .colour);
    const uint32_t listed = v.counters[COUNTER_LISTED];
    EXPECT_EQ(listed, v.counters[COUNTER_EMPTY] + v.counters[COUNTER_CLEAR]) << scene;
    // Every ray's march from the full cache, before the boxes grow: its colour and lookups.
    auto marchAll = [&](auto makeAccess, long& lookups) {
      for (int pixel = 0; pixel < f.width * f.height; ++pixel) {
        RayState s = initialRayState();
        auto access = makeAccess();
        Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
        ASSERT_EQ(march(ray, f.lod, s, access), MarchResult::Finished) << scene << " " << pixel;
        ASSERT_EQ(std::memcmp(&s.colour, &filled[pixel], sizeof(Vec4f)), 0) << scene << pixel;
        lookups += access.lookups;
      }
    };
    long before = 0;
    marchAll([&] { return CachedAccess<BrickPool>{v, pool, f.lod}; }, before);
    const std::vector<uint32_t> old = cache.entries();
    cache.beginFrame(f);  // the same frame again: the boxes grow
    v = cache.view();
    int boxes[2] = {0, 0}, grown[2] = {0, 0};  // CLEAR, EMPTY
    const Clipmap& m = cache.clipmap();
    for (int level = 0; level < m.levels; ++level)
      for (int z = 0; z < m.width; ++z)
        for (int y = 0; y < m.width; ++y)
          for (int x = 0; x < m.width; ++x) {
            Vec3i g = m.windowOrigin[level] + Vec3i{x, y, z};
            const uint32_t i = m.entryIndex(level, g), e = cache.entries()[i];
            const bool empty = isEmptyEntry(e);
            if (!empty && !(isClearEntry(e) && e != ENTRY_CLEAR)) continue;
            if (empty && !isEmptyEntry(old[i])) ADD_FAILURE() << "an entry became EMPTY";
            if (e == old[i]) continue;
            EmptyReach was = emptyReach(old[i]), r = emptyReach(e);
            auto covers = [](Vec3i p, Vec3i q) { return p.x >= q.x && p.y >= q.y && p.z >= q.z; };
            if (empty) {  // an EMPTY box grows from the producer's
              ASSERT_TRUE(covers(r.below, was.below) && covers(r.above, was.above)) << scene;
            }
            grown[empty] += 1;
            if (++boxes[empty] % 16 == 1) {
              ASSERT_EQ(nonEmptyInBox(info.world, {g, level}, e, rng, 2, 1, !empty), "") << scene;
            }
          }
    // A ray that leaves a grown box may land in a brick it skipped before inside another brick's
    // EMPTY box, never produced: produced now (EMPTY), as the next frame's rays would.
    int landed = 0;
    for (int pixel = 0; pixel < f.width * f.height; ++pixel) {
      Vec4f c = marchFilling(f.primaryRay(pixel % f.width, pixel / f.width), f, cache, info.world,
                             [&](const BrickKey&) { ++landed; })
                    .colour;
      ASSERT_EQ(std::memcmp(&c, &filled[pixel], sizeof(Vec4f)), 0) << scene << pixel;
    }
    long lookups[2] = {0, 0};
    marchAll([&] { return CachedAccess<BrickPool>{v, pool, f.lod}; }, lookups[0]);
    marchAll([&] { return ClearBricksAlone{{v, pool, f.lod}}; }, lookups[1]);
    std::printf(
        "[ measure ] %s: %u EMPTY and CLEAR bricks listed, boxes grown: %d CLEAR, %d EMPTY; "
        "%d bricks produced after; lookups %ld before, %ld after, %ld with each CLEAR brick "
        "alone\n",
        scene, listed, grown[0], grown[1], landed, before, lookups[0], lookups[1]);
    EXPECT_GT(grown[0], 100) << scene;
    EXPECT_GT(grown[1], 100) << scene;
    EXPECT_LT(lookups[0], lookups[1]) << scene;
    EXPECT_LT(lookups[0], before) << scene;
  }
}

// A resident brick's run (its samples with no brick test each) samples what the brick-by-brick
// march samples, bit for bit, faces included.
TEST(Cache, RunsOfSamplesChangeNoPixel) {
  for (const char* scene : {"forest", "random-spheres"})
    expectSameMarches(scene, plainAccess,
                      [](const CacheView& v, const BrickPool& pool, const Lod& lod) {
                        return NoRuns{{v, pool, lod}};
                      });
}

// marchWarp's use of Marcher (render/march_warp.cuh): a ray seeks only when nothing of its run is
// due, and its run is read in shares of any size (the warp's rounds), each sample read with the
// run's brick. The colours and the counts are march()'s, bit for bit: a run one sample too long
// or a share that loses a sample fails it.
TEST(Cache, RunsReadInSharesAsTheWarpReadsThemChangeNoPixel) {
  for (const char* scene : {"forest", "random-spheres"}) {
    int share = 0;
    expectSameMarches(
        scene, plainAccess, plainAccess,
        [&share](const Ray& ray, const Lod& lod, RayState& s, CachedAccess<BrickPool>& access) {
          using Seek = Marcher<CachedAccess<BrickPool>>::Seek;
          Marcher<CachedAccess<BrickPool>> m(ray, lod, s, access);
          for (;;) {
            Seek k = m.seek();
            if (k == Seek::Moved) continue;
            if (k != Seek::Due)
              return k == Seek::Stopped ? MarchResult::Stopped : MarchResult::Finished;
            int left = m.runLength();
            while (left > 0 && !s.finished(lod)) {
              int take = std::min(left, 1 + share++ % 5);  // shares of 1 to 5 samples
              left -= take;
              for (int i = 0; i < take && !s.finished(lod); ++i) {
                m.composite(access.read(m.resident, m.position()));
                access.countSamples(1);
              }
            }
          }
        },
        true);
  }
}

// pt's warp march breaks off when the first of its rays stops (render/march_warp.cuh,
// WarpMarchEnd::FirstStop): the others are Paused anywhere - between seeks, or part way through a
// run - and march() resumes each from its state alone, looking its brick up again. The colours
// are those of one uninterrupted march, bit for bit.
TEST(Cache, MarchesPausedAnywhereResumeWithoutChangingAPixel) {
  for (const char* scene : {"forest", "random-spheres", "perlin"}) {
    int pause = 0;
    expectSameMarches(
        scene, plainAccess, plainAccess,
        [&pause](const Ray& ray, const Lod& lod, RayState& s, CachedAccess<BrickPool>& access) {
          using Seek = Marcher<CachedAccess<BrickPool>>::Seek;
          Marcher<CachedAccess<BrickPool>> m(ray, lod, s, access);
          int rounds = 1 + pause++ % 23;  // the warp breaks off after 1 to 23 rounds
          for (int round = 0; round < rounds; ++round) {
            Seek k = m.seek();
            if (k == Seek::Moved) continue;
            if (k != Seek::Due)
              return k == Seek::Stopped ? MarchResult::Stopped : MarchResult::Finished;
            int take = std::min(m.runLength(), 1 + round % 3);  // a share: part of the run
            for (int i = 0; i < take && !s.finished(lod); ++i)
              m.composite(access.read(m.resident, m.position()));
          }
          return march(ray, lod, s, access);  // Paused: resumed alone
        });
  }
}

// Leaving clear cells and clear bricks early changes no pixel, bit for bit, and saves many of the
// sample steps near perlin's ground.
TEST(Cache, ClearCellsAndBricksAreSkippedWithoutChangingAPixel) {
  BrickCacheCpu cache(30000);
  FrameSetup f = frameAt(findScene("perlin").start.position, 0);
  cache.beginFrame(f);
  CacheView v = cache.view();
  BrickPool pool = cache.pool();
  uint64_t samples = 0, allSamples = 0;
  int covered = 0;
  for (int pixel = 0; pixel < f.width * f.height; ++pixel) {
    Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
    RayState filling =
        marchFilling(ray, f, cache, findScene("perlin").world, [](const BrickKey&) {});
    RayState s = initialRayState(), all = initialRayState();
    CachedAccess<BrickPool> access{v, pool, f.lod};
    EveryCellOccupied every{{v, pool, f.lod}};
    ASSERT_EQ(march(ray, f.lod, s, access), MarchResult::Finished) << pixel;
    ASSERT_EQ(march(ray, f.lod, all, every), MarchResult::Finished) << pixel;
    ASSERT_EQ(std::memcmp(&s.colour, &all.colour, sizeof(Vec4f)), 0) << pixel;
    ASSERT_EQ(std::memcmp(&s.colour, &filling.colour, sizeof(Vec4f)), 0) << pixel;
    samples += access.samples;
    allSamples += every.samples;
    covered += s.colour.w > 0.5f ? 1 : 0;
  }
  EXPECT_GT(covered, f.width * f.height / 4) << "the view must hold ground";
  // The bricks of zeros are CLEAR in both marches (no samples to read); the clear cells of the
  // others still save a third of the sample steps (24 882 of 37 984 when CLEAR came in).
  EXPECT_LT(samples * 4, allSamples * 3) << samples << " sample steps against " << allSamples;
}

}  // namespace gvdp::detail
