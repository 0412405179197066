// Mesh files: OFF, PLY (ASCII, binary little and big endian) and OBJ in; binary PLY out.
// Polygons are triangulated as fans (v0, vi, vi+1). A file that cannot be a mesh (missing,
// unknown extension, truncated, counts that lie, a coordinate that is NaN or infinite, an index
// out of range, no faces) throws one InputError line that starts with the file's name.
#pragma once

#include <string>
#include <string_view>

#include "gvdp/mesh/mesh.h"

namespace gvdp::detail {

// By extension, case-insensitive: .off, .ply, .obj. The mesh as stored (no placement).
Mesh readMesh(const std::string& path);

// The readers over a file's bytes; `name` starts every error message.
Mesh readOff(std::string_view text, const std::string& name);
Mesh readObj(std::string_view text, const std::string& name);
Mesh readPly(std::string_view bytes, const std::string& name);

// Binary little-endian PLY: float x y z per vertex, a uchar-counted uint list per face.
void writePly(const Mesh& mesh, const std::string& path);

}  // namespace gvdp::detail
