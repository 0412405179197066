// PLY (Turk's Polygon File Format): ASCII, binary_little_endian and binary_big_endian 1.0.
// The vertex element's x, y, z and the face element's vertex_indices (or vertex_index) list are
// read; every other property and element is read past. The body must hold exactly what the
// header's counts say: a shorter body is truncated, a longer one has counts that lie.
#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "gvdp/base/error.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/mesh/text_tokens.h"

namespace gvdp::detail {
namespace {

enum class Format { Ascii, Little, Big };

struct Property {
  std::string name;
  int type = 0;           // bytes of a scalar (or of a list's items); float types flagged below
  bool isFloat = false;   //
  bool isSigned = false;  //
  bool isList = false;
  int countType = 0;  // bytes of a list's count
  bool countSigned = false;
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::vector<Property> properties;
};

// Bytes and kind of a PLY scalar type name; false when unknown.
bool scalarType(std::string_view t, int& bytes, bool& isFloat, bool& isSigned) {
  struct Kind {
    const char* a;
    const char* b;
    int bytes;
    bool isFloat, isSigned;
  };
  static const Kind KINDS[] = {
      {"char", "int8", 1, false, true},    {"uchar", "uint8", 1, false, false},
      {"short", "int16", 2, false, true},  {"ushort", "uint16", 2, false, false},
      {"int", "int32", 4, false, true},    {"uint", "uint32", 4, false, false},
      {"float", "float32", 4, true, true}, {"double", "float64", 8, true, true}};
  for (const Kind& k : KINDS)
    if (t == k.a || t == k.b) {
      bytes = k.bytes;
      isFloat = k.isFloat;
      isSigned = k.isSigned;
      return true;
    }
  return false;
}

// Reads the body's values in order, as doubles, from ASCII tokens or binary bytes.
class BodyReader {
 public:
  BodyReader(std::string_view body, Format format, const std::string& name)
      : body_(body), format_(format), name_(name) {}

  double read(int bytes, bool isFloat, bool isSigned, const std::string& what) {
    if (format_ == Format::Ascii) {
      std::string_view token = nextToken();
      GVDP_INPUT_CHECK(!token.empty(), name_, ": truncated in ", what);
      if (isFloat) {
        float f = 0.0f;
        GVDP_INPUT_CHECK(parseFloat(token, f), name_, ": '", token, "' is not a number in ", what);
        return f;
      }
      int64_t v = 0;
      GVDP_INPUT_CHECK(parseInt(token, v), name_, ": '", token, "' is not an integer in ", what);
      return static_cast<double>(v);
    }
    GVDP_INPUT_CHECK(pos_ + static_cast<size_t>(bytes) <= body_.size(), name_, ": truncated in ",
                     what);
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, static_cast<size_t>(bytes));
    pos_ += static_cast<size_t>(bytes);
    bool swap = (format_ == Format::Big) != (std::endian::native == std::endian::big);
    if (swap)
      for (int i = 0; i < bytes / 2; ++i) std::swap(b[i], b[bytes - 1 - i]);
    if (isFloat) {
      if (bytes == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    uint64_t u = 0;
    for (int i = 0; i < bytes; ++i)  // b is now in native order; assemble little-endian
      u |= static_cast<uint64_t>(b[std::endian::native == std::endian::big ? bytes - 1 - i : i])
           << (8 * i);
    if (isSigned && bytes < 8 && (u >> (8 * bytes - 1)) != 0) u |= ~uint64_t{0} << (8 * bytes);
    return isSigned ? static_cast<double>(static_cast<int64_t>(u)) : static_cast<double>(u);
  }

  bool atEnd() {
    if (format_ != Format::Ascii) return pos_ == body_.size();
    return nextToken().empty();
  }
  size_t remainingBytes() const { return body_.size() - pos_; }

 private:
  static bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  }
  std::string_view nextToken() {
    while (pos_ < body_.size() && isSpace(body_[pos_])) ++pos_;
    size_t start = pos_;
    while (pos_ < body_.size() && !isSpace(body_[pos_])) ++pos_;
    return body_.substr(start, pos_ - start);
  }

