#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "gvdp/base/error.h"
#include "gvdp/cache/produce.h"
#include "gvdp/world/noise.h"
#include "gvdp/world/registry.h"
#include "gvdp/world/spheres.h"
#include "gvdp/world/terrain.h"

namespace gvdp::detail {

TEST(Noise, StaysWithinTheBoundsProducersRelyOn) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-5000.0, 5000.0);
  float maxValue = 0.0f, maxSlope = 0.0f;
  for (int i = 0; i < 300000; ++i) {
    NoiseSample n = gradientNoise({u(rng), u(rng), u(rng)}, 7);
    maxValue = std::max(maxValue, std::fabs(n.value));
    maxSlope = std::max(maxSlope, length(n.grad));
  }
  EXPECT_LE(maxValue, NOISE_MAX_ABS);
  EXPECT_LE(maxSlope, NOISE_LIPSCHITZ);
  EXPECT_GT(maxValue, 0.5f);  // not degenerate
}

// The Hessian bound of the second-order box bounds (world/terrain.h): the Frobenius norm of the
// noise's Hessian, by central differences of the analytic gradient, stays under NOISE_HESSIAN.
TEST(Noise, CurvatureStaysWithinTheBoundProducersRelyOn) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-5000.0, 5000.0);
  double maxNorm = 0.0;
  for (int i = 0; i < 200000; ++i) {
    Vec3d p{u(rng), u(rng), u(rng)};
    const double h = 1e-4;
    double norm2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      Vec3d q = p, r = p;
      (a == 0 ? q.x : a == 1 ? q.y : q.z) += h;
      (a == 0 ? r.x : a == 1 ? r.y : r.z) -= h;
      Vec3f d = (gradientNoise(q, 5).grad - gradientNoise(r, 5).grad) * static_cast<float>(0.5 / h);
      norm2 += d.x * d.x + d.y * d.y + d.z * d.z;
    }
    maxNorm = std::max(maxNorm, std::sqrt(norm2));
  }
  EXPECT_LE(maxNorm, NOISE_HESSIAN);
  EXPECT_GT(maxNorm, 0.5 * NOISE_HESSIAN);  // the bound is not loose by more than 2x
}

TEST(Noise, AnalyticGradientMatchesFiniteDifferences) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (int i = 0; i < 2000; ++i) {
    Vec3d p{u(rng), u(rng), u(rng)};
    const double h = 1e-3;
    NoiseSample n = gradientNoise(p, 3);
    float dx = (gradientNoise({p.x + h, p.y, p.z}, 3).value -
                gradientNoise({p.x - h, p.y, p.z}, 3).value) /
               (2 * h);
    float dy = (gradientNoise({p.x, p.y + h, p.z}, 3).value -
                gradientNoise({p.x, p.y - h, p.z}, 3).value) /
               (2 * h);
    EXPECT_NEAR(n.grad.x, dx, 2e-2f);
    EXPECT_NEAR(n.grad.y, dy, 2e-2f);
  }
}

TEST(Noise, IsSmoothAMillionUnitsFromTheOrigin) {
  // Far from the origin, a small step still changes the value continuously and the gradient
  // predicts it: the lattice reduction in double keeps full detail.
  Vec3d p{1.0e6 + 0.3, 7.1, -2.0e6 + 0.9};
  NoiseSample a = gradientNoise(p, 5);
  const double h = 1e-3;
  NoiseSample b = gradientNoise({p.x + h, p.y, p.z}, 5);
  EXPECT_NEAR((b.value - a.value) / h, a.grad.x, 2e-2);
  EXPECT_NE(a.value, b.value);
}

class SceneTest : public ::testing::TestWithParam<int> {
 protected:
  const SceneInfo& scene() const { return allScenes()[GetParam()]; }
};

namespace {
// FNV-1a over 32-bit words.
uint64_t hashWord(uint64_t h, uint32_t word) {
  for (int b = 0; b < 4; ++b) h = (h ^ ((word >> (8 * b)) & 255u)) * 1099511628211ull;
  return h;
}
}  // namespace

