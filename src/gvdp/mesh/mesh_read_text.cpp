// The text formats: OFF (Princeton's Object File Format, also COFF/NOFF/CNOFF: values after a
// vertex's coordinates or a face's indices, colours and normals, are ignored) and Wavefront OBJ
// (v and f lines; f takes i, i/t, i//n and i/t/n, negative indices count back from the last
// vertex read; every other keyword is ignored). Line numbers are 1-based in messages.
#include <string>
#include <vector>

#include "gvdp/base/error.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/mesh/text_tokens.h"

namespace gvdp::detail {
namespace {

// Fan triangulation of one polygon.
void addPolygon(Mesh& mesh, const std::vector<uint32_t>& polygon) {
  for (size_t i = 1; i + 1 < polygon.size(); ++i) {
    mesh.indices.push_back(polygon[0]);
    mesh.indices.push_back(polygon[i]);
    mesh.indices.push_back(polygon[i + 1]);
  }
}

Vec3f parseVertex(const std::vector<std::string_view>& t, size_t first, const std::string& where) {
  GVDP_INPUT_CHECK(t.size() >= first + 3, where, ": a vertex needs three coordinates");
  float c[3];
  for (int k = 0; k < 3; ++k)
    GVDP_INPUT_CHECK(parseFloat(t[first + k], c[k]), where, ": '", t[first + k],
                     "' is not a number");
  return {c[0], c[1], c[2]};
}

}  // namespace

Mesh readOff(std::string_view text, const std::string& name) {
  Mesh mesh;
  std::vector<std::string_view> t;
  std::string_view line;
  size_t pos = 0;
  int lineNo = 0;
  auto where = [&] { return name + ":" + std::to_string(lineNo); };
  // The next line holding tokens (comments and blank lines skipped); false at the end.
  auto nextTokens = [&] {
    while (nextLine(text, pos, line)) {
      ++lineNo;
      splitTokens(line, t);
      if (!t.empty()) return true;
    }
    return false;
  };
  GVDP_INPUT_CHECK(nextTokens(), name, ": empty file");
  std::string_view header = t[0];
  GVDP_INPUT_CHECK(header.size() >= 3 && header.substr(header.size() - 3) == "OFF", where(),
                   ": not an OFF file (header '", header, "')");
  size_t first = 1;  // counts may follow the header on its line
  if (t.size() == 1) {
    GVDP_INPUT_CHECK(nextTokens(), name, ": truncated before the counts");
    first = 0;
  }
  int64_t nv = 0, nf = 0;
  GVDP_INPUT_CHECK(t.size() >= first + 2 && parseInt(t[first], nv) && parseInt(t[first + 1], nf),
                   where(), ": expected the counts 'vertices faces edges'");
  GVDP_INPUT_CHECK(nv > 0 && nv < (int64_t{1} << 32) && nf >= 0 && nf < (int64_t{1} << 31), where(),
                   ": counts out of range (", nv, " vertices, ", nf, " faces)");
  // A count is a promise about the lines that follow: reserve no more than the text can hold.
  mesh.vertices.reserve(static_cast<size_t>(std::min<int64_t>(nv, text.size() / 6 + 1)));
  for (int64_t i = 0; i < nv; ++i) {
    GVDP_INPUT_CHECK(nextTokens(), name, ": truncated: ", i, " of ", nv, " vertices");
    mesh.vertices.push_back(parseVertex(t, 0, where()));
  }
  std::vector<uint32_t> polygon;
  for (int64_t f = 0; f < nf; ++f) {
    GVDP_INPUT_CHECK(nextTokens(), name, ": truncated: ", f, " of ", nf, " faces");
    int64_t n = 0;
    GVDP_INPUT_CHECK(parseInt(t[0], n) && n >= 3 && static_cast<size_t>(n) < t.size(), where(),
                     ": a face needs a vertex count of at least 3 and that many indices");
    polygon.clear();
    for (int64_t k = 1; k <= n; ++k) {
      int64_t index = 0;
      GVDP_INPUT_CHECK(parseInt(t[k], index), where(), ": '", t[k], "' is not an index");
      GVDP_INPUT_CHECK(index >= 0 && index < nv, where(), ": index ", index, " out of range (", nv,
                       " vertices)");
      polygon.push_back(static_cast<uint32_t>(index));
    }
    addPolygon(mesh, polygon);
  }
  GVDP_INPUT_CHECK(!nextTokens(), where(), ": more data than the header's counts (", nv,
                   " vertices, ", nf, " faces)");
  validateMesh(mesh, name);
  return mesh;
}

Mesh readObj(std::string_view text, const std::string& name) {
  Mesh mesh;
  std::vector<std::string_view> t;
  std::vector<uint32_t> polygon;
  std::string_view line;
  size_t pos = 0;
  int lineNo = 0;
  while (nextLine(text, pos, line)) {
    ++lineNo;
    splitTokens(line, t);
    if (t.empty()) continue;
    std::string where = name + ":" + std::to_string(lineNo);
    if (t[0] == "v") {
      mesh.vertices.push_back(parseVertex(t, 1, where));
    } else if (t[0] == "f") {
      GVDP_INPUT_CHECK(t.size() >= 4, where, ": a face needs at least three vertices");
      polygon.clear();
      for (size_t k = 1; k < t.size(); ++k) {
        std::string_view v = t[k].substr(0, t[k].find('/'));
        int64_t index = 0;
        GVDP_INPUT_CHECK(parseInt(v, index) && index != 0, where, ": '", t[k],
                         "' is not a vertex reference");
        int64_t resolved =
            index > 0 ? index - 1 : static_cast<int64_t>(mesh.vertices.size()) + index;
        GVDP_INPUT_CHECK(resolved >= 0 && resolved < (int64_t{1} << 32), where, ": index ", index,
                         " out of range (", mesh.vertices.size(), " vertices before it)");
        polygon.push_back(static_cast<uint32_t>(resolved));
      }
      addPolygon(mesh, polygon);
    }
  }
  // Positive indices may name vertices of later lines; validateMesh checks them all.
  validateMesh(mesh, name);
  return mesh;
}

}  // namespace gvdp::detail
