#include "gvdp/io/output_paths.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace fs = std::filesystem;

namespace {

// `dir` and those of its ancestors that do not exist yet, outermost first.
std::vector<fs::path> missingDirectories(const fs::path& dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  return missing;
}

// Creates and removes a file in `dir`; returns why it failed, or "" when files can be written.
std::string probeDirectory(const fs::path& dir) {
  fs::path probe = dir / (".gvdp_write_probe_" + std::to_string(::getpid()));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return std::strerror(errno);  // before anything else can change errno
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

}  // namespace

OutputPaths::~OutputPaths() {
  std::error_code ec;
  for (auto p = created_.rbegin(); p != created_.rend(); ++p) fs::remove(*p, ec);  // empty ones
}

void OutputPaths::directory(const std::string& dir) {
  GVDP_INPUT_CHECK(!dir.empty(), "empty output directory name");
  fs::path path = fs::path(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();  // "out/" is "out"
  std::vector<fs::path> missing = missingDirectories(path);
  std::error_code ec;
  fs::create_directories(path, ec);
  if (!ec) created_.insert(created_.end(), missing.begin(), missing.end());
  GVDP_INPUT_CHECK(!ec, "cannot create output directory '", dir, "': ", ec.message());
  GVDP_INPUT_CHECK(fs::is_directory(path, ec), "output directory '", dir, "' is not a directory");
  std::string why = probeDirectory(path);
  GVDP_INPUT_CHECK(why.empty(), "cannot write to output directory '", dir, "': ", why);
}

void OutputPaths::file(const std::string& path) {
  GVDP_INPUT_CHECK(!path.empty(), "empty output file name");
  std::error_code ec;
  bool existed = fs::exists(path, ec);
  // O_NONBLOCK: a FIFO without a reader is refused instead of waited on.
  int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | (existed ? 0 : O_CREAT | O_EXCL), 0644);
  int error = errno;
  GVDP_INPUT_CHECK(fd >= 0, "cannot write '", path, "': ", std::strerror(error));
  ::close(fd);
  if (!existed) ::unlink(path.c_str());
}

}  // namespace gvdp::detail
