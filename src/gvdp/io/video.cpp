#include "gvdp/io/video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "gvdp/base/error.h"

extern char** environ;

namespace gvdp::detail {

std::string findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  size_t start = 0;
  while (start <= dirs.size()) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string dir = dirs.substr(start, end - start);
    std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate))
      return candidate;
    start = end + 1;
  }
  return "";
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, int fps)
    : path_(path), width_(width), height_(height) {
  std::string ffmpeg = findOnPath("ffmpeg");
  GVDP_INPUT_CHECK(!ffmpeg.empty(), "--video '", path,
                   "' needs the ffmpeg command, which is not on the PATH (Debian: apt-get install "
                   "ffmpeg)");
  GVDP_CHECK(width > 0 && height > 0 && fps > 0, "bad video size or rate");
  std::vector<std::string> args = {
      ffmpeg,      "-hide_banner",
      "-loglevel", "error",
      "-nostdin",  "-y",
      "-f",        "rawvideo",
      "-pix_fmt",  "rgba",
      "-s",        std::to_string(width) + "x" + std::to_string(height),
      "-r",        std::to_string(fps),
      "-i",        "pipe:0",
      "-vf",       "pad=ceil(iw/2)*2:ceil(ih/2)*2",
      "-c:v",      "libx264",
      "-pix_fmt",  "yuv420p",
      "-crf",      "18",
      "-preset",   "fast",
      path};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int fds[2];
  GVDP_CHECK(::pipe(fds) == 0, "pipe: errno ", errno);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  pid_t pid = -1;
  int rc = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    throw InputError(
        concat("cannot start '", ffmpeg, "' for --video '", path, "' (errno ", rc, ")"));
  }
  pid_ = pid;
  pipe_ = fds[1];
  // A stopped ffmpeg makes write() fail with EPIPE instead of killing this process.
  std::signal(SIGPIPE, SIG_IGN);
}

VideoWriter::~VideoWriter() {
  if (pid_ < 0) return;
  try {
    close();
  } catch (const Error&) {
    // Destruction during an error already being reported: the first error is the one shown.
  }
}

void VideoWriter::add(const Image& image) {
  GVDP_CHECK(pipe_ >= 0, "video '", path_, "' is closed");
  GVDP_CHECK(image.width == width_ && image.height == height_, "video frame ", image.width, "x",
             image.height, " in a ", width_, "x", height_, " video");
  const char* bytes = reinterpret_cast<const char*>(image.pixels.data());
  size_t left = image.pixels.size() * sizeof(uint32_t);
  while (left > 0) {
    ssize_t n = ::write(pipe_, bytes, left);
    if (n < 0 && errno == EINTR) continue;
    GVDP_CHECK(n > 0, "ffmpeg stopped taking frames for '", path_, "' (errno ", errno, ")");
    bytes += n;
    left -= static_cast<size_t>(n);
  }
  ++frames_;
}

int VideoWriter::close() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  int status = 0;
  pid_t pid = pid_;
  pid_ = -1;
  if (pid < 0) return frames_;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  GVDP_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "ffmpeg failed writing '", path_,
             "' (status ", status, ")");
  return frames_;
}

}  // namespace gvdp::detail
