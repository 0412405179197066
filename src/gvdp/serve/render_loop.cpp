#include "gvdp/serve/render_loop.h"

#include <algorithm>
#include <optional>

#include "gvdp/base/error.h"
#include "gvdp/io/timeline_export.h"
#include "gvdp/serve/jpeg.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {

namespace {
constexpr double RATE_WINDOW_SECONDS = 2.0;  // FPS figures are over the last 2 s
constexpr size_t HISTORY = 240;              // frame times kept for the page's chart
constexpr size_t LATENCIES = 32;             // input-to-frame latencies, for their median

std::unique_ptr<Renderer> makeViewRenderer(const LoopOptions& o, const ViewSettings& v) {
  RendererOptions r;
  r.scheduler.backend = o.backend;
  r.scheduler.kind = v.scheduler;
  r.scheduler.poolBricks = o.poolBricks;
  r.scheduler.budgetMs = v.budgetMs;
  r.width = v.width;
  r.height = v.height;
  return makeRenderer(v.scene, r);
}

double seconds(RenderLoop::Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

double median(std::deque<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

template <class T>
void keepLast(std::deque<T>& d, size_t n) {
  while (d.size() > n) d.pop_front();
}
}  // namespace

RenderLoop::RenderLoop(const LoopOptions& options)
    : options_(options),
      gpu_(options.backend == Backend::Cuda),
      renderer_(makeViewRenderer(options, options.view)),
      camera_(findScene(options.view.scene).start),
      active_(options.view),
      view_(options.view) {
  GVDP_CHECK(options.encoders >= 1 && options.quality >= 1 && options.quality <= 100,
             "bad encoder options");
  if (gpu_) {
    stream_.reset(createGpuStream());
    downloads_.resize(static_cast<size_t>(options.encoders) + 2);  // made at their first frame
    for (int i = 0; i < static_cast<int>(downloads_.size()); ++i) freeDownloads_.push_back(i);
  }
  lastFrameTime_ = heldTime_ = Clock::now();
  lastRequest_ = Clock::time_point{};
  held_.speed = 1.0;
  renderThread_ = std::thread([this] { renderThread(); });
  for (int i = 0; i < options.encoders; ++i) encoders_.emplace_back([this] { encoderThread(); });
}

RenderLoop::~RenderLoop() {
  stop();
}

void RenderLoop::stop() {
  std::lock_guard joining(joinMutex_);
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  jobs_.notify_all();
  frames_.notify_all();
  if (renderThread_.joinable()) renderThread_.join();
  for (std::thread& t : encoders_)
    if (t.joinable()) t.join();
}

void RenderLoop::setView(const ViewSettings& view) {
  {
    std::lock_guard lock(mutex_);
    view_ = view;
    viewPending_ = true;
  }
  wake_.notify_all();
}

ViewSettings RenderLoop::view() const {
  std::lock_guard lock(mutex_);
  return view_;
}

void RenderLoop::input(const FlyInput& in) {
  {
    std::lock_guard lock(mutex_);
    held_.seq = std::max(held_.seq, in.seq);
    held_.move = in.move;
    held_.speed = in.speed;
    heldTime_ = Clock::now();
    turnYaw_ += in.yaw;
    turnPitch_ += in.pitch;
    // Moving the camera takes it off its path (an input that moves nothing leaves it on).
    bool moves = in.move.x != 0 || in.move.y != 0 || in.move.z != 0 || in.yaw != 0 || in.pitch != 0;
    if (moves && view_.path) {
      view_.path.reset();
      leavePath_ = true;
    }
  }
  wake_.notify_all();
}

bool RenderLoop::wanted(Clock::time_point now) const {
  return viewPending_ || timelineWanted_ || seconds(now - lastRequest_) < options_.idleSeconds;
}

std::shared_ptr<const LiveFrame> RenderLoop::frameAfter(uint64_t after,
                                                        std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  lastRequest_ = Clock::now();
  wake_.notify_all();
  bool ready =
      frames_.wait_for(lock, timeout, [&] { return stop_ || (newest_ && newest_->seq > after); });
  if (!ready || stop_) return nullptr;
  serveTimes_.push_back(Clock::now());
  keepLast(serveTimes_, 4096);
  return newest_;
}

std::string RenderLoop::timeline(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  uint64_t before = timelineSeq_;
  timelineWanted_ = true;
  lastRequest_ = Clock::now();
  wake_.notify_all();
  bool ready = frames_.wait_for(lock, timeout, [&] { return stop_ || timelineSeq_ > before; });
  return ready && !stop_ ? timelinePng_ : std::string();
}

void RenderLoop::renderThread() {
  std::unique_lock lock(mutex_);
  while (!stop_ && failure_.empty()) {
    if (!wanted(Clock::now())) {
      wake_.wait_for(lock, std::chrono::milliseconds(100));
      continue;
    }
    try {
      renderOne(lock);
    } catch (const std::exception& e) {
      if (!lock.owns_lock()) lock.lock();
      failure_ = e.what();  // the server keeps answering, with the reason in its stats
      frames_.notify_all();
    }
  }
}

std::string RenderLoop::rebuild(const ViewSettings& view) {
  std::string error;
  renderer_.reset();  // its pool goes before the next one is made
  try {
    renderer_ = makeViewRenderer(options_, view);
  } catch (const Error& e) {
    error = e.what();
    renderer_ = makeViewRenderer(options_, active_);  // it ran before
    return error;
  }
  if (view.scene != active_.scene) camera_ = FlyCamera(findScene(view.scene).start);
  if (view.scene != active_.scene || view.path != active_.path) pathFrame_ = 0;
  active_ = view;
  return error;
}

// The buffers of a job no encoder will take (or has encoded) go back; lock held.
void RenderLoop::release(Job& job) {
  if (job.download >= 0)
    freeDownloads_.push_back(job.download);
  else
    freeImages_.push_back(std::move(job.image));
  wake_.notify_all();
}

// One frame: called and returns with the lock held; renders and encodes without it.
void RenderLoop::renderOne(std::unique_lock<std::mutex>& lock) {
  // The frame's buffer. On the GPU: a free download, else the one of the frame waiting for an
  // encoder (that frame is dropped), else wait for an encoder to finish one.
  Image image;
  int download = -1;
  if (gpu_) {
    wake_.wait(lock, [&] { return stop_ || !freeDownloads_.empty() || pending_; });
    if (stop_) return;
    if (!freeDownloads_.empty()) {
      download = freeDownloads_.back();
      freeDownloads_.pop_back();
    } else {
      download = pending_->download;
      pending_.reset();
      ++dropped_;
    }
  } else if (!freeImages_.empty()) {
    image = std::move(freeImages_.back());
    freeImages_.pop_back();
  }
  std::optional<ViewSettings> newView;
  if (viewPending_) newView = view_;
  viewPending_ = false;
  Clock::time_point now = Clock::now();
  FlyInput held = held_;
  if (seconds(now - heldTime_) > HOLD_SECONDS) held.move = {0, 0, 0};
  Clock::time_point inputTime = heldTime_;
  float yaw = turnYaw_, pitch = turnPitch_;
  turnYaw_ = turnPitch_ = 0;
  bool withTimeline = timelineWanted_;
  timelineWanted_ = false;
  bool leavePath = leavePath_;
  leavePath_ = false;
  lock.unlock();

  std::string error = newView ? rebuild(*newView) : std::string();
  double dt = std::min(seconds(now - lastFrameTime_), 0.25);
  lastFrameTime_ = now;
  const SceneInfo& scene = findScene(active_.scene);
  if (leavePath) active_.path.reset();
  if (active_.path)
    camera_ = FlyCamera(cameraAt(*active_.path, scene.start, scene.speed, pathFrame_++));
  camera_.turn(yaw, pitch);
  camera_.fly(held.move, held.speed * scene.speed * FLY_FRAMES_PER_SECOND, dt);
  if (withTimeline) renderer_->recordTimeline(true);
  Clock::time_point callStart = Clock::now();
  FrameStats stats;
  if (gpu_) {
    // The image stays on the device; its download to page-locked memory overlaps the next frame
    // and the encoder waits for it.
    size_t bytes = static_cast<size_t>(active_.width) * active_.height * sizeof(uint32_t);
    std::unique_ptr<PinnedDownload>& d = downloads_[static_cast<size_t>(download)];
    if (!d || d->bytes() != bytes) d = std::make_unique<PinnedDownload>(bytes);
    stats = renderer_->render(camera_.pose(), static_cast<uint32_t*>(d->device()), stream_.get());
    d->start(stream_.get());
  } else {
    stats = renderer_->render(camera_.pose(), image);
  }
  double callMs = 1e3 * seconds(Clock::now() - callStart);
  std::string png;
  if (withTimeline) {
    renderer_->recordTimeline(false);
    const TimelineCapture& t = stats.timeline;
    std::string title = std::string(schedulerName(active_.scheduler)) + " on " +
                        std::string(backendName(options_.backend)) + ", " + active_.scene +
                        " frame " + std::to_string(stats.index) + ", " +
                        std::to_string(active_.width) + "x" + std::to_string(active_.height);
    png = encodePng(timelineImage(t.records, t.lanes, title));
    stats.timeline = {};
  }
  uint32_t poolBricks = renderer_->options().scheduler.poolBricks;

  lock.lock();
  if (newView) {
    viewError_ = error;
    if (!viewPending_) view_ = active_;
  }
  poolBricks_ = poolBricks;
  auto job = std::make_unique<Job>();
  job->seq = ++rendered_;
  job->inputSeq = held.seq;
  job->inputTime = inputTime;
  job->renderMs = stats.ms;
  job->width = active_.width;
  job->height = active_.height;
  job->image = std::move(image);
  job->download = download;
  renderTimes_.push_back(Clock::now());
  keepLast(renderTimes_, 4096);
  frameMs_.push_back(stats.ms);
  keepLast(frameMs_, HISTORY);
  frameMsTotal_ += stats.ms;
  callMsTotal_ += callMs;
  last_ = stats;
  lastPose_ = camera_.pose();
  if (withTimeline) {
    timelinePng_ = std::move(png);
    ++timelineSeq_;
    frames_.notify_all();
  }
  if (pending_) {  // not taken by an encoder yet: dropped
    ++dropped_;
    release(*pending_);
  }
  pending_ = std::move(job);
  jobs_.notify_one();
}

void RenderLoop::encoderThread() {
  JpegEncoder encoder;
  std::unique_lock lock(mutex_);
  while (true) {
    jobs_.wait(lock, [&] { return stop_ || pending_; });
    if (stop_) return;
    std::unique_ptr<Job> job = std::move(pending_);
    encoding_.insert(job->seq);
    lock.unlock();
    auto frame = std::make_shared<LiveFrame>();
    frame->seq = job->seq;
    frame->inputSeq = job->inputSeq;
    frame->width = job->width;
    frame->height = job->height;
    frame->renderMs = job->renderMs;
    if (job->download >= 0) {
      const void* pixels = downloads_[static_cast<size_t>(job->download)]->wait();
      frame->jpeg = encoder.encode(static_cast<const uint32_t*>(pixels), job->width, job->height,
                                   options_.quality);
    } else {
      frame->jpeg = encoder.encode(job->image, options_.quality);
    }
    lock.lock();
    encoding_.erase(job->seq);
    ready_[job->seq] = {std::move(frame), job->inputTime};
    release(*job);
    // Frames are published in order: one that another encoder finished first waits for it
    // (dropping it would lose a frame the loop rendered; showing it later would go back).
    Clock::time_point now = Clock::now();
    while (!ready_.empty() && (encoding_.empty() || ready_.begin()->first < *encoding_.begin())) {
      Ready r = std::move(ready_.begin()->second);
      ready_.erase(ready_.begin());
      if (r.frame->inputSeq > latencySeq_) {
        latencySeq_ = r.frame->inputSeq;
        latencyMs_.push_back(1e3 * seconds(now - r.inputTime));
        keepLast(latencyMs_, LATENCIES);
      }
      newest_ = std::move(r.frame);
      encodeTimes_.push_back(now);
      keepLast(encodeTimes_, 4096);
    }
    frames_.notify_all();
  }
}

nlohmann::json RenderLoop::stats() const {
  std::lock_guard lock(mutex_);
  Clock::time_point now = Clock::now();
  nlohmann::json j;
  j["scene"] = view_.scene;
  j["scheduler"] = schedulerName(view_.scheduler);
  j["backend"] = backendName(options_.backend);
  j["width"] = view_.width;
  j["height"] = view_.height;
  j["budgetMs"] = view_.budgetMs < 0.0 ? nlohmann::json() : nlohmann::json(view_.budgetMs);
  j["path"] = pathName(view_.path);
  j["rendering"] = wanted(now) && failure_.empty();
  j["frame"] = rendered_;
  j["renderFps"] = rate(renderTimes_, now);
  j["encodedFps"] = rate(encodeTimes_, now);
  j["servedFps"] = rate(serveTimes_, now);
  j["dropped"] = dropped_;
  j["frameMs"] = last_.ms;
  j["frameMsHistory"] = std::vector<double>(frameMs_.begin(), frameMs_.end());
  // Sums over every frame so far (the renderer's frame times; the wall time of its call: frame,
  // image to its buffer, counters): a client's window takes their differences.
  j["frameMsTotal"] = frameMsTotal_;
  j["renderCallMsTotal"] = callMsTotal_;
  j["latencyMs"] = median(latencyMs_);  // input received to its first frame encoded, median
  j["bricksProduced"] = last_.cache.produced;
  j["poolResident"] = last_.cache.resident;
  j["poolBricks"] = poolBricks_;
  j["unfinishedPixels"] = last_.unfinishedPixels;
  j["coarserPixels"] = last_.cache.coarser;
  j["degraded"] = last_.degraded;
  j["camera"] = {{"x", lastPose_.position.x},
                 {"y", lastPose_.position.y},
                 {"z", lastPose_.position.z},
                 {"yaw", lastPose_.yaw},
                 {"pitch", lastPose_.pitch}};
  j["inputSeq"] = held_.seq;
  j["error"] = failure_.empty() ? viewError_ : failure_;
  return j;
}

double RenderLoop::rate(const std::deque<Clock::time_point>& times, Clock::time_point now) {
  size_t n = 0;
  Clock::time_point first = now;
  for (auto it = times.rbegin(); it != times.rend() && seconds(now - *it) <= RATE_WINDOW_SECONDS;
       ++it) {
    ++n;
    first = *it;
  }
  if (n < 2) return 0.0;
  return static_cast<double>(n - 1) / std::max(seconds(now - first), 1e-6);
}

}  // namespace gvdp::detail
