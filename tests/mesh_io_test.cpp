// The mesh readers and writer (mesh/mesh_io.h) on tiny files written here, every malformed case
// refused in one line naming the file; the subdivision (mesh/mesh_subdivide.h); placement.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gvdp/base/error.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/mesh/mesh_subdivide.h"
#include "mesh_test_util.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

std::string dir() {
  static std::string d = [] {
    std::string p = test::tempDir("mesh_io");
    std::filesystem::create_directories(p);
    return p;
  }();
  return d;
}

std::string writeFile(const std::string& name, const std::string& bytes) {
  std::string path = dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The unit square in z = 0 as one quad and one triangle on top of it at z = 1.
const char* OFF_TEXT =
    "OFF # a comment\n"
    "# counts follow\n"
    "5 2 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n\n0.5 0.5 1.0\n"
    "4 0 1 2 3\n"
    "3 0 1 4   # a triangle\n";

void expectSquareAndTip(const Mesh& m) {
  ASSERT_EQ(m.vertices.size(), 5u);
  ASSERT_EQ(m.triangleCount(), 3u);
  // the quad as a fan (0, 1, 2), (0, 2, 3)
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4}));
  EXPECT_EQ(m.vertices[4].z, 1.0f);
  EXPECT_EQ(m.vertices[2].x, 1.0f);
}

template <class T>
void put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

// The same square and tip as binary PLY, with doubles, an extra property, an extra element.
std::string binaryPly(bool big) {
  std::string s = std::string("ply\nformat ") +
                  (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment test\nelement vertex 5\nproperty double x\nproperty double y\n"
                  "property double z\nproperty uchar red\nelement face 2\n"
                  "property list uchar int vertex_indices\nproperty float quality\n"
                  "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  const double v[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
  for (const auto& p : v) {
    for (double c : p) put(s, c, big);
    put<uint8_t>(s, 200, big);
  }
  put<uint8_t>(s, 4, big);
  for (int i : {0, 1, 2, 3}) put<int32_t>(s, i, big);
  put(s, 0.5f, big);
  put<uint8_t>(s, 3, big);
  for (int i : {0, 1, 4}) put<int32_t>(s, i, big);
  put(s, 0.5f, big);
  put<int32_t>(s, 0, big);
  put<int32_t>(s, 1, big);
  return s;
}

const char* PLY_ASCII =
    "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 5\nproperty float x\n"
    "property float y\nproperty float z\nproperty float nx\nelement face 2\n"
    "property list uchar uint vertex_index\nend_header\n"
    "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n0.5 0.5 1 1\n4 0 1 2 3\n3 0 1 4\n";

}  // namespace

TEST(MeshIo, ReadsOffWithCommentsAndQuads) {
  expectSquareAndTip(readMesh(writeFile("square.off", OFF_TEXT)));
  // counts on the header line, colours after coordinates and indices (COFF)
  expectSquareAndTip(
      readMesh(writeFile("square_colours.OFF",
                         "COFF 5 2 0\n0 0 0 9 9 9\n1 0 0 9 9 9\n1 1 0 9 9 9\n0 1 0 9 9 9\n"
                         "0.5 0.5 1 9 9 9\n4 0 1 2 3 255 0 0\n3 0 1 4 0 255 0\n")));
}

TEST(MeshIo, ReadsPlyAsciiAndBinaryOfBothEndians) {
  expectSquareAndTip(readMesh(writeFile("square_ascii.ply", PLY_ASCII)));
  expectSquareAndTip(readMesh(writeFile("square_le.ply", binaryPly(false))));
  expectSquareAndTip(readMesh(writeFile("square_be.ply", binaryPly(true))));
}

TEST(MeshIo, ReadsObjWithQuadsNegativeIndicesAndSlashForms) {
  expectSquareAndTip(readMesh(
      writeFile("square.obj",
                "# a comment\nmtllib none.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                "vt 0 0\nvn 0 0 1\ns off\nusemtl x\n"
                "f 1/1/1 2/1/1 3//1 4/1\n"  // the quad, every slash form
                "v 0.5 0.5 1.0 # the tip\n"
                "f -5 -4 -1\n")));  // relative indices: 0 1 4
}

TEST(MeshIo, WritePlyRoundTrips) {
  Mesh m = test::icosphere(1);
  std::string path = dir() + "/sphere.ply";
  writePly(m, path);
  Mesh back = readMesh(path);
  EXPECT_EQ(back.indices, m.indices);
  ASSERT_EQ(back.vertices.size(), m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    EXPECT_EQ(std::bit_cast<uint32_t>(back.vertices[i].x),
              std::bit_cast<uint32_t>(m.vertices[i].x));
    EXPECT_EQ(back.vertices[i].z, m.vertices[i].z);
  }
}

