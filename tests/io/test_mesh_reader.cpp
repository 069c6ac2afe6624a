// Mesh files: PLY (ASCII, binary of both byte orders) and OBJ read into the same triangles,
// with their normals and uv; malformed files refused with the line or element named.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <sys/stat.h>

#include "core/error.h"
#include "io/mesh_cache.h"
#include "io/mesh_reader.h"
#include "support/errors.h"

namespace nx {
namespace {

std::string writeFile(const std::string& name, const std::string& bytes) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// A unit square in z = 0 as two triangles, with normals +z and uv = (x, y).
const float kPositions[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const int kFaces[2][3] = {{0, 1, 2}, {0, 2, 3}};

std::string plyHeader(const std::string& format) {
  return "ply\nformat " + format +
         " 1.0\ncomment a unit square\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
         "property float u\nproperty float v\nelement face 2\n"
         "property list uchar int vertex_indices\nend_header\n";
}

std::string asciiPly() {
  std::string s = plyHeader("ascii");
  for (const auto& p : kPositions)
    s += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
         " 0 0 1 " + std::to_string(p[0]) + " " + std::to_string(p[1]) + "\n";
  for (const auto& f : kFaces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         "\n";
  return s;
}

template <class T>
void put(std::string& s, T v, bool bigEndian) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binaryPly(bool bigEndian) {
  std::string s = plyHeader(bigEndian ? "binary_big_endian" : "binary_little_endian");
  for (const auto& p : kPositions)
    for (float v : {p[0], p[1], p[2], 0.0f, 0.0f, 1.0f, p[0], p[1]}) put(s, v, bigEndian);
  for (const auto& f : kFaces) {
    put<uint8_t>(s, 3, bigEndian);
    for (int i : f) put<int32_t>(s, i, bigEndian);
  }
  return s;
}

// The mesh's triangles as sorted corner lists, sorted: equal for equal geometry whatever the
// vertex order and numbering.
std::vector<std::array<std::array<float, 3>, 3>> triangleSet(const TriangleMesh& m) {
  std::vector<std::array<std::array<float, 3>, 3>> out;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    std::array<std::array<float, 3>, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.position(m.triangle(t)[k]);
      tri[static_cast<size_t>(k)] = {p.x, p.y, p.z};
    }
    std::sort(tri.begin(), tri.end());
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MeshReader, AsciiAndBinaryPlyReadTheSameSquare) {
  const TriangleMesh ascii = readMeshFile(writeFile("sq_ascii.ply", asciiPly())).mesh;
  for (bool big : {false, true}) {
    const TriangleMesh bin =
        readMeshFile(writeFile(big ? "sq_be.ply" : "sq_le.ply", binaryPly(big))).mesh;
    EXPECT_EQ(triangleSet(bin), triangleSet(ascii)) << big;
  }
  ASSERT_EQ(ascii.triangleCount(), 2u);
  ASSERT_TRUE(ascii.hasNormals());
  ASSERT_TRUE(ascii.hasUv());
  for (uint32_t i = 0; i < ascii.vertexCount(); ++i) {
    EXPECT_EQ(ascii.normal(i).z, 1.0f);
    float u, v;
    ascii.uv(i, u, v);
    EXPECT_EQ(u, ascii.position(i).x); // uv = (x, y) as written
    EXPECT_EQ(v, ascii.position(i).y);
  }
}

TEST(MeshReader, ObjOfTheSameObjectAgreesWithPly) {
  // The square as one quad (triangulated on reading), with uv and normals.
  const std::string obj = "# a unit square\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                          "f 1/1/1 2/2/1 3/3/1 4/4/1\n";
  const TriangleMesh fromObj = readMeshFile(writeFile("sq.obj", obj)).mesh;
  const TriangleMesh fromPly = readMeshFile(writeFile("sq2.ply", asciiPly())).mesh;
  EXPECT_EQ(fromObj.triangleCount(), 2u);
  // Both triangulations of a square cover it; compare the areas and the corner set.
  double area = 0;
  for (size_t t = 0; t < fromObj.triangleCount(); ++t) {
    const TriangleShape c = fromObj.corners(t);
    area += 0.5 * length(cross(c.b - c.a, c.c - c.a));
  }
  EXPECT_NEAR(area, 1.0, 1e-7);
  ASSERT_TRUE(fromObj.hasUv());
  ASSERT_TRUE(fromObj.hasNormals());
  for (uint32_t i = 0; i < fromObj.vertexCount(); ++i) {
    float u, v;
    fromObj.uv(i, u, v);
    EXPECT_EQ(u, fromObj.position(i).x);
    EXPECT_EQ(v, fromObj.position(i).y);
    EXPECT_EQ(fromObj.normal(i).z, 1.0f);
  }
  // Written as the PLY's two triangles, the OBJ reads the same triangles.
  const std::string obj2 = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf -4 -2 -1\n";
  EXPECT_EQ(triangleSet(readMeshFile(writeFile("sq3.obj", obj2)).mesh), triangleSet(fromPly));
}

TEST(MeshReader, TransformMovesPointsAndNormals) {
  TriangleMesh m = readMeshFile(writeFile("sq4.ply", asciiPly())).mesh;
  // Scale x by 2, then rotate 90 degrees about +x (y -> z), then translate by (1, 2, 3).
  const Matrix3 r = {{{2, 0, 0}, {0, 0, -1}, {0, 1, 0}}};
  m.transform(r, Vec3d(1, 2, 3));
  for (uint32_t i = 0; i < 4; ++i) {
    const Vec3 p = m.position(i);
    const float* q = kPositions[i];
    // The vertex order is the file's (no vertex is shared twice in this square).
    EXPECT_FLOAT_EQ(p.x, 2 * q[0] + 1);
    EXPECT_FLOAT_EQ(p.y, -q[2] + 2);
    EXPECT_FLOAT_EQ(p.z, q[1] + 3);
    EXPECT_NEAR(m.normal(i).x, 0.0f, 1e-7f); // +z rotates to -y
    EXPECT_NEAR(m.normal(i).y, -1.0f, 1e-7f);
  }
}

TEST(MeshReader, MalformedFilesNameTheProblem) {
  std::string ascii = asciiPly();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.ply", ascii.substr(0, ascii.size() - 10)},
      {"short.ply", ascii.substr(0, ascii.size() - 8)},
      {"badface.ply", ascii.substr(0, ascii.rfind("3 0 2 3")) + "3 0 2 4\n"},
      {"twoverts.ply", ascii.substr(0, ascii.rfind("3 0 2 3")) + "2 0 2\n"},
      {"extra.ply", ascii + "1 2 3\n"},
      {"shortbin.ply", binaryPly(false).substr(0, binaryPly(false).size() - 3)},
      {"noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                     "y\nproperty float z\nend_header\n0 0 0\n"},
      {"badformat.ply", "ply\nformat text 1.0\nend_header\n"},
      {"badref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"},
      {"badvt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"},
      {"inf.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n"},
      {"empty.obj", ""},
      {"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"},
      {"pointref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\np 9\n"},
      {"lineref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 -4\n"},
      // Fuzzing findings: a vertex of 5 numbers made the library leak; a second vertex element,
      // a list-valued x, float indices and a NUL in the header are refused before it.
      {"fivev.obj", "v 0 1 1\nv 1 1 1\nv 1 1 0 1 1\nv 1 1 1\nf 3 2 1\n"},
      {"twovert.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                      "y\nproperty float z\nelement vertex 1\nproperty float x\nproperty float "
                      "y\nproperty float z\nelement face 1\nproperty list uchar int "
                      "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 0\n3 0 1 2\n"},
      {"floatidx.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                       "y\nproperty float z\nelement face 1\nproperty list uchar float "
                       "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"plus.ply", ascii.substr(0, ascii.rfind("3 0 2 3")) + "+3 0 2 3\n"},
      {"hex.obj", "v 0 0 0\nv 1 0 0\nv 0 0x1 0\nf 1 2 3\n"},
      {"dot.obj", "v 0 1 1\nv 1 1 1\nv 1 .1 1\nv 7 1 1\nf 1 4 3\ng 5\nv 4 3 2\nf 5 2 1"},
      {"nul.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng 5\0l 1\n", 40)},
      {"indent.obj", "v 1 1 1\nv 1 1 1\nv 7 1 1\nf 1 3 3\ng 5\n v 1 1 1\nf 4 3 2"},
      {"nul.ply", std::string("ply\nformat ascii 1.0\nelement v\0rtex 3\n", 38)},
  };
  const std::vector<std::string> expected = {
      "truncated.ply:20: expected more numbers on this face line, found 3",
      "short.ply: expected 2 face lines, found the end of the file after 1",
      "badface.ply:21: expected vertex indices within [0, 4), found 4",
      "twoverts.ply:21: expected a face of at least 3 vertices, found 2",
      "extra.ply:22: expected the end of the file after the last element",
      "shortbin.ply: expected 2 face items in the binary body, found the file ending within item 1",
      "noface.ply:7: expected a 'face' element in the header (the mesh has no faces)",
      "badformat.ply:2: expected 'format ascii|binary_little_endian|binary_big_endian 1.0'",
      "badref.obj:4: expected a vertex reference",
      "badvt.obj:4: expected references to the 0 texture coordinates read so far, found '1/1'",
      "inf.obj:2: expected a finite number, found 'inf'",
      "empty.obj: expected faces ('f' lines), found none",
      "flat.obj': every triangle has zero area",
      "pointref.obj:5: expected references to the 3 vertices read so far, found '9'",
      "lineref.obj:5: expected references to the 3 vertices read so far, found '-4'",
      "fivev.obj:3: expected 3, 4 or 6 numbers after 'v' (x y z, x y z w or x y z r g b), found 5",
      "twovert.ply:13: expected one 'vertex' element in the header, found two",
      "floatidx.ply:9: expected the face property 'vertex_indices' as a list of integers",
      "plus.ply:21: expected a whole list length, found '+3'",
      "hex.obj:3: expected a finite number, found '0x1'",
      "dot.obj:3: expected a finite number, found '.1'",
      "nul.obj:5: expected text without control bytes in an OBJ file, found the byte 0",
      "indent.obj:6: expected the statement 'v' at the start of its line (the mesh library "
      "skips indented lines), found it indented",
      "nul.ply:3: expected printable ASCII in the PLY header, found the byte 0",
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = writeFile(cases[i].first, cases[i].second);
    const std::string message = test::errorMessage([&] { readMeshFile(path); });
    EXPECT_NE(message.find(expected[i]), std::string::npos) << cases[i].first << ": " << message;
  }
}

// A binary PLY cut exactly at an item boundary is truncated too (it passed the check, then
// spun through 4e9 declared faces or reached the library's "mIndices[0] is out of range");
// binary indices are checked like ASCII ones.
TEST(MeshReader, BinaryPlyCutAtAnItemBoundaryIsTruncated) {
  const std::string whole = binaryPly(false);
  const size_t oneFace = 1 + 3 * 4;
  const std::string cut = writeFile("cutface.ply", whole.substr(0, whole.size() - oneFace));
  EXPECT_EQ(test::errorMessage([&] { readMeshFile(cut); }),
            cut +
                ": expected 2 face items in the binary body, found the file ending before item "
                "1 (truncated at byte " +
                std::to_string(whole.size() - oneFace) + ")");
  std::string huge = whole;
  huge.replace(huge.find("element face 2"), 14, "element face 4000000000");
  const std::string many = writeFile("manyfaces.ply", huge);
  EXPECT_NE(test::errorMessage([&] {
              readMeshFile(many);
            }).find("expected 4000000000 face items in the binary body, found the file ending"),
            std::string::npos);
  std::string bad = whole;
  const int32_t outside = 7, negative = -2;
  std::memcpy(&bad[bad.size() - 4], &outside, 4);
  EXPECT_EQ(test::errorMessage([&] { readMeshFile(writeFile("binindex.ply", bad)); }),
            ::testing::TempDir() +
                "/binindex.ply: expected vertex indices within [0, 4), found 7 in face 1");
  std::memcpy(&bad[bad.size() - 4], &negative, 4);
  EXPECT_EQ(test::errorMessage([&] { readMeshFile(writeFile("binneg.ply", bad)); }),
            ::testing::TempDir() +
                "/binneg.ply: expected vertex indices within [0, 4), found -2 in face 1");
}

// An OBJ's mtllib is never opened (the library opened it relative to the working directory:
// a FIFO there blocked forever, a directory gave "File read error").
TEST(MeshReader, ObjMaterialLibrariesAreNotOpened) {
  const std::string dir = ::testing::TempDir() + "/mtl";
  std::filesystem::create_directories(dir + "/lib.mtl.d");
  const std::string fifo = dir + "/fifo.mtl";
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  for (const std::string& lib : {fifo, std::string("fifo.mtl"), dir + "/lib.mtl.d"}) {
    std::ofstream(dir + "/m.obj") << "mtllib " << lib << "\n" << body;
    EXPECT_EQ(readMeshFile(dir + "/m.obj").mesh.triangleCount(), 1u) << lib;
  }
  std::filesystem::remove(fifo);
}

// A file read again with the same bytes comes from the cache (the same triangles, not parsed
// again); changed on disk, it is parsed anew; the same bytes under another format's extension
// are not taken for it.
TEST(MeshReader, FilesReadAgainComeFromTheCacheByTheirBytes) {
  // Bytes no other test reads (a comment in the header).
  std::string original = asciiPly();
  original.insert(original.find('\n', original.find("format")) + 1, "comment read twice\n");
  const std::string path = writeFile("cached.ply", original);
  const size_t before = cachedMeshCount();
  const TriangleMesh first = readMeshFile(path).mesh;
  EXPECT_EQ(cachedMeshCount(), before + 1);
  const MeshFile again = readMeshFile(path);
  EXPECT_EQ(cachedMeshCount(), before + 1);
  EXPECT_EQ(again.bytes, original);
  EXPECT_EQ(triangleSet(again.mesh), triangleSet(first));
  // The file changed in place (one vertex moved): its new triangles, a second entry.
  std::string moved = original;
  const size_t at = moved.find("end_header\n") + 11; // the first vertex's x: 0 becomes 0.25
  moved.replace(at, moved.find(' ', at) - at, "0.25");
  writeFile("cached.ply", moved);
  const TriangleMesh changed = readMeshFile(path).mesh;
  EXPECT_EQ(cachedMeshCount(), before + 2);
  EXPECT_NE(triangleSet(changed), triangleSet(first));
  // Transforming a read mesh leaves the cached one as it was.
  TriangleMesh scaled = readMeshFile(path).mesh;
  scaled.transform(Matrix3{{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}}, Vec3d());
  EXPECT_EQ(triangleSet(readMeshFile(path).mesh), triangleSet(changed));
  // The cache is keyed by size and SHA-256, keeps no bytes, and can be emptied.
  EXPECT_EQ(meshKeyOf(moved, "ply").digest, meshKeyOf(std::string(moved), "ply").digest);
  EXPECT_FALSE(meshKeyOf(moved, "ply") == meshKeyOf(original, "ply"));
  EXPECT_FALSE(meshKeyOf(moved, "ply") == meshKeyOf(moved, "obj"));
  clearMeshCache();
  EXPECT_EQ(cachedMeshCount(), 0u);
  EXPECT_EQ(triangleSet(readMeshFile(path).mesh), triangleSet(changed));
  EXPECT_EQ(cachedMeshCount(), 1u);
}

} // namespace
} // namespace nx
