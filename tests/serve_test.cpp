// The browser viewer's server side (gvdp serve): parameters, the flown camera, JPEG frames, the
// render loop and the HTTP API, on the CPU backend at small sizes. The page itself is driven in a
// real browser by tests/serve_browser_test.py.
#include <httplib.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "gvdp/base/error.h"
#include "gvdp/serve/driver_seat.h"
#include "gvdp/serve/jpeg.h"
#include "gvdp/serve/server.h"
#include "gvdp/world/registry.h"
#include "test_util.h"

namespace gvdp::detail {

namespace {
using namespace std::chrono_literals;

LoopOptions smallLoop(const std::string& scene = "perlin", Backend backend = Backend::Cpu) {
  LoopOptions o;
  o.backend = backend;
  o.view.scene = scene;
  o.view.scheduler = SchedulerKind::Sp;
  o.view.width = 48;
  o.view.height = 32;
  o.poolBricks = 20000;
  o.quality = 95;
  return o;
}

// The next frame after `after`, waiting as long as a cold CPU frame may take.
std::shared_ptr<const LiveFrame> nextFrame(RenderLoop& loop, uint64_t after) {
  for (int i = 0; i < 60; ++i)
    if (auto f = loop.frameAfter(after, 1000ms)) return f;
  return nullptr;
}
}  // namespace

TEST(ServeParams, NumbersAreWholeFiniteAndBounded) {
  EXPECT_EQ(parseIntParam("width", "640", 16, 3840), 640);
  for (const char* bad :
       {"", "abc", "64x", " 64", "64 ", "1e3", "99999", "-5", "15", "99999999999999999999999"})
    EXPECT_THROW(parseIntParam("width", bad, 16, 3840), InputError) << bad;
  EXPECT_DOUBLE_EQ(parseNumberParam("speed", "2.5", 0.01, 100), 2.5);
  for (const char* bad : {"nan", "inf", "-inf", "1e400", "0", "101", "2,5", ""})
    EXPECT_THROW(parseNumberParam("speed", bad, 0.01, 100), InputError) << bad;
  Vec3f v = parseVec3Param("move", "1,-0.5,0", -1, 1);
  EXPECT_EQ(v.x, 1.0f);
  EXPECT_EQ(v.y, -0.5f);
  EXPECT_EQ(v.z, 0.0f);
  for (const char* bad : {"1,0", "1,0,0,0", "2,0,0", "a,b,c", ",,", "nan,0,0"})
    EXPECT_THROW(parseVec3Param("move", bad, -1, 1), InputError) << bad;
  EXPECT_EQ(parseClientId("c-x_9"), "c-x_9");
  for (const char* bad : {"", "a b", "../x", "<script>", "0123456789012345678901234567890123"})
    EXPECT_THROW(parseClientId(bad), InputError) << bad;
  try {
    parseIntParam("width", std::string(100, 'x') + "\n\x01", 16, 3840);
    FAIL();
  } catch (const InputError& e) {  // echoed cut and printable
    std::string m = e.what();
    EXPECT_LT(m.size(), 100u);
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

TEST(ServeParams, ViewSettingsNameTheBadValue) {
  ViewSettings cur;
  cur.width = 320;
  cur.height = 200;
  auto parse = [&](std::optional<std::string> scene, std::optional<std::string> sched,
                   std::optional<std::string> w, std::optional<std::string> budget,
                   Backend b = Backend::Cpu) {
    return parseViewSettings(cur, b, {scene, sched, w, std::nullopt, budget, std::nullopt});
  };
  ViewSettings v = parse("forest", "dp", "640", "8");
  EXPECT_EQ(v.scene, "forest");
  EXPECT_EQ(v.scheduler, SchedulerKind::Dp);
  EXPECT_EQ(v.width, 640);
  EXPECT_EQ(v.height, 200);
  EXPECT_DOUBLE_EQ(v.budgetMs, 8.0);
  EXPECT_LT(parse(std::nullopt, std::nullopt, std::nullopt, "off").budgetMs, 0.0);
  EXPECT_EQ(parse(std::nullopt, "graph", std::nullopt, std::nullopt, Backend::Cuda).scheduler,
            SchedulerKind::Graph);
  auto refused = [&](auto f, const std::string& mentions) {
    try {
      f();
      ADD_FAILURE() << mentions;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
    }
  };
  refused([&] { parse("moon", {}, {}, {}); }, "'moon'");
  refused([&] { parse({}, "direct", {}, {}); }, "'direct'");
  refused([&] { parse({}, "graph", {}, {}); }, "'graph'");
  refused([&] { parse({}, {}, "100000", {}); }, "'100000'");
  refused([&] { parse({}, {}, {}, "-1"); }, "'-1'");
  refused([&] { parse({}, {}, {}, "1001"); }, "'1001'");
  ViewParams onPath;
  onPath.path = "walkthrough";
  EXPECT_EQ(parseViewSettings(cur, Backend::Cpu, onPath).path, Movement::Walkthrough);
  EXPECT_FALSE(parseViewSettings(v, Backend::Cpu, ViewParams{{}, {}, {}, {}, {}, "free"}).path);
  refused(
      [&] {
        parseViewSettings(cur, Backend::Cpu, ViewParams{{}, {}, {}, {}, {}, "moonwalk"});
      },
      "'moonwalk'");
}

TEST(ServeCamera, FliesInTheCamerasFrameAndClampsPitch) {
  CameraPose start{{1, 2, 3}, 0.0f, 0.0f};
  FlyCamera cam(start);
  cam.fly({0, 0, 1}, 4.0, 0.5);  // forward at yaw 0 is +z: 2 units
  EXPECT_NEAR(cam.pose().position.z, 5.0, 1e-6);
  EXPECT_NEAR(cam.pose().position.x, 1.0, 1e-6);
  cam.fly({1, 0, 0}, 1.0, 1.0);  // right is the image's right
  CameraBasis b = cameraBasis(start);
  EXPECT_NEAR(cam.pose().position.x, 1.0 + b.right.x, 1e-6);
  cam.fly({0, 1, 0}, 1.0, 3.0);
  EXPECT_NEAR(cam.pose().position.y, 5.0, 1e-6);
  cam.turn(0.0f, 10.0f);
  EXPECT_FLOAT_EQ(cam.pose().pitch, MAX_FLY_PITCH);
  cam.turn(7.0f, -20.0f);
  EXPECT_FLOAT_EQ(cam.pose().pitch, -MAX_FLY_PITCH);
  EXPECT_LE(std::fabs(cam.pose().yaw), static_cast<float>(M_PI));
}

TEST(ServeJpeg, EncodesWhatDecodesBackClose) {
  Image image(61, 37);  // odd sizes: 4:2:0 chroma covers a partial block
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      image.pixels[y * image.width + x] = static_cast<uint32_t>(x * 4) |
                                          static_cast<uint32_t>(y * 6) << 8 | 0x40u << 16 |
                                          0xffu << 24;
  JpegEncoder encoder;
  std::string jpeg = encoder.encode(image, 95);
  ASSERT_GT(jpeg.size(), 100u);
  EXPECT_EQ(jpeg.substr(0, 2), "\xff\xd8");
  Image back = decodeJpeg(jpeg);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  EXPECT_GT(psnr(image, back), 35.0);
  EXPECT_THROW(decodeJpeg("not a jpeg"), InputError);
  EXPECT_THROW(decodeJpeg(jpeg.substr(0, 20)), InputError);
}

TEST(ServeSeat, OneDriverUntilItFallsSilent) {
  DriverSeat seat;
  auto t0 = DriverSeat::Clock::now();
  EXPECT_TRUE(seat.free(t0));
  EXPECT_TRUE(seat.claim("a", t0));
  EXPECT_FALSE(seat.claim("b", t0 + 1s));
  EXPECT_TRUE(seat.drives("a", t0 + 1s));
  EXPECT_TRUE(seat.claim("a", t0 + 2s));  // a's input keeps the seat
  EXPECT_FALSE(seat.claim("b", t0 + 4s));
  EXPECT_TRUE(seat.claim("b", t0 + 6s));  // a silent for 4 s
  EXPECT_FALSE(seat.drives("a", t0 + 6s));
  EXPECT_FALSE(seat.claim("a", t0 + 7s));
}

// On the GPU the frames take the page-locked downloads (overlapping the next frame) instead.
void streamsTheRenderersFramesAndFliesOnInput(Backend backend) {
  LoopOptions o = smallLoop("perlin", backend);
  o.encoders = 2;
  RenderLoop loop(o);
  auto first = nextFrame(loop, 0);
  ASSERT_TRUE(first);
  EXPECT_GE(first->seq, 1u);  // frames come while it waits: the newest is the one it gets
  Image shown = decodeJpeg(first->jpeg);
  ASSERT_EQ(shown.width, 48);
  ASSERT_EQ(shown.height, 32);
  // The first frames are the scene from its start pose (no input yet), as the renderer makes it.
  RendererOptions r;
  r.scheduler.backend = backend;
  r.scheduler.kind = SchedulerKind::Sp;
  r.scheduler.poolBricks = 20000;
  r.width = 48;
  r.height = 32;
  Image reference;
  makeRenderer("perlin", r)->render(findScene("perlin").start, reference);
  EXPECT_GT(psnr(reference, shown), 30.0);

  // Held forward: the camera moves along +z-ish and the frames report the input.
  FlyInput in;
  in.seq = 7;
  in.move = {0, 0, 1};
  in.speed = 4.0;
  loop.input(in);
  auto f = first;
  for (int i = 0; i < 200 && f && f->inputSeq < 7; ++i) f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->inputSeq, 7u);
  f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  nlohmann::json s = loop.stats();
  CameraPose start = findScene("perlin").start;
  double moved = std::hypot(s["camera"]["x"].get<double>() - start.position.x,
                            s["camera"]["z"].get<double>() - start.position.z);
  EXPECT_GT(moved, 0.0) << s.dump();
  EXPECT_EQ(s["unfinishedPixels"], 0);
  EXPECT_GT(s["poolResident"].get<uint64_t>(), 0u);
  EXPECT_EQ(s["inputSeq"], 7);

  // A new view: frames of the new size; the timeline of a frame as a PNG.
  ViewSettings v = loop.view();
  v.width = 40;
  v.height = 24;
  loop.setView(v);
  for (int i = 0; i < 100 && f && f->width != 40; ++i) f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->height, 24);
  std::string png = loop.timeline(60s);
  EXPECT_EQ(png.substr(0, 4), "\x89PNG");
  loop.stop();
  EXPECT_FALSE(loop.frameAfter(f->seq, 10ms));  // stopped: no wait
}

TEST(ServeLoop, StreamsTheRenderersFramesAndFliesOnInput) {
  streamsTheRenderersFramesAndFliesOnInput(Backend::Cpu);
}

TEST(GpuServe, StreamsTheRenderersFramesThroughPageLockedDownloads) {
  GVDP_REQUIRE_GPU();
  streamsTheRenderersFramesAndFliesOnInput(Backend::Cuda);
}

// On a path the camera is the benchmark's pose of each frame, until an input moves it.
TEST(ServeLoop, FollowsACameraPathUntilTheDriverMovesIt) {
  LoopOptions o = smallLoop("aligned-spheres");
  o.view.path = Movement::Forward;
  RenderLoop loop(o);
  const SceneInfo& scene = findScene("aligned-spheres");
  auto f = nextFrame(loop, 0);
  ASSERT_TRUE(f);
  f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  nlohmann::json s = loop.stats();
  uint64_t frame = s["frame"];  // frames 0..frame-1 of the path were rendered
  CameraPose expected =
      cameraAt(Movement::Forward, scene.start, scene.speed, static_cast<int>(frame) - 1);
  EXPECT_NEAR(s["camera"]["z"].get<double>(), expected.position.z, 1e-9) << s.dump();
  EXPECT_GT(s["camera"]["z"].get<double>(), scene.start.position.z);
  EXPECT_EQ(s["path"], "forward");
  FlyInput still;  // moves nothing: stays on the path
  still.seq = 1;
  loop.input(still);
  EXPECT_EQ(loop.view().path, Movement::Forward);
  FlyInput turn;
  turn.seq = 2;
  turn.yaw = 0.5f;
  loop.input(turn);
  EXPECT_FALSE(loop.view().path);
  for (int i = 0; i < 100 && f && f->inputSeq < 2; ++i) f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  f = nextFrame(loop, f->seq);
  ASSERT_TRUE(f);
  s = loop.stats();
  EXPECT_EQ(s["path"], "free");
  double yaw = s["camera"]["yaw"];
  EXPECT_NEAR(yaw, scene.start.yaw + 0.5, 1e-5) << "turned from the path's pose, then flown freely";
}

TEST(ServeLoop, ABadViewKeepsTheLastOneAndSaysWhy) {
  RenderLoop loop(smallLoop());
  auto f = nextFrame(loop, 0);
  ASSERT_TRUE(f);
  ViewSettings v = loop.view();
  v.scheduler = SchedulerKind::Graph;  // parseViewSettings refuses it on the CPU; the loop too
  loop.setView(v);
  std::string error;
  for (int i = 0; i < 100 && error.empty(); ++i) {
    f = nextFrame(loop, f->seq);
    ASSERT_TRUE(f);
    error = loop.stats()["error"];
  }
  EXPECT_NE(error.find("graph"), std::string::npos) << error;
  EXPECT_EQ(loop.view().scheduler, SchedulerKind::Sp);
  EXPECT_TRUE(nextFrame(loop, f->seq));  // still rendering
}

TEST(ServeHttp, AnswersThePageTheApiAndBadRequests) {
  ServeOptions o;
  o.port = 0;
  o.loop = smallLoop();
  ViewerServer server(o);
  std::thread serving([&] { server.run(); });
  httplib::Client http("127.0.0.1", server.port());
  http.set_read_timeout(60, 0);

  auto page = http.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<title>gvdp viewer</title>"), std::string::npos);
  auto config = http.Get("/api/config");
  ASSERT_TRUE(config);
  nlohmann::json c = nlohmann::json::parse(config->body);
  EXPECT_EQ(c["scenes"].size(), allScenes().size());
  EXPECT_EQ(c["view"]["width"], 48);

  auto frame = [&](uint64_t after) {
    for (int i = 0; i < 60; ++i) {
      auto r = http.Get(("/api/frame?client=t&after=" + std::to_string(after)).c_str());
      if (!r || r->status != 204) return r;
    }
    return httplib::Result{nullptr, httplib::Error::Unknown};
  };
  auto f = frame(0);
  ASSERT_TRUE(f);
  ASSERT_EQ(f->status, 200);
  EXPECT_EQ(f->get_header_value("Content-Type"), "image/jpeg");
  EXPECT_GE(std::stoull(f->get_header_value("X-Frame")), 1u);
  EXPECT_EQ(decodeJpeg(f->body).width, 48);

  struct Bad {
    const char* method;
    std::string path;
    int status;
    const char* mentions;
  };
  const std::string huge(5000, 'x');
  std::vector<Bad> bad = {
      {"GET", "/api/frame?after=abc", 400, "bad after 'abc'"},
      {"GET", "/api/frame?after=-1", 400, "bad after"},
      {"GET", "/api/frame?after=1&after=2", 400, "given 2 times"},
      {"GET", "/api/frame?bogus=1", 400, "unknown parameter 'bogus'"},
      {"GET", "/api/frame?client=%3Cscript%3E", 400, "bad client"},
      {"POST", "/api/view?client=a&width=100000", 400, "bad width '100000'"},
      {"POST", "/api/view?client=a&height=1e9", 400, "bad height"},
      {"POST", "/api/view?client=a&scene=moon", 400, "'moon'"},
      {"POST", "/api/view?client=a&scheduler=direct", 400, "'direct'"},
      {"POST", "/api/view?client=a&budget=nan", 400, "bad budget"},
      {"POST", "/api/view?width=64", 400, "missing parameter 'client'"},
      {"POST", "/api/input?client=a&move=0,0,9", 400, "bad move"},
      {"POST", "/api/input?client=a&speed=inf", 400, "bad speed"},
      {"POST", "/api/input?client=a&yaw=" + huge, 400, "bad yaw"},
      {"GET", "/../../etc/passwd", 404, "not found"},
      {"GET", "/%2e%2e/%2e%2e/etc/passwd", 404, "not found"},
      {"GET", "/api/../../../etc/passwd", 404, "not found"},
      {"GET", "/viewer.html", 404, "not found"},
      {"GET", "/api/input", 404, "not found"},
  };
  for (const Bad& b : bad) {
    auto r = std::string(b.method) == "GET" ? http.Get(b.path.c_str())
                                            : http.Post(b.path.c_str(), "", "text/plain");
    ASSERT_TRUE(r) << b.path;
    EXPECT_EQ(r->status, b.status) << b.path << ": " << r->body;
    EXPECT_NE(r->body.find(b.mentions), std::string::npos) << b.path << ": " << r->body;
    EXPECT_EQ(std::count(r->body.begin(), r->body.end(), '\n'), 1) << "one line: " << r->body;
  }
  auto postStatus = [&](const std::string& path, const std::string& body = "") {
    auto r = http.Post(path.c_str(), body, "text/plain");
    return r ? r->status : -1;  // -1: no answer
  };
  EXPECT_EQ(postStatus("/api/input?client=a", std::string(100000, 'x')), 413);

  // One driver: a's input takes the seat, b watches (409) and still gets frames.
  EXPECT_EQ(postStatus("/api/input?client=a&seq=1&move=0,0,1&speed=2"), 200);
  EXPECT_EQ(postStatus("/api/input?client=b&seq=1&move=1,0,0"), 409);
  EXPECT_EQ(postStatus("/api/view?client=b&width=64"), 409);
  auto path = http.Post("/api/view?client=a&path=forward&budget=25", "", "text/plain");
  ASSERT_TRUE(path);
  EXPECT_EQ(path->status, 200) << path->body;
  EXPECT_EQ(nlohmann::json::parse(path->body)["path"], "forward");
  auto stats = http.Get("/api/stats?client=a");
  ASSERT_TRUE(stats);
  nlohmann::json s = nlohmann::json::parse(stats->body);
  EXPECT_TRUE(s["driving"].get<bool>());
  EXPECT_EQ(s["width"], 48);
  EXPECT_EQ(s["path"], "forward");
  EXPECT_EQ(s["budgetMs"], 25.0);
  uint64_t seen = std::stoull(f->get_header_value("X-Frame"));
  auto again = frame(seen);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200);  // still serving after every bad request
  EXPECT_GT(std::stoull(again->get_header_value("X-Frame")), seen);
  auto tl = http.Post("/api/timeline?client=b", "", "text/plain");
  ASSERT_TRUE(tl);
  EXPECT_EQ(tl->status, 200);
  EXPECT_EQ(tl->body.substr(0, 4), "\x89PNG");

  server.stop();
  serving.join();
}

// Constructing a server on `o` throws InputError mentioning `mentions`.
void expectCannotListen(const ServeOptions& o, const std::string& mentions) {
  try {
    ViewerServer server(o);
    ADD_FAILURE() << "listened on " << o.host << ":" << o.port;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

TEST(ServeHttp, APortInUseIsRefusedNotShared) {
  ServeOptions o;
  o.port = 0;
  o.loop = smallLoop();
  ViewerServer first(o);
  o.port = first.port();
  expectCannotListen(o, "cannot listen on 127.0.0.1:" + std::to_string(o.port));
}

TEST(ServeHttp, AnAddressItCannotListenOnIsOneLine) {
  ServeOptions o;
  o.host = "256.1.2.3";
  o.port = 0;
  o.loop = smallLoop();
  expectCannotListen(o, "cannot listen on 256.1.2.3");
}

}  // namespace gvdp::detail