// A scene is the same world in every build and run (BENCHMARKS.md compares commits on it): 1000
// samples near the start camera hash to the value pinned here. A deliberate change to a scene
// updates the pin and says so in its commit.
// aligned-spheres' hash changed on 2026-11-25 with its empty flags (the exact distance to the
// other cells' spheres instead of a bound from the cell border): its colours did not.
TEST_P(SceneTest, ProducerGivesThePinnedWorld) {
  const uint64_t PINNED[SCENE_COUNT] = {0xb9138b889d2ae3ebull, 0x07527150f01905fdull,
                                        0x05ef53a88f7fa095ull, 0x78f7418f4f951f36ull,
                                        0xa4d01f5c31ff4688ull};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  uint64_t h = 14695981039346656037ull;
  for (int i = 0; i < 1000; ++i) {
    Vec3d p = scene().start.position + Vec3d{u(rng), u(rng), u(rng)};
    float vs = scene().world.voxelSize0() * static_cast<float>(1 << (i % 8));
    VoxelSample v = scene().world.voxel(p, vs);
    h = hashWord(hashWord(h, v.rgba), v.empty);
    if (v.empty) {
      EXPECT_EQ(v.rgba >> 24, 0u) << "an empty sample must be transparent";
    }
  }
  std::printf("[ measure ] %s world hash 0x%016llxull\n", std::string(scene().name).c_str(),
              static_cast<unsigned long long>(h));
  EXPECT_EQ(h, PINNED[GetParam()]) << scene().name;
}

TEST_P(SceneTest, HasMatterAndEmptySpaceNearTheStartCamera) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-12.0, 12.0);
  int matter = 0, empty = 0;
  const int N = 4000;
  for (int i = 0; i < N; ++i) {
    Vec3d p = scene().start.position + Vec3d{u(rng), u(rng), u(rng)};
    VoxelSample s = scene().world.voxel(p, scene().world.voxelSize0());
    matter += (s.rgba >> 24) > 0;
    empty += s.empty;
  }
  EXPECT_GT(matter, N / 50) << scene().name;
  EXPECT_GT(empty, N / 10) << scene().name;
  // The eye itself is in empty space.
  EXPECT_TRUE(scene().world.voxel(scene().start.position, scene().world.voxelSize0()).empty)
      << scene().name;
}

// docs/DESIGN.md: a brick is EMPTY at a coarse level only if nothing is there at any finer level.
// Per sample: an empty flag at voxel size V means zero opacity at every finer size v <= V/2
// within 0.9 V (the farthest a finer sample of that brick can be from its nearest coarse one).
TEST_P(SceneTest, EmptinessIsConservativeAcrossLevels) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int tested = 0;
  for (int level = 1; level < 8; ++level) {
    float V = scene().world.voxelSize0() * static_cast<float>(1 << level);
    double spread = 40.0 * V;
    int found = 0;
    for (int i = 0; i < 40000 && found < 150; ++i) {
      Vec3d c = scene().start.position + Vec3d{u(rng) * spread, u(rng) * spread, u(rng) * spread};
      if (!scene().world.voxel(c, V).empty) continue;
      // Only coarse samples near matter make the test bite: look for a sample with matter
      // within 16 voxels.
      bool nearMatter = false;
      for (int k = 0; k < 8 && !nearMatter; ++k) {
        Vec3d q = c + Vec3d{u(rng), u(rng), u(rng)} * (16.0 * V);
        nearMatter = (scene().world.voxel(q, V).rgba >> 24) > 0;
      }
      if (!nearMatter) continue;
      ++found;
      for (int k = 0; k < 40; ++k) {
        float v = V / static_cast<float>(2 << (k % 3));
        Vec3d q = c + Vec3d{u(rng), u(rng), u(rng)} * (0.9 * V / std::sqrt(3.0));
        ASSERT_EQ(scene().world.voxel(q, v).rgba >> 24, 0u)
            << scene().name << ": empty at voxel size " << V << " but matter at " << v;
        ++tested;
      }
    }
  }
  EXPECT_GT(tested, 1000) << scene().name << ": too few coarse empty samples near matter";
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneTest, ::testing::Range(0, SCENE_COUNT),
                         [](const auto& param) {
                           std::string n(allScenes()[param.param].name);
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

// random-spheres looks at the neighbour cells within reach only and stops at the first sphere
// within it (world/spheres.h): its empty flag must be the one the spheres of all 26 neighbours
// give, at every level the neighbours decide it and beyond.
TEST(RandomSpheres, EmptyFlagIsTheOneAllNeighboursGive) {
  const uint32_t SEED = 9u;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-60.0, 60.0);
  for (int level = 0; level < 7; ++level) {
    float vs = std::ldexp(1.0f / 16.0f, level), reach = EMPTY_MARGIN_VOXELS * vs;
    int empties = 0, nearBorder = 0;
    for (int i = 0; i < 20000; ++i) {
      Vec3d p{u(rng), u(rng), u(rng)};
      SphereCell c = sphereCellOf(p);
      Sphere own = randomSphereOf(c.cell, SEED);
      float nearest = own.exists ? sphereLength(c.local - own.centre) - own.radius : 1e30f;
      float border = distanceToCellBorder(c.local);
      if (border < reach && reach <= SPHERE_CELL) {
        ++nearBorder;
        for (int n = 0; n < 27; ++n) {
          Vec3i d{n % 3 - 1, (n / 3) % 3 - 1, n / 9 - 1};
          Sphere s = randomSphereOf(c.cell + d, SEED);
          if (!s.exists || (d.x == 0 && d.y == 0 && d.z == 0)) continue;
          Vec3f centre = s.centre + Vec3f{d.x * SPHERE_CELL, d.y * SPHERE_CELL, d.z * SPHERE_CELL};
          nearest = std::min(nearest, sphereLength(c.local - centre) - s.radius);
        }
      } else {
        nearest = std::min(nearest, border);
      }
      bool empty = nearest >= reach;
      ASSERT_EQ(produceRandomSpheres(p, vs, SEED).empty, empty)
          << "level " << level << " at " << p.x << " " << p.y << " " << p.z;
      empties += empty;
    }
    if (level < 4) {
      EXPECT_GT(empties, 1000) << "level " << level;  // not degenerate
    }
    if (level >= 1 && level <= 5) {
      EXPECT_GT(nearBorder, 5000) << "level " << level;
    }
  }
}

