// The clipmap geometry of a frame (paper 3.2): per level, a window of W^3 bricks centred on the
// eye, addressed toroidally (global brick coordinate mod W) so that a moving window keeps the
// entries it still covers. Also the global brick coordinates of the frame's local origin per
// level, to turn the local brick coordinates of the ray march into global ones.
#pragma once

#include "gvdp/cache/brick_key.h"
#include "gvdp/render/frame.h"

namespace gvdp::detail {

struct Clipmap {
  int width;  // W, bricks per axis and level
  int levels;
  Vec3i windowOrigin[MAX_LEVELS];      // global brick coordinates of each window's min corner
  Vec3i localOriginBrick[MAX_LEVELS];  // global brick coordinates of the local origin
  Vec3i windowPhase[MAX_LEVELS];       // windowOrigin mod W, per axis
  Vec3i localToWindow[MAX_LEVELS];     // localOriginBrick - windowOrigin

  GVDP_HD Vec3i globalBrick(int level, Vec3i localBrick) const {
    return localOriginBrick[level] + localBrick;
  }
  // The global coordinates of the eye's brick at `level`: the window's centre.
  GVDP_HD Vec3i eyeBrick(int level) const {
    int half = width / 2;
    return windowOrigin[level] + Vec3i{half, half, half};
  }
  GVDP_HD bool inWindow(int level, Vec3i g) const {
    Vec3i d = g - windowOrigin[level];
    return d.x >= 0 && d.y >= 0 && d.z >= 0 && d.x < width && d.y < width && d.z < width;
  }
  GVDP_HD uint32_t entryIndex(int level, Vec3i g) const {
    uint32_t w = static_cast<uint32_t>(width);
    return ((static_cast<uint32_t>(level) * w + static_cast<uint32_t>(floorMod(g.z, width))) * w +
            static_cast<uint32_t>(floorMod(g.y, width))) *
               w +
           static_cast<uint32_t>(floorMod(g.x, width));
  }
  // The entry of brick g of `level` if it lies in the level's window, else NOT_IN_WINDOW: the
  // march's lookup, with no division (entryIndex's floorMod): g - windowOrigin lies in [0, W),
  // so g mod W is it plus the window's phase, less W once.
  static constexpr uint32_t NOT_IN_WINDOW = 0xffffffffu;
  GVDP_HD uint32_t windowEntry(int level, Vec3i g) const {
    return windowEntryAt(level, g - windowOrigin[level]);
  }
  // The same for local brick coordinates (the march's).
  GVDP_HD uint32_t windowEntryOfLocal(int level, Vec3i localBrick) const {
    return windowEntryAt(level, localBrick + localToWindow[level]);
  }
  // d: the brick's offset from the window's min corner.
  GVDP_HD uint32_t windowEntryAt(int level, Vec3i d) const {
    if (static_cast<unsigned>(d.x) >= static_cast<unsigned>(width) ||
        static_cast<unsigned>(d.y) >= static_cast<unsigned>(width) ||
        static_cast<unsigned>(d.z) >= static_cast<unsigned>(width))
      return NOT_IN_WINDOW;
    Vec3i m = d + windowPhase[level];
    auto wrap = [&](int a) { return static_cast<uint32_t>(a >= width ? a - width : a); };
    uint32_t w = static_cast<uint32_t>(width);
    return ((static_cast<uint32_t>(level) * w + wrap(m.z)) * w + wrap(m.y)) * w + wrap(m.x);
  }
  size_t entryCount() const {
    return static_cast<size_t>(levels) * static_cast<size_t>(width) * width * width;
  }
};

// The clipmap of a frame: windows centred on the eye's brick at every level.
inline Clipmap clipmapOf(const FrameSetup& frame) {
  Clipmap c{};
  c.width = clipmapWidthFor(frame.lod.pixelAngle);
  c.levels = frame.lod.levels;
  for (int level = 0; level < c.levels; ++level) {
    double brickSize = static_cast<double>(frame.lod.voxelSize(level)) * BRICK_WIDTH;
    // The local origin is a multiple of the coarsest brick: exact integers at every level.
    Vec3i origin{static_cast<int>(std::llround(frame.localOrigin.x / brickSize)),
                 static_cast<int>(std::llround(frame.localOrigin.y / brickSize)),
                 static_cast<int>(std::llround(frame.localOrigin.z / brickSize))};
    c.localOriginBrick[level] = origin;
    Vec3i eye = floorToInt(frame.eye / static_cast<float>(brickSize));
    int half = c.width / 2;
    c.windowOrigin[level] = origin + eye - Vec3i{half, half, half};  // eyeBrick's inverse
    Vec3i o = c.windowOrigin[level];
    c.windowPhase[level] = {floorMod(o.x, c.width), floorMod(o.y, c.width), floorMod(o.z, c.width)};
    c.localToWindow[level] = origin - o;
  }
  return c;
}

}  // namespace gvdp::detail
