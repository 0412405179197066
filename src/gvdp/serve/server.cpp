#include "gvdp/serve/server.h"

#include <httplib.h>

#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <optional>

#include "gvdp/base/error.h"
#include "gvdp/serve/driver_seat.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {

namespace {
using httplib::Request;
using httplib::Response;
using Handler = std::function<void(const Request&, Response&)>;

constexpr auto FRAME_WAIT = std::chrono::milliseconds(1000);
constexpr auto TIMELINE_WAIT = std::chrono::milliseconds(30000);
constexpr int HTTP_THREADS = 32;

void reply(Response& res, int status, const std::string& line) {
  res.status = status;
  res.set_content(line + "\n", "text/plain; charset=utf-8");
}

// A parameter given at most once, or nullopt.
std::optional<std::string> param(const Request& req, const char* name) {
  size_t n = req.get_param_value_count(name);
  GVDP_INPUT_CHECK(n <= 1, "parameter '", name, "' given ", n, " times");
  if (n == 0) return std::nullopt;
  return req.get_param_value(name);
}

std::string requiredClient(const Request& req) {
  std::optional<std::string> c = param(req, "client");
  GVDP_INPUT_CHECK(c, "missing parameter 'client'");
  return parseClientId(*c);
}

// Every handler: only the parameters it knows, InputError as 400, anything else as 500.
Handler guarded(std::vector<std::string> known, Handler handler) {
  return
      [known = std::move(known), handler = std::move(handler)](const Request& req, Response& res) {
        try {
          for (const auto& [name, value] : req.params)
            GVDP_INPUT_CHECK(std::find(known.begin(), known.end(), name) != known.end(),
                             "unknown parameter '", printable(name), "'");
          handler(req, res);
        } catch (const InputError& e) {
          reply(res, 400, e.what());
        } catch (const std::exception& e) {
          reply(res, 500, std::string("internal error: ") + e.what());
        }
      };
}

nlohmann::json viewJson(const ViewSettings& v) {
  return {{"scene", v.scene},
          {"scheduler", schedulerName(v.scheduler)},
          {"width", v.width},
          {"height", v.height},
          {"budgetMs", v.budgetMs < 0.0 ? nlohmann::json() : nlohmann::json(v.budgetMs)},
          {"path", pathName(v.path)}};
}
}  // namespace

struct ViewerServer::Impl {
  explicit Impl(const ServeOptions& o) : options(o), loop(o.loop) {}
  void routes();
  nlohmann::json config() const;

  ServeOptions options;
  RenderLoop loop;
  DriverSeat seat;
  httplib::Server http;
  int port = 0;
  std::mutex runMutex;  // run() and stop() from different threads
  bool running = false, stopping = false;
};

nlohmann::json ViewerServer::Impl::config() const {
  nlohmann::json scenes = nlohmann::json::array();
  for (const SceneInfo& s : allScenes())
    scenes.push_back({{"name", s.name}, {"description", s.description}});
  nlohmann::json schedulers = {"sp", "dp", "pt"};
  nlohmann::json paths = {"free"};
  for (int m = 0; m < MOVEMENT_COUNT; ++m) paths.push_back(movementName(static_cast<Movement>(m)));
  if (options.loop.backend == Backend::Cuda) schedulers.push_back("graph");
  return {{"scenes", scenes},
          {"schedulers", schedulers},
          {"paths", paths},
          {"backend", backendName(options.loop.backend)},
          {"limits",
           {{"minSize", MIN_VIEW_SIZE},
            {"maxWidth", MAX_VIEW_WIDTH},
            {"maxHeight", MAX_VIEW_HEIGHT},
            {"maxBudgetMs", MAX_VIEW_BUDGET_MS}}},
          {"view", viewJson(loop.view())}};
}

