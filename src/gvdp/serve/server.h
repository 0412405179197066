// `gvdp serve`: the HTTP server of the browser viewer (docs/DESIGN.md "The viewer"). It serves
// the page (compiled in: no file is ever read from disk) and a small API over one RenderLoop:
//   GET  /                 the page
//   GET  /api/config       scenes, schedulers, limits, the current view
//   GET  /api/frame        ?after=N&client=ID: the newest JPEG frame after frame N (waits up
//                          to a second; 204 when none came); headers X-Frame, X-Input, X-Frame-Ms
//   POST /api/input        ?client=ID&seq=N&move=r,u,f&yaw=&pitch=&speed=: the driver's input
//   POST /api/view         ?client=ID&scene=&scheduler=&width=&height=&budget=: a new view
//   GET  /api/stats        ?client=ID: the loop's figures, and whether this client drives
//   POST /api/timeline     ?client=ID: the next frame's GPU-cores timeline, PNG
// Every parameter is parsed and bounded (serve/params.h); a bad or unknown one is answered 400
// with a one-line reason, a client that does not hold the driver's seat 409, any other path 404.
#pragma once

#include <memory>
#include <string>

#include "gvdp/serve/render_loop.h"

namespace gvdp::detail {

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (port() says which)
  LoopOptions loop;
};

class ViewerServer {
 public:
  // Starts the render loop and binds the port; throws InputError when it cannot.
  explicit ViewerServer(const ServeOptions& options);
  ~ViewerServer();
  int port() const;
  // Serves until stop(); then stops the render loop.
  void run();
  // From any thread (not a signal handler).
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The page, compiled in from serve/viewer.html.
const std::string& viewerPage();

}  // namespace gvdp::detail