TEST(Registry, FindsScenesByNameAndRejectsUnknownOnes) {
  EXPECT_EQ(findScene("forest").world.kind, SceneKind::Forest);
  EXPECT_EQ(allScenes().size(), 5u);
  try {
    findScene("moon");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'moon'"), std::string::npos);
  }
}

}  // namespace gvdp::detail

namespace gvdp::detail {
namespace {

// Whether `points` random points of the cube of side s at lo are empty, transparent voxels of
// the world at voxelSize (a cube its box bound cleared); names the first that is not.
template <class World>
::testing::AssertionResult cubeIsEmpty(const World& world, Vec3d lo, double s, float voxelSize,
                                       int points, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < points; ++k) {
    Vec3d p{lo.x + s * unit(rng), lo.y + s * unit(rng), lo.z + s * unit(rng)};
    VoxelSample v = world.voxel(p, voxelSize);
    if (!v.empty || v.rgba != 0u) return ::testing::AssertionFailure() << "point " << k;
  }
  return ::testing::AssertionSuccess();
}

// The built-in box bounds are conservative: inside a box one clears, every voxel of that size
// is flagged empty and transparent; each scene with a bound clears some boxes.
template <class World>
void expectConservativeBound(const World& world, double yLo, double yHi, const char* name) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xz(-200.0, 200.0), y(yLo, yHi), unit(0.0, 1.0);
  int cleared = 0;
  for (int i = 0; i < 4000; ++i) {
    int level = static_cast<int>(unit(rng) * 8.0);
    float voxelSize = ldexpf(world.voxelSize0(), level);
    double s = 11.0 * voxelSize * (1.0 + 3.0 * unit(rng));  // a brick's box and larger
    Vec3d lo{xz(rng), y(rng), xz(rng)};
    Vec3d hi{lo.x + s, lo.y + s, lo.z + s};
    if (!world.emptyBox(lo, hi, voxelSize)) continue;
    ++cleared;
    ASSERT_TRUE(cubeIsEmpty(world, lo, s, voxelSize, 16, rng)) << name << " box " << i;
  }
  EXPECT_GT(cleared, 100) << name << ": the bound should clear some boxes";
}

