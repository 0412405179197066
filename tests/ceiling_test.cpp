// Lod::ceiling (render/ceiling.h): above a level's ceiling every sample is zero, and the rays
// that end there render the very image they rendered before, with fewer lookups.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "gvdp/render/ceiling.h"
#include "gvdp/render/direct.h"
#include "test_util.h"

namespace gvdp::detail {

using test::sceneName;

namespace {

// A world opaque below height H whose bound is as tight as its flags: a voxel centre at or above
// H + v is flagged empty (every finer voxel within v of it is at or above H), and a box is clear
// exactly when all of it is.
constexpr double SLAB_TOP = 3.3;
struct SlabWorld {
  float finest;
  GVDP_HD VoxelSample voxel(Vec3d c, float v) const {
    bool solid = c.y < SLAB_TOP;
    return {solid ? packRgba8({0.5f, 0.5f, 0.5f}, 1.0f) : 0u, c.y >= SLAB_TOP + v};
  }
  GVDP_HD bool emptyBox(Vec3d lo, Vec3d, float v) const { return lo.y >= SLAB_TOP + v; }
  GVDP_HD float voxelSize0() const { return finest; }
};

// The sample the cached march would take at p, level `level` (direct.h: the producer's voxels
// quantised as a brick stores them).
template <class P>
Vec4f sampleAt(const FrameSetup& f, const P& producer, int level, Vec3f p) {
  DirectAccess<P> access{f, producer};
  return access.sample({BrickState::Resident, 0u, level, {0, 0, 0}}, p);
}

bool isZero(Vec4f c) {
  return c.x == 0.0f && c.y == 0.0f && c.z == 0.0f && c.w == 0.0f;
}

// Half the side of a level's clipmap window (clipmap.h), which holds every sample of the level.
float windowHalf(const FrameSetup& f, int level) {
  return static_cast<float>(clipmapWidthFor(f.lod.pixelAngle) / 2) * BRICK_WIDTH *
         f.lod.voxelSize(level);
}

// A position of `level` in its window, at a height from `y` up to y + 40 voxels (and no higher
// than the window).
Vec3f randomAbove(const FrameSetup& f, int level, float y, std::mt19937& rng) {
  float v = f.lod.voxelSize(level), half = windowHalf(f, level);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), up(0.0f, 1.0f);
  float top = std::min(y + 40.0f * v, f.eye.y + half);
  return {f.eye.x + half * u(rng), y + (top - y) * up(rng), f.eye.z + half * u(rng)};
}

}  // namespace

// The ceiling is where the bound stops clearing, plus the filter's reach and a quarter voxel:
// samples above it are zero, and a sample a little below the slab's top is not.
TEST(Ceiling, LiesAboveTheLastNonzeroSampleByTheFiltersReach) {
  SlabWorld world{0.25f};
  FrameSetup f = makeFrame({{10.0, 2.0, -7.0}, 0.3f, 0.1f}, world.finest, 160, 100, 8, 0);
  setCeilings(f, world);
  std::mt19937 rng(7);
  for (int level = 0; level < f.lod.levels; ++level) {
    double v = f.lod.voxelSize(level);
    double expected = SLAB_TOP + v + 1.25 * v - f.localOrigin.y;
    EXPECT_NEAR(f.lod.ceiling[level], expected, CEILING_RESOLUTION * v + 1e-4) << level;
    for (int k = 0; k < 200; ++k) {
      Vec3f p = randomAbove(f, level, f.lod.ceiling[level] + 1e-3f, rng);
      EXPECT_TRUE(isZero(sampleAt(f, world, level, p))) << level << " y " << p.y;
    }
    float inside = static_cast<float>(SLAB_TOP - f.localOrigin.y - 0.25 * v);
    EXPECT_FALSE(isZero(sampleAt(f, world, level, {f.eye.x, inside, f.eye.z}))) << level;
  }
}

// The built-in worlds: every sample of a level's window above its ceiling is zero; the terrains
// and the forest have one at the coarse levels (a fine level's window may end below the height
// the bound clears), random-spheres none (its bound refuses boxes of over 125 cells).
TEST(Ceiling, BuiltinWorldsSampleZeroAboveTheirCeilings) {
  std::mt19937 rng(11);
  for (int i = 0; i < SCENE_COUNT; ++i) {
    SequenceOptions o;
    o.scene = sceneName(i);
    o.width = 160;
    o.height = 100;
    const BuiltinScene& world = findScene(o.scene).world;
    for (int frame : {0, 17}) {
      FrameSetup f = frameOf(o, frame);
      setCeilings(f, world);
      int levels = 0;
      for (int level = 0; level < f.lod.levels; ++level) {
        if (f.lod.ceiling[level] == NO_CEILING) continue;
        ++levels;
        if (f.lod.ceiling[level] >= f.eye.y + windowHalf(f, level)) continue;
        for (int k = 0; k < 60; ++k) {
          Vec3f p = randomAbove(f, level, f.lod.ceiling[level] + 1e-3f, rng);
          EXPECT_TRUE(isZero(sampleAt(f, world, level, p))) << o.scene << " level " << level;
        }
      }
      bool terrain = o.scene == "perlin" || o.scene == "fbm" || o.scene == "forest";
      if (terrain) {
        EXPECT_NE(f.lod.ceiling[f.lod.levels - 1], NO_CEILING) << o.scene;
      }
      if (o.scene == "random-spheres") {
        EXPECT_EQ(levels, 0);
      }
      std::printf("[ measure ] %s frame %d: a ceiling at %d of %d levels\n", o.scene.c_str(), frame,
                  levels, f.lod.levels);

    }
  }
}

// The same frames with and without ceilings (sp, CPU), the walkthrough's poses and the same
// poses looking up (the sky): the same pixels, and fewer lookups where rays rise out of the world.
TEST(Ceiling, RaysEndingAtTheCeilingsChangeNoImage) {
  for (const char* scene : {"perlin", "forest"}) {
    SequenceOptions o;
    o.scene = scene;
    o.width = 96;
    o.height = 64;
    o.scheduler = {Backend::Cpu, SchedulerKind::Sp};
    const BuiltinScene& world = findScene(o.scene).world;
    for (float pitch : {0.0f, 0.5f}) {
      std::unique_ptr<Scheduler> without = test::schedulerFor(o), with = test::schedulerFor(o);
      uint64_t lookupsWithout = 0, lookupsWith = 0;
      for (int frame = 0; frame < 4; ++frame) {
        CameraPose pose = poseOf(o, frame);
        pose.pitch += pitch;
        FrameSetup f = frameOf(o, world.voxelSize0(), pose, frame), g = f;
        setCeilings(g, world);
        Image a, b;
        lookupsWithout += without->render(f, a).cache.lookups;
        lookupsWith += with->render(g, b).cache.lookups;
        EXPECT_EQ(a.pixels, b.pixels) << scene << " pitch +" << pitch << " frame " << frame;
      }
      EXPECT_LE(lookupsWith, lookupsWithout) << scene;
      if (pitch > 0.0f) {
        EXPECT_LT(lookupsWith, lookupsWithout) << scene << ": the sky ends rays";
      }
      std::printf("[ measure ] %s sp cpu 96x64 x4, pitch +%.1f: %llu lookups without ceilings, %llu "
                  "with\n",
                  scene, pitch, static_cast<unsigned long long>(lookupsWithout),
                  static_cast<unsigned long long>(lookupsWith));
    }
  }
}

}  // namespace gvdp::detail