  std::string_view body_;
  Format format_;
  const std::string& name_;
  size_t pos_ = 0;
};

}  // namespace

Mesh readPly(std::string_view bytes, const std::string& name) {
  size_t pos = 0;
  std::string_view line;
  std::vector<std::string_view> t;
  GVDP_INPUT_CHECK(nextLine(bytes, pos, line) && line.substr(0, 3) == "ply", name,
                   ": not a PLY file (no 'ply' line)");
  Format format = Format::Ascii;
  bool formatSeen = false, ended = false;
  std::vector<Element> elements;
  while (!ended) {
    GVDP_INPUT_CHECK(nextLine(bytes, pos, line), name, ": truncated header (no end_header)");
    splitTokens(line, t, 0);
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      ended = true;
    } else if (t[0] == "format") {
      GVDP_INPUT_CHECK(t.size() >= 2, name, ": bad format line");
      if (t[1] == "ascii")
        format = Format::Ascii;
      else if (t[1] == "binary_little_endian")
        format = Format::Little;
      else if (t[1] == "binary_big_endian")
        format = Format::Big;
      else
        GVDP_INPUT_CHECK(false, name, ": unknown PLY format '", t[1], "'");
      formatSeen = true;
    } else if (t[0] == "element") {
      Element e;
      GVDP_INPUT_CHECK(
          t.size() == 3 && parseInt(t[2], e.count) && e.count >= 0 && e.count < (int64_t{1} << 32),
          name, ": bad element line '", line, "'");
      e.name = std::string(t[1]);
      elements.push_back(e);
    } else if (t[0] == "property") {
      GVDP_INPUT_CHECK(!elements.empty(), name, ": a property before any element");
      Property p;
      bool ok = false;
      if (t.size() == 5 && t[1] == "list") {
        bool countFloat = false;
        p.isList = true;
        ok = scalarType(t[2], p.countType, countFloat, p.countSigned) && !countFloat &&
             scalarType(t[3], p.type, p.isFloat, p.isSigned);
        p.name = std::string(t[4]);
      } else if (t.size() == 3) {
        ok = scalarType(t[1], p.type, p.isFloat, p.isSigned);
        p.name = std::string(t[2]);
      }
      GVDP_INPUT_CHECK(ok, name, ": bad property line '", line, "'");
      elements.back().properties.push_back(p);
    } else {
      GVDP_INPUT_CHECK(false, name, ": unknown header line '", line, "'");
    }
  }
  GVDP_INPUT_CHECK(formatSeen, name, ": no format line");
  BodyReader body(bytes.substr(std::min(pos, bytes.size())), format, name);
  Mesh mesh;
  int64_t vertexCount = -1;
  std::vector<uint32_t> polygon;
  for (const Element& e : elements) {
    bool isVertex = e.name == "vertex", isFace = e.name == "face";
    int axisOf[16];
    int listIndex = -1;
    for (size_t i = 0; i < e.properties.size() && i < 16; ++i) {
      const Property& p = e.properties[i];
      axisOf[i] = !isVertex || p.isList ? -1
                                        : (p.name == "x"   ? 0
                                           : p.name == "y" ? 1
                                           : p.name == "z" ? 2
                                                           : -1);
      if (isFace && p.isList && (p.name == "vertex_indices" || p.name == "vertex_index"))
        listIndex = static_cast<int>(i);
    }
    GVDP_INPUT_CHECK(e.properties.size() <= 16, name, ": element ", e.name,
                     " has over 16 properties");
    if (isVertex) {
      int seen = 0;
      for (size_t i = 0; i < e.properties.size(); ++i) seen |= axisOf[i] >= 0 ? 1 << axisOf[i] : 0;
      GVDP_INPUT_CHECK(seen == 7, name, ": the vertex element lacks x, y or z");
      // The smallest a vertex can be: one byte or one ASCII character and a space per value.
      GVDP_INPUT_CHECK(static_cast<size_t>(e.count) <= body.remainingBytes() / 3, name,
                       ": truncated: ", e.count, " vertices cannot fit in the ",
                       body.remainingBytes(), " bytes after the header");
      mesh.vertices.reserve(static_cast<size_t>(e.count));
      vertexCount = e.count;
    }
    if (isFace) GVDP_INPUT_CHECK(listIndex >= 0, name, ": the face element has no vertex_indices");
    for (int64_t r = 0; r < e.count; ++r) {
      std::string what =
          "element " + e.name + " " + std::to_string(r) + " of " + std::to_string(e.count);
      float xyz[3] = {0.0f, 0.0f, 0.0f};
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (!p.isList) {
          double v = body.read(p.type, p.isFloat, p.isSigned, what);
          if (isVertex && axisOf[i] >= 0) xyz[axisOf[i]] = static_cast<float>(v);
          continue;
        }
        double n = body.read(p.countType, false, p.countSigned, what);
        GVDP_INPUT_CHECK(n >= 0 && n <= 1e6, name, ": a list of ", n, " items in ", what);
        bool faceList = static_cast<int>(i) == listIndex;
        if (faceList) GVDP_INPUT_CHECK(n >= 3, name, ": a face of ", n, " vertices (", what, ")");
        polygon.clear();
        for (int k = 0; k < static_cast<int>(n); ++k) {
          double v = body.read(p.type, p.isFloat, p.isSigned, what);
          if (!faceList) continue;
          GVDP_INPUT_CHECK(v >= 0 && v < static_cast<double>(vertexCount), name, ": index ", v,
                           " out of range (", vertexCount < 0 ? 0 : vertexCount, " vertices; ",
                           what, ")");
          polygon.push_back(static_cast<uint32_t>(v));
        }
        for (size_t k = 1; k + 1 < polygon.size(); ++k)
          mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
      }
      if (isVertex) mesh.vertices.push_back({xyz[0], xyz[1], xyz[2]});
    }
  }
  GVDP_INPUT_CHECK(vertexCount >= 0, name, ": no vertex element");
  GVDP_INPUT_CHECK(body.atEnd(), name, ": more data than the header's counts");
  validateMesh(mesh, name);
  return mesh;
}

}  // namespace gvdp::detail