// Near the surface the second-order form (the centre's gradient and the curvature bound) and the
// amplitudes of the layers finer than a box clear boxes the Lipschitz bound alone does not, and
// only empty ones: perlin and fbm boxes of one to four level-0 bricks around the ground, each
// cleared box checked at 64 points.
TEST(BoxBound, SecondOrderBoundsClearMoreBoxesNearTheSurface) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> xz(-100.0, 100.0), y(-20.0, 30.0), unit(0.0, 1.0);
  PerlinWorld perlin{findScene("perlin").world.finest, 1};
  FbmWorld fbm{findScene("fbm").world.finest, 1};
  int cleared[2] = {0, 0}, byLipschitz[2] = {0, 0};
  for (int i = 0; i < 20000; ++i) {
    int which = i % 2;
    float voxelSize = which ? fbm.voxelSize0() : perlin.voxelSize0();
    double s = voxelSize * (10.0 + 30.0 * unit(rng));
    Vec3d lo{xz(rng), y(rng), xz(rng)}, hi{lo.x + s, lo.y + s, lo.z + s};
    bool empty = which ? fbm.emptyBox(lo, hi, voxelSize) : perlin.emptyBox(lo, hi, voxelSize);
    if (!empty) continue;
    ++cleared[which];
    BoxCentre b = boxCentre(lo, hi);
    if (which == 0) {
      float d = perlinDensity(b.centre, 1).d + PERLIN_LIPSCHITZ * b.halfDiagonal;
      byLipschitz[0] += -d >= PERLIN_LIPSCHITZ * EMPTY_MARGIN_VOXELS * voxelSize + DENSITY_SLACK;
    } else {
      int octaves = fbmOctaves(voxelSize);
      float d = fbmDensity(b.centre, octaves, 1).d + fbmLipschitz(octaves) * b.halfDiagonal;
      byLipschitz[1] += d + DENSITY_SLACK <= -1.5f * fbmEmptyReach(voxelSize, octaves);
    }
    ASSERT_TRUE(which ? cubeIsEmpty(fbm, lo, s, voxelSize, 64, rng)
                      : cubeIsEmpty(perlin, lo, s, voxelSize, 64, rng))
        << (which ? "fbm" : "perlin") << " box " << i;
  }
  std::printf(
      "[ measure ] near-surface boxes cleared: perlin %d (Lipschitz alone %d), fbm %d (%d)\n",
      cleared[0], byLipschitz[0], cleared[1], byLipschitz[1]);
  EXPECT_GT(cleared[0], byLipschitz[0] * 11 / 10);
  EXPECT_GT(cleared[1], byLipschitz[1] * 11 / 10);
}

// Below the treetops forest clears boxes by its distance bounds at their centres (the air
// between trunks, crowns and the ground), only empty ones: 64 points of each checked.
TEST(BoxBound, ForestClearsTheAirBetweenItsTrees) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> xz(-300.0, 300.0), unit(0.0, 1.0);
  ForestWorld forest{findScene("forest").world.finest, 1};
  int cleared = 0;
  for (int i = 0; i < 4000; ++i) {
    float voxelSize = ldexpf(forest.voxelSize0(), static_cast<int>(unit(rng) * 4.0));
    double s = voxelSize * (10.0 + 30.0 * unit(rng));
    Vec3d lo{xz(rng), -2.0 + (TREE_TOP - s + 2.0) * unit(rng), xz(rng)};
    Vec3d hi{lo.x + s, lo.y + s, lo.z + s};
    if (!forest.emptyBox(lo, hi, voxelSize)) continue;
    ++cleared;
    ASSERT_TRUE(cubeIsEmpty(forest, lo, s, voxelSize, 64, rng)) << "box " << i;
  }
  std::printf("[ measure ] forest boxes cleared below the treetops: %d of 4000\n", cleared);
  EXPECT_GT(cleared, 400);
}

TEST(BoxBound, BuiltinBoundsAreConservative) {
  expectConservativeBound(PerlinWorld{findScene("perlin").world.finest, 1}, -10.0, 80.0, "perlin");
  expectConservativeBound(FbmWorld{findScene("fbm").world.finest, 1}, -10.0, 150.0, "fbm");
  expectConservativeBound(ForestWorld{findScene("forest").world.finest, 1}, 0.0, 60.0, "forest");
  expectConservativeBound(AlignedSpheresWorld{findScene("aligned-spheres").world.finest, 0}, -30.0,
                          30.0, "aligned-spheres");
}

// random-spheres' box bound as nested loops over the cells the box and its margin overlap: the
// reference for the bound's walk over them (world/spheres.h: from part on by steps of parts).
bool spheresBoundOverEveryCell(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  double margin = EMPTY_MARGIN_VOXELS * static_cast<double>(voxelSize);
  if (margin > SPHERE_CELL) return false;
  margin += SPHERE_SLACK;
  auto cellOf = [](double a) { return static_cast<int>(std::floor(a / SPHERE_CELL)); };
  Vec3i c0{cellOf(lo.x - margin), cellOf(lo.y - margin), cellOf(lo.z - margin)};
  Vec3i c1{cellOf(hi.x + margin), cellOf(hi.y + margin), cellOf(hi.z + margin)};
  if ((c1.x - c0.x + 1) * (c1.y - c0.y + 1) * (c1.z - c0.z + 1) > SPHERE_BOX_CELLS) return false;
  auto gap = [](double c, double a, double b) { return c < a ? a - c : c > b ? c - b : 0.0; };
  for (int z = c0.z; z <= c1.z; ++z)
    for (int y = c0.y; y <= c1.y; ++y)
      for (int x = c0.x; x <= c1.x; ++x) {
        Sphere s = randomSphereOf({x, y, z}, seed);
        if (!s.exists) continue;
        double dx = gap(x * SPHERE_CELL + s.centre.x, lo.x, hi.x);
        double dy = gap(y * SPHERE_CELL + s.centre.y, lo.y, hi.y);
        double dz = gap(z * SPHERE_CELL + s.centre.z, lo.z, hi.z);
        if (dx * dx + dy * dy + dz * dz < (s.radius + margin) * (s.radius + margin)) return false;
      }
  return true;
}

