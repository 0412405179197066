// readMesh (by extension) and writePly (binary little endian).
#include "gvdp/mesh/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string readBytes(const std::string& path) {
  std::error_code ec;
  GVDP_INPUT_CHECK(!std::filesystem::is_directory(path, ec), path, ": is a directory");
  std::ifstream in(path, std::ios::binary);
  GVDP_INPUT_CHECK(in, path, ": cannot open (", std::strerror(errno), ")");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  GVDP_INPUT_CHECK(!in.bad(), path, ": read error");
  return bytes;
}

void putLittle(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

}  // namespace

Mesh readMesh(const std::string& path) {
  std::string ext = lowerExtension(path);
  GVDP_INPUT_CHECK(ext == ".off" || ext == ".ply" || ext == ".obj", path, ": unknown mesh format '",
                   ext, "' (expected .off, .ply or .obj)");
  std::string bytes = readBytes(path);
  if (ext == ".off") return readOff(bytes, path);
  if (ext == ".obj") return readObj(bytes, path);
  return readPly(bytes, path);
}

void writePly(const Mesh& mesh, const std::string& path) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment written by gvdp\nelement vertex " +
      std::to_string(mesh.vertices.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
      std::to_string(mesh.triangleCount()) +
      "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.reserve(out.size() + 12 * mesh.vertices.size() + 13 * mesh.triangleCount());
  for (Vec3f v : mesh.vertices)
    for (float c : {v.x, v.y, v.z}) putLittle(out, std::bit_cast<uint32_t>(c));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    out.push_back(3);
    for (int k = 0; k < 3; ++k) putLittle(out, mesh.indices[3 * t + k]);
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  GVDP_INPUT_CHECK(file, path, ": cannot write (", std::strerror(errno), ")");
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  file.close();
  GVDP_INPUT_CHECK(file, path, ": write failed");
}

}  // namespace gvdp::detail
