// gvdp with your own world: a walk into a ball of gyroid (gyroid.h), rendered to PNGs with the
// FPS printed. Usage: custom_producer [cpu|cuda] [sp|dp|pt|graph|direct] [frames] [dir]
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "gvdp/io.h"
#include "gvdp/make_renderer.h"
#include "gyroid.h"

int main(int argc, char** argv) try {
  gvdp::RendererOptions options;
  options.scheduler.backend = gvdp::parseBackend(argc > 1 ? argv[1] : "cpu");
  options.scheduler.kind = gvdp::parseScheduler(argc > 2 ? argv[2] : "sp");
  int frames = 60;
  if (argc > 3) {
    std::string_view arg = argv[3];
    auto [end, error] = std::from_chars(arg.data(), arg.data() + arg.size(), frames);
    if (error != std::errc{} || end != arg.data() + arg.size() || frames < 1 || frames > 100000)
      throw gvdp::InputError("bad frame count '" + std::string(arg) + "' (expected 1..100000)");
  }
  std::string dir = argc > 4 ? argv[4] : ".";
  options.width = 480;
  options.height = 270;

  Gyroid gyroid{4.0f, 2.0f, 0.3f, 0.005f};  // radius, period, shell, finest voxel
  auto renderer = gvdp::makeRenderer(gyroid, options);

  gvdp::Image image;
  double totalMs = 0.0;
  for (int f = 0; f < frames; ++f) {
    gvdp::CameraPose pose{{0.0, 0.5, -9.0 + 0.08 * f}, 0.0f, 0.0f};  // position, yaw, pitch
    gvdp::FrameStats stats = renderer->render(pose, image);
    totalMs += stats.ms;
    char name[64];
    std::snprintf(name, sizeof name, "/gyroid_%03d.png", f);
    gvdp::writePng(image, dir + name);
    std::printf("frame %3d  %7.2f ms  %6llu bricks produced  %lld unfinished pixels\n", f, stats.ms,
                static_cast<unsigned long long>(stats.cache.produced),
                static_cast<long long>(stats.unfinishedPixels));
  }
  std::printf("%d frames of %dx%d, %s %s: %.1f FPS\n", frames, options.width, options.height,
              argc > 1 ? argv[1] : "cpu", argc > 2 ? argv[2] : "sp", 1000.0 * frames / totalMs);
  return 0;
} catch (const gvdp::InputError& e) {
  std::fprintf(stderr, "custom_producer: %s\n", e.what());
  return 2;
} catch (const std::exception& e) {
  std::fprintf(stderr, "custom_producer: %s\n", e.what());
  return 1;
}