// A group tests a box bound in parts (cache/produce.h: growEmptyBoxes, brickBoundedEmpty): every
// part clear must mean exactly what the whole bound says, whatever the number of parts, for
// random-spheres' split bound and for a bound in one part (perlin's: part 0 is the whole).
TEST(BoxBound, PartsGiveTheWholeBoundsAnswer) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> at(-100.0, 100.0), unit(0.0, 1.0);
  const BuiltinScene spheres = findScene("random-spheres").world,
                     perlin = findScene("perlin").world;
  int cleared = 0, refused = 0;
  for (int i = 0; i < 3000; ++i) {
    const BuiltinScene& world = i % 4 == 3 ? perlin : spheres;
    int level = static_cast<int>(unit(rng) * 5.0);
    float voxelSize = ldexpf(world.voxelSize0(), level);
    double s = 10.0 * voxelSize * (1.0 + 8.0 * unit(rng));
    Vec3d lo{at(rng), i % 4 == 3 ? 20.0 + at(rng) * 0.3 : at(rng), at(rng)};
    Vec3d hi{lo.x + s, lo.y + s * unit(rng), lo.z + s};
    bool whole = world.emptyBox(lo, hi, voxelSize);
    (whole ? cleared : refused) += 1;
    if (&world == &spheres) {
      ASSERT_EQ(whole, spheresBoundOverEveryCell(lo, hi, voxelSize, spheres.seed)) << "box " << i;
    }
    for (int parts : {1, 2, 3, 5, 7, 16, 28}) {
      bool all = true;
      for (int part = 0; part < parts; ++part)
        all = emptyBoxPartOf(world, lo, hi, voxelSize, part, parts) && all;
      ASSERT_EQ(all, whole) << "box " << i << ", " << parts << " parts";
    }
  }
  EXPECT_GT(cleared, 300);
  EXPECT_GT(refused, 300);
}

// A brick whose box the bound refuses is tested again as sub-boxes (cache/produce.h:
// brickBoundedEmpty, world/producer.h: boundSplit). Every brick they clear must evaluate EMPTY,
// sample by sample, and they must clear some that the whole box does not (perlin, fbm, forest);
// the sphere worlds do not split.
TEST(BoxBound, SubBoxesClearOnlyBricksThatEvaluateEmpty) {
  EXPECT_EQ(findScene("random-spheres").world.boundSplit(), 1);
  EXPECT_EQ(findScene("aligned-spheres").world.boundSplit(), 1);
  for (const char* name : {"perlin", "fbm", "forest"}) {
    const SceneInfo& scene = findScene(name);
    const BuiltinScene world = scene.world;
    ASSERT_EQ(world.boundSplit(), 3) << name;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-12.0, 12.0);
    std::uniform_int_distribution<int> level(0, 2);
    int refined = 0, refused = 0;
    for (int i = 0; i < 100000 && refined < 60; ++i) {
      int l = level(rng);
      double brick = ldexp(world.voxelSize0(), l) * BRICK_WIDTH;  // bricks near the start
      auto at = [&](double x) { return static_cast<int>(std::floor((x + offset(rng)) / brick)); };
      const Vec3d& p = scene.start.position;
      BrickKey key{{at(p.x), at(p.y), at(p.z)}, l};
      if (brickBoundedEmpty(world, key)) continue;
      bool sub = brickBoundedEmpty(ThreadScope{}, world, key);
      if (!sub) {
        ++refused;
        continue;
      }
      ++refined;
      for (int s = 0; s < BRICK_SAMPLE_COUNT; ++s)
        ASSERT_TRUE(produceBrickSample(world, key, s).empty)
            << name << ": sample " << s << " of brick (" << key.brick.x << ", " << key.brick.y
            << ", " << key.brick.z << ") level " << l << ", cleared by its sub-boxes";
    }
    EXPECT_GE(refined, 60) << name;
    EXPECT_GT(refused, 0) << name;
  }
}

}  // namespace
}  // namespace gvdp::detail