void ViewerServer::Impl::routes() {
  auto page = [](const Request&, Response& res) {
    res.set_content(viewerPage(), "text/html; charset=utf-8");
  };
  http.Get("/", guarded({}, page));
  http.Get("/index.html", guarded({}, page));
  http.Get("/api/config", guarded({}, [this](const Request&, Response& res) {
             res.set_content(config().dump(), "application/json");
           }));
  http.Get("/api/frame", guarded({"after", "client"}, [this](const Request& req, Response& res) {
             std::optional<std::string> after = param(req, "after");
             if (std::optional<std::string> c = param(req, "client")) parseClientId(*c);
             uint64_t n = after ? parseIntParam("after", *after, 0, int64_t{1} << 62) : 0;
             std::shared_ptr<const LiveFrame> f = loop.frameAfter(n, FRAME_WAIT);
             if (!f) {
               res.status = 204;  // none yet: ask again
               return;
             }
             res.set_header("X-Frame", std::to_string(f->seq));
             res.set_header("X-Input", std::to_string(f->inputSeq));
             res.set_header("X-Frame-Ms", std::to_string(f->renderMs));
             res.set_content(f->jpeg, "image/jpeg");
           }));
  http.Post("/api/input",
            guarded({"client", "seq", "move", "yaw", "pitch", "speed"},
                    [this](const Request& req, Response& res) {
                      std::string client = requiredClient(req);
                      FlyInput in;
                      if (auto v = param(req, "seq"))
                        in.seq = parseIntParam("seq", *v, 0, int64_t{1} << 53);
                      if (auto v = param(req, "move")) in.move = parseVec3Param("move", *v, -1, 1);
                      if (auto v = param(req, "yaw"))
                        in.yaw = static_cast<float>(parseNumberParam("yaw", *v, -3.15, 3.15));
                      if (auto v = param(req, "pitch"))
                        in.pitch = static_cast<float>(parseNumberParam("pitch", *v, -3.15, 3.15));
                      if (auto v = param(req, "speed"))
                        in.speed = parseNumberParam("speed", *v, 0.01, 100.0);
                      if (!seat.claim(client, DriverSeat::Clock::now()))
                        return reply(res, 409, "another client drives the camera; watching");
                      loop.input(in);
                      reply(res, 200, "ok");
                    }));
  http.Post("/api/view",
            guarded({"client", "scene", "scheduler", "width", "height", "budget", "path"},
                    [this](const Request& req, Response& res) {
                      std::string client = requiredClient(req);
                      ViewSettings v = parseViewSettings(
                          loop.view(), options.loop.backend,
                          {param(req, "scene"), param(req, "scheduler"), param(req, "width"),
                           param(req, "height"), param(req, "budget"), param(req, "path")});
                      if (!seat.claim(client, DriverSeat::Clock::now()))
                        return reply(res, 409, "another client drives the camera; watching");
                      loop.setView(v);
                      res.set_content(viewJson(v).dump(), "application/json");
                    }));
  http.Get("/api/stats", guarded({"client"}, [this](const Request& req, Response& res) {
             nlohmann::json j = loop.stats();
             auto now = DriverSeat::Clock::now();
             std::optional<std::string> c = param(req, "client");
             j["driving"] = c && seat.drives(parseClientId(*c), now);
             j["seatFree"] = seat.free(now);
             res.set_content(j.dump(), "application/json");
           }));
  http.Post("/api/timeline", guarded({"client"}, [this](const Request& req, Response& res) {
              if (std::optional<std::string> c = param(req, "client")) parseClientId(*c);
              std::string png = loop.timeline(TIMELINE_WAIT);
              if (png.empty()) return reply(res, 503, "no frame was rendered in time");
              res.set_content(png, "image/png");
            }));
  http.set_error_handler(
      httplib::Server::HandlerWithResponse([](const Request& req, Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        reply(res, res.status,
              res.status == 404 ? "not found: " + printable(req.path)
                                : "request refused (HTTP " + std::to_string(res.status) + ")");
        return httplib::Server::HandlerResponse::Handled;
      }));
}

ViewerServer::ViewerServer(const ServeOptions& options) : impl_(std::make_unique<Impl>(options)) {
  httplib::Server& http = impl_->http;
  http.new_task_queue = [] { return new httplib::ThreadPool(HTTP_THREADS); };
  http.set_payload_max_length(4096);  // the API takes its parameters in the URL
  // A frame's headers and body go out at once: with Nagle's algorithm the body waited for the
  // client's delayed ACK, 40 ms a frame (the H100 run delivered 22.7 of 460 FPS before this).
  http.set_tcp_nodelay(true);
  // SO_REUSEADDR (a restart binds at once) but not httplib's default SO_REUSEPORT, with which a
  // second server on the same port bound too and the kernel split the clients between them.
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  http.set_keep_alive_max_count(1000000);
  http.set_keep_alive_timeout(2);
  http.set_default_headers({{"Cache-Control", "no-store"}, {"X-Content-Type-Options", "nosniff"}});
  impl_->routes();
  int port = options.port;
  bool bound = false;
  if (port == 0) {
    port = http.bind_to_any_port(options.host);
    bound = port > 0;
  } else {
    bound = http.bind_to_port(options.host, port);
  }
  if (!bound) {
    int e = errno;
    impl_->loop.stop();
    throw InputError(concat("cannot listen on ", options.host, ":", options.port, " (",
                            e ? std::strerror(e) : "bad address", ")"));
  }
  impl_->port = port;
}

ViewerServer::~ViewerServer() {
  stop();
}

int ViewerServer::port() const {
  return impl_->port;
}

void ViewerServer::run() {
  {
    std::lock_guard lock(impl_->runMutex);
    if (impl_->stopping) return;
    impl_->running = true;
  }
  impl_->http.listen_after_bind();
  {
    std::lock_guard lock(impl_->runMutex);
    impl_->running = false;
  }
  impl_->loop.stop();
}

void ViewerServer::stop() {
  bool running = false;
  {
    std::lock_guard lock(impl_->runMutex);
    impl_->stopping = true;
    running = impl_->running;
  }
  impl_->loop.stop();  // wakes every waiting request first
  if (!running) return;
  // run() may not have reached its listening loop yet, which a stop before it would not end.
  while (!impl_->http.is_running()) {
    {
      std::lock_guard lock(impl_->runMutex);
      if (!impl_->running) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  impl_->http.stop();
}

}  // namespace gvdp::detail
