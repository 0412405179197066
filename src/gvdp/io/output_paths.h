// Output paths are checked before any work starts, so that a command refused for an unwritable
// output leaves nothing behind and never fails after rendering: a directory is created and a
// probe file is written and removed in it; a file is opened for writing (and removed again if it
// did not exist). Directories created here are removed again when a later check throws, unless
// keep() was called once every output passed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gvdp::detail {

class OutputPaths {
 public:
  OutputPaths() = default;
  OutputPaths(const OutputPaths&) = delete;
  OutputPaths& operator=(const OutputPaths&) = delete;
  ~OutputPaths();

  // Throw InputError naming the path and why it cannot be written.
  void directory(const std::string& dir);
  void file(const std::string& path);
  // Every output passed: the directories created stay.
  void keep() { created_.clear(); }

 private:
  std::vector<std::filesystem::path> created_;  // outermost first
};

}  // namespace gvdp::detail
