// The mesh commands of the gvdp command line: `gvdp mesh subdivide` (make a large mesh from a
// small one), `gvdp mesh sphere` (an icosphere of 20 x 4^N triangles) and `gvdp kdtree` (build
// the full-SAH kd-tree of a mesh, time it and its rays).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace gvdp::detail {

class MeshCommands {
 public:
  explicit MeshCommands(CLI::App& app);  // adds the subcommands
  // After parsing: the exit status of the mesh command that was parsed, if one was.
  std::optional<int> runParsed() const;

 private:
  CLI::App* mesh_;
  CLI::App* subdivide_;
  CLI::App* sphere_;
  CLI::App* kdtree_;
  int times_ = 1;
  std::string in_, out_;
  int sphereTimes_ = 5;
  std::string sphereOut_;
  std::string kdMesh_, builders_ = "all";
  int64_t repeat_ = 3, rays_ = 200000;
};

}  // namespace gvdp::detail