// Every broken file: InputError, one line, naming the file and the problem.
TEST(MeshIo, BrokenFilesAreOneLineInputErrorsNamingTheFile) {
  std::string ply = binaryPly(false);
  std::string plyHeaderOnly = ply.substr(0, ply.find("end_header\n") + 11);
  struct Case {
    std::string name, bytes, mentions;
  };
  const Case cases[] = {
      {"truncated.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n", "truncated: 2 of 5 vertices"},
      {"truncated_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "1 of 2 faces"},
      {"more.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "more data"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "not finite"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "not finite"},
      {"huge.off", "OFF\n3 1 0\n0 0 0\n1 1e60 0\n0 1 0\n3 0 1 2\n", "not finite"},
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "index 3 out of range"},
      {"noface.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "no faces"},
      {"header.off", "PFF\n3 0 0\n", "not an OFF file"},
      {"empty.off", "", "empty file"},
      {"word.off", "OFF\n3 1 0\n0 zero 0\n1 0 0\n0 1 0\n3 0 1 2\n", "'zero' is not a number"},
      {"twogon.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "vertex count of at least 3"},
      {"lying_counts.off", "OFF\n4000000000 1 0\n0 0 0\n", "truncated: 1 of 4000000000"},
      {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "uses vertex 3 of 3"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "'0' is not a vertex reference"},
      {"negative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n", "index -3 out of range"},
      {"noface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
      {"nan.obj", "v 0 0 0\nv 1 -nan 0\nv 0 1 0\nf 1 2 3\n", "not finite"},
      {"short.obj", "v 0 0\nf 1 1 1\n", "three coordinates"},
      {"truncated_le.ply", ply.substr(0, ply.size() - 30), "truncated"},
      {"header_only.ply", plyHeaderOnly, "truncated"},
      {"longer.ply", ply + "extra", "more data"},
      {"no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
       "no end_header"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown PLY format"},
      {"noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
       "lacks x, y or z"},
      {"index.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
       "index 7 out of range"},
      {"nan.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n",
       "not finite"},
      {"noface.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
       "no faces"},
      {"lying.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
       "property float y\nproperty float z\nend_header\nabc",
       "4000000000 vertices cannot fit"},
      {"cube.stl", "solid cube\n", "unknown mesh format '.stl'"},
  };
  for (const Case& c : cases) {
    std::string path = writeFile(c.name, c.bytes);
    try {
      readMesh(path);
      ADD_FAILURE() << c.name << ": no error";
    } catch (const InputError& e) {
      std::string m = e.what();
      EXPECT_EQ(m.find(path), 0u) << c.name << ": " << m;
      EXPECT_NE(m.find(c.mentions), std::string::npos) << c.name << ": " << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << c.name << ": " << m;
    }
  }
  std::string missing = dir() + "/missing.off";
  try {
    readMesh(missing);
    ADD_FAILURE() << "missing file: no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find(missing + ": cannot open"), 0u) << e.what();
  }
  EXPECT_THROW(writePly(test::cubeMesh(), "/proc/gvdp_cannot_be_here.ply"), InputError);
}

TEST(MeshSubdivide, FourTimesTheFacesAndAClosedMeshStaysClosed) {
  for (const Mesh& m0 : {test::cubeMesh(), test::icosphere(0)}) {
    ASSERT_TRUE(test::isClosed(m0));
    Mesh m = m0;
    for (int i = 1; i <= 3; ++i) {
      size_t edges = m.indices.size() / 2;  // closed: every edge in two triangles
      Mesh next = subdivide(m, 1);
      EXPECT_EQ(next.triangleCount(), 4 * m.triangleCount());
      EXPECT_EQ(next.vertices.size(), m.vertices.size() + edges);
      EXPECT_TRUE(test::isClosed(next)) << "after " << i;
      m = next;
    }
    EXPECT_EQ(subdivide(m0, 3).indices, m.indices);
  }
  // midpoints: the first new vertex of a cube lies halfway along an edge
  Mesh c = subdivide(test::cubeMesh(0.0f, 2.0f), 1);
  for (size_t i = 8; i < c.vertices.size(); ++i) {
    Vec3f v = c.vertices[i];
    int halves = (v.x == 1.0f) + (v.y == 1.0f) + (v.z == 1.0f);
    EXPECT_GE(halves, 1) << i;
  }
}

TEST(MeshIo, PlaceMeshCentresAndScalesTheLongestSide) {
  Mesh m = test::cubeMesh(3.0f, 4.0f);
  m.vertices[0].x = -5.0f;  // x spans 12
  placeMesh(m);
  Box3f b = meshBounds(m);
  EXPECT_FLOAT_EQ(b.hi.x - b.lo.x, MESH_PLACED_SIZE);
  EXPECT_FLOAT_EQ(b.lo.x + b.hi.x, 0.0f);
  EXPECT_FLOAT_EQ(b.lo.y + b.hi.y, 0.0f);
  EXPECT_FLOAT_EQ(b.hi.y - b.lo.y, 4.0f / 12.0f);
}

}  // namespace gvdp::detail
