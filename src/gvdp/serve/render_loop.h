// The viewer's render loop (`gvdp serve`): one thread renders frames of a flown camera with the
// public Renderer while any client asks for them, and hands each image to JPEG encoder threads;
// a client always gets the newest encoded frame. Frames are dropped, never queued: a frame whose
// encoding has not started when the next one is rendered is replaced by it (every encoder busy),
// and clients slower than the loop skip frames. Encoded frames are published in order.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "gvdp/base/gpu.h"
#include "gvdp/renderer.h"
#include "gvdp/serve/fly_camera.h"
#include "gvdp/serve/params.h"

namespace gvdp::detail {

struct LoopOptions {
  Backend backend = Backend::Cpu;
  ViewSettings view;         // the first view; width and height set
  uint32_t poolBricks = 0;   // 0: the backend's default
  int encoders = 1;          // JPEG encoder threads
  int quality = 80;          // JPEG quality, 1..100
  double idleSeconds = 2.0;  // no frame asked for in this long: the loop waits
};

// What the driving client holds now. A held direction lapses after HOLD_SECONDS without input
// (a client that went away mid-key does not fly the camera on).
struct FlyInput {
  uint64_t seq = 0;          // the client's counter: frames report the last one they show
  Vec3f move{0, 0, 0};       // right, up, forward, each -1..1
  double speed = 1.0;        // a factor of the scene's speed
  float yaw = 0, pitch = 0;  // radians to turn by, once
};
constexpr double HOLD_SECONDS = 1.0;
// The scene's speed (units per frame of its camera paths) is flown at this many frames a second.
constexpr double FLY_FRAMES_PER_SECOND = 30.0;

struct LiveFrame {
  uint64_t seq = 0;       // frames rendered by the loop, from 1
  uint64_t inputSeq = 0;  // the last input the frame shows
  int width = 0, height = 0;
  double renderMs = 0;  // FrameStats::ms
  std::string jpeg;
};

class RenderLoop {
 public:
  using Clock = std::chrono::steady_clock;

  // Builds the first renderer (throws InputError for a bad view) and starts the threads.
  explicit RenderLoop(const LoopOptions& options);
  RenderLoop(const RenderLoop&) = delete;
  RenderLoop& operator=(const RenderLoop&) = delete;
  ~RenderLoop();
  // Stops and joins every thread; waiting callers return.
  void stop();

  // Validated settings, applied before the next frame (a new scene starts at its start pose).
  void setView(const ViewSettings& view);
  ViewSettings view() const;
  void input(const FlyInput& in);
  // The newest frame after frame `after`, waiting up to `timeout`; null on timeout or stop. A call
  // keeps the loop rendering for LoopOptions::idleSeconds.
  std::shared_ptr<const LiveFrame> frameAfter(uint64_t after, std::chrono::milliseconds timeout);
  // The next frame rendered with its GPU-cores timeline recorded: the picture as PNG bytes, or ""
  // on timeout or stop.
  std::string timeline(std::chrono::milliseconds timeout);
  // FPS (rendered, encoded, served), the last frame's numbers, pool occupancy, camera, latency.
  nlohmann::json stats() const;

 private:
  struct Job {
    uint64_t seq = 0, inputSeq = 0;
    Clock::time_point inputTime;
    double renderMs = 0;
    int width = 0, height = 0;
    Image image;        // cpu backend
    int download = -1;  // cuda backend: downloads_[download]
  };
  void release(Job& job);
  struct Ready {
    std::shared_ptr<const LiveFrame> frame;
    Clock::time_point inputTime;
  };
  void renderThread();
  void encoderThread();
  void renderOne(std::unique_lock<std::mutex>& lock);
  // Render thread, lock not held: the renderer of `view`, or the error that kept the last one.
  std::string rebuild(const ViewSettings& view);
  bool wanted(Clock::time_point now) const;
  static double rate(const std::deque<Clock::time_point>& times, Clock::time_point now);

  const LoopOptions options_;
  const bool gpu_;
  mutable std::mutex mutex_;
  std::mutex joinMutex_;            // stop() from several threads
  std::condition_variable wake_;    // the render thread: a request, a view, stop
  std::condition_variable jobs_;    // encoders: a job, stop
  std::condition_variable frames_;  // frameAfter and timeline callers
  bool stop_ = false;

  // The GPU's frames go to the host through these (each held by the render thread, a pending job
  // or an encoder); the vector keeps its size, an entry is remade by the thread holding it.
  OwnedGpuStream stream_;
  std::vector<std::unique_ptr<PinnedDownload>> downloads_;

  // Render thread only (besides construction).
  std::unique_ptr<Renderer> renderer_;
  FlyCamera camera_;
  ViewSettings active_;  // the renderer's
  int pathFrame_ = 0;    // the next frame of active_.path
  Clock::time_point lastFrameTime_;

  // Under mutex_.
  ViewSettings view_;
  bool viewPending_ = false, leavePath_ = false;
  std::string viewError_, failure_;
  uint32_t poolBricks_ = 0;
  FlyInput held_;
  Clock::time_point heldTime_, lastRequest_;
  float turnYaw_ = 0, turnPitch_ = 0;
  bool timelineWanted_ = false;
  uint64_t timelineSeq_ = 0;
  std::string timelinePng_;
  std::unique_ptr<Job> pending_;
  std::vector<Image> freeImages_;
  std::vector<int> freeDownloads_;
  std::shared_ptr<const LiveFrame> newest_;
  std::set<uint64_t> encoding_;      // frames encoders have taken
  std::map<uint64_t, Ready> ready_;  // encoded, waiting for an older frame's encoding
  uint64_t rendered_ = 0, dropped_ = 0, latencySeq_ = 0;
  double frameMsTotal_ = 0, callMsTotal_ = 0;
  std::deque<Clock::time_point> renderTimes_, encodeTimes_, serveTimes_;
  std::deque<double> frameMs_, latencyMs_;
  FrameStats last_;
  CameraPose lastPose_{};

  std::thread renderThread_;
  std::vector<std::thread> encoders_;
};

}  // namespace gvdp::detail
