// Tests of LoadPly: Mitsuba's rectangle against the OBJ, both byte orders, polygons, attributes,
// and malformed files (errors with line or byte, counts checked before allocation).
#include "engine/io/ply_loader.h"

#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <cmath>
#include <string>

#include "engine/io/obj_loader.h"
#include "tests/engine/io/mesh_file_writers.h"

namespace ptlab {
namespace {

const std::string kMitsubaData = ptlab::test_data::Path("mitsuba3");

// Whether a and b describe the same triangles: corner by corner, equal positions, normals and
// uvs (to 1e-6), in the same order.
void ExpectSameMesh(const MeshData& a, const MeshData& b) {
  ASSERT_EQ(a.indices.size(), b.indices.size());
  ASSERT_EQ(a.normals.empty(), b.normals.empty());
  ASSERT_EQ(a.uvs.empty(), b.uvs.empty());
  for (size_t k = 0; k < a.indices.size(); ++k) {
    const uint32_t i = a.indices[k], j = b.indices[k];
    EXPECT_NEAR(a.positions[i].x, b.positions[j].x, 1e-6) << k;
    EXPECT_NEAR(a.positions[i].y, b.positions[j].y, 1e-6) << k;
    EXPECT_NEAR(a.positions[i].z, b.positions[j].z, 1e-6) << k;
    if (!a.normals.empty()) {
      EXPECT_NEAR(a.normals[i].x, b.normals[j].x, 1e-6) << k;
      EXPECT_NEAR(a.normals[i].y, b.normals[j].y, 1e-6) << k;
      EXPECT_NEAR(a.normals[i].z, b.normals[j].z, 1e-6) << k;
    }
    if (!a.uvs.empty()) {
      EXPECT_NEAR(a.uvs[i].x, b.uvs[j].x, 1e-6) << k;
      EXPECT_NEAR(a.uvs[i].y, b.uvs[j].y, 1e-6) << k;
    }
  }
}

TEST(PlyLoader, MitsubaRectangleMatchesTheObj) {
  const StatusOr<MeshData> obj = LoadObj(kMitsubaData + "/tests/obj/rectangle_normals_uv.obj");
  ASSERT_TRUE(obj.ok()) << obj.status().message();
  const StatusOr<MeshData> ply = LoadPly(kMitsubaData + "/tests/ply/rectangle_normals_uv.ply");
  ASSERT_TRUE(ply.ok()) << ply.status().message();
  EXPECT_EQ(ply->triangle_count(), 2u);
  EXPECT_EQ(ply->uvs.size(), 4u);  // texture_u / texture_v
  ExpectSameMesh(*ply, *obj);
  EXPECT_TRUE(ply->attributes.empty());
}

TEST(PlyLoader, BinaryBothByteOrdersRoundTrip) {
  const MeshData grid = test_util::GridMesh(7);
  for (bool big : {false, true}) {
    const StatusOr<MeshData> m =
        LoadPlyFromBytes(test_util::PlyBinaryBytes(grid, big), big ? "be.ply" : "le.ply");
    ASSERT_TRUE(m.ok()) << m.status().message();
    EXPECT_EQ(m->positions.size(), grid.positions.size());
    EXPECT_EQ(m->indices, grid.indices);
    ExpectSameMesh(*m, grid);
  }
}

TEST(PlyLoader, PolygonsAreFanTriangulatedAndAttributesGrouped) {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment a quad and a pentagon\n"
      "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "property float s\nproperty float t\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nproperty float temperature\n"
      "element face 2\nproperty list uchar uint vertex_index\nproperty float weight_0\n"
      "property float dir_x\nproperty float dir_y\n"
      "element edge 1\nproperty int vertex1\nproperty list uchar int more\n"
      "end_header\n"
      "0 0 0 0 0 255 0 0 1.5\n1 0 0 1 0 0 255 0 2.5\n1 1 0 1 1 0 0 255 3.5\n"
      "0 1 0 0 1 255 255 255 4.5\n2 0 0 1 0 0 0 0 5.5\n2 1 0 1 1 128 128 128 6.5\n"
      "4 0 1 2 3 0.25 1 0\n"
      "5 1 4 5 2 3 0.75 0 1\n"
      "0 2 7 8\n";
  const StatusOr<MeshData> m = LoadPlyFromBytes(text, "poly.ply");
  ASSERT_TRUE(m.ok()) << m.status().message();
  ASSERT_EQ(m->triangle_count(), 2u + 3u);
  const std::vector<uint32_t> expected = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2, 1, 2, 3};
  EXPECT_EQ(m->indices, expected);
  ASSERT_EQ(m->uvs.size(), 6u);  // s / t
  EXPECT_EQ(m->uvs[2].x, 1.0f);
  ASSERT_EQ(m->attributes.size(), 4u);
  const MeshAttribute& color = m->attributes[0];
  EXPECT_EQ(color.name, "vertex_color");
  EXPECT_EQ(color.dim, 3u);
  ASSERT_EQ(color.rows(), 6u);
  EXPECT_EQ(color.values[0], 1.0f);  // 255 / 255
  EXPECT_EQ(color.values[1], 0.0f);
  // 128 / 255 decoded from sRGB: ((0.50196 + 0.055) / 1.055)^2.4 = 0.21586.
  EXPECT_NEAR(color.values[15], 0.215861, 1e-5);
  const MeshAttribute& temperature = m->attributes[1];
  EXPECT_EQ(temperature.name, "vertex_temperature");
  EXPECT_EQ(temperature.dim, 1u);
  EXPECT_EQ(temperature.values[3], 4.5f);  // floats are kept as they are
  const MeshAttribute& weight = m->attributes[2];
  EXPECT_EQ(weight.name, "face_weight");
  EXPECT_EQ(weight.dim, 1u);
  ASSERT_EQ(weight.rows(), 5u);  // one row per triangle: the quad's twice, the pentagon's thrice
  EXPECT_EQ(weight.values, (std::vector<float>{0.25f, 0.25f, 0.75f, 0.75f, 0.75f}));
  const MeshAttribute& dir = m->attributes[3];
  EXPECT_EQ(dir.name, "face_dir");
  EXPECT_EQ(dir.dim, 2u);
  EXPECT_EQ(dir.values, (std::vector<float>{1, 0, 1, 0, 0, 1, 0, 1, 0, 1}));
}

TEST(PlyLoader, MitsubaMeshAttributeSphere) {
  const StatusOr<MeshData> m =
      LoadPly(kMitsubaData + "/tests/scenes/mesh_attributes/meshes/sphere_attribute.ply");
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->positions.size(), 1192u);
  EXPECT_EQ(m->triangle_count(), 528u);
  EXPECT_EQ(m->normals.size(), 1192u);
  EXPECT_EQ(m->uvs.size(), 1192u);
  ASSERT_EQ(m->attributes.size(), 3u);
  EXPECT_EQ(m->attributes[0].name, "vertex_color");
  EXPECT_EQ(m->attributes[0].dim, 3u);
  EXPECT_EQ(m->attributes[0].rows(), 1192u);
  EXPECT_EQ(m->attributes[1].name, "face_color");
  EXPECT_EQ(m->attributes[1].rows(), 528u);
  EXPECT_EQ(m->attributes[2].name, "face_weight");
  EXPECT_EQ(m->attributes[2].dim, 1u);
}

// The error of `bytes`, which must not load.
std::string ErrorOf(const std::string& bytes) {
  const StatusOr<MeshData> m = LoadPlyFromBytes(bytes, "bad.ply");
  EXPECT_FALSE(m.ok());
  return m.ok() ? "" : m.status().message();
}

const std::string kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyLoader, MalformedFilesGiveErrorsWithWhere) {
  EXPECT_NE(ErrorOf("").find("bad.ply:1:"), std::string::npos);
  EXPECT_NE(ErrorOf("plx\n").find("bad.ply:1: expected 'ply'"), std::string::npos);
  EXPECT_NE(ErrorOf("ply\nformat ascii 2.0\nend_header\n").find("bad.ply:2:"), std::string::npos);
  EXPECT_NE(ErrorOf("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty half y\n")
                .find("bad.ply:5: unknown type 'half'"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n").find("bad.ply:3:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ply\nformat ascii 1.0\nelement vertex 3\n").find("end_header"),
            std::string::npos);
  // Data: a bad number names its line, property and row.
  std::string e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(e.find("bad.ply:11:"), std::string::npos) << e;
  EXPECT_NE(e.find("property 'z' of vertex 1"), std::string::npos) << e;
  EXPECT_NE(e.find("'x'"), std::string::npos) << e;
  e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_NE(e.find("out of range; expected 0 to 2"), std::string::npos) << e;
  e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  EXPECT_NE(e.find("expected 3 or more"), std::string::npos) << e;
  e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n");
  EXPECT_NE(e.find("bad.ply:13:"), std::string::npos) << e;
  e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n7\n");
  EXPECT_NE(e.find("expected the end of the file"), std::string::npos) << e;
  e = ErrorOf(kAsciiHeader + "0 0 0\n1 0 0\n");
  EXPECT_NE(e.find("found the end of the file"), std::string::npos) << e;
  EXPECT_NE(ErrorOf(kAsciiHeader + "0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n").find("bad.ply:10:"),
            std::string::npos);
  // Normals that are zero, and only some of nx ny nz.
  e = ErrorOf(
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n");
  EXPECT_NE(e.find("vertex 1: normal is zero"), std::string::npos) << e;
  e = ErrorOf(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nelement face 0\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 1\n");
  EXPECT_NE(e.find("some of nx, ny, nz"), std::string::npos) << e;
  // No face element; no vertex element.
  EXPECT_NE(ErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n")
                .find("no element 'face'"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ply\nformat ascii 1.0\nend_header\n").find("no element 'vertex'"),
            std::string::npos);
}

TEST(PlyLoader, BinaryErrorsNameTheByteAndHugeCountsAreRefusedBeforeAllocation) {
  const MeshData grid = test_util::GridMesh(2);
  const std::string good = test_util::PlyBinaryBytes(grid, false);
  ASSERT_TRUE(LoadPlyFromBytes(good, "ok.ply").ok());
  // Truncated in the faces.
  std::string e = ErrorOf(good.substr(0, good.size() - 3));
  EXPECT_NE(e.find("bad.ply: byte "), std::string::npos) << e;
  EXPECT_NE(e.find("vertex index"), std::string::npos) << e;
  // A 100-byte file that claims 2^40 vertices is refused without allocating.
  const std::string huge =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0123456789";
  e = ErrorOf(huge);
  EXPECT_NE(e.find("vertices; expected at most 4294967295"), std::string::npos) << e;
  const std::string many =
      "ply\nformat binary_little_endian 1.0\nelement vertex 400000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0123456789";
  e = ErrorOf(many);
  EXPECT_NE(e.find("declares 400000000 rows"), std::string::npos) << e;
  EXPECT_NE(e.find("only 10 bytes are left"), std::string::npos) << e;
  // A face list count of 255 with a few bytes left.
  std::string list = good.substr(0, good.size() - 13 * 8);
  list += char(255);
  e = ErrorOf(list);
  EXPECT_FALSE(e.empty());
  // Trailing bytes after the last element.
  EXPECT_NE(ErrorOf(good + "x").find("expected the end of the file"), std::string::npos);
}

// The fuzz seeds are valid files (so that the fuzzer starts from meshes that load).
TEST(PlyLoader, FuzzSeedsLoad) {
  for (const char* name : {"grid_le.ply", "grid_be.ply", "quad_attributes_ascii.ply"}) {
    const StatusOr<MeshData> m =
        LoadPly(PTLAB_SOURCE_DIR "/tests/fuzz/seeds/ply/" + std::string(name));
    ASSERT_TRUE(m.ok()) << m.status().message();
    EXPECT_GE(m->triangle_count(), 2u) << name;
  }
}

TEST(PlyLoader, MissingFile) {
  const StatusOr<MeshData> m = LoadPly("/nonexistent/mesh.ply");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("/nonexistent/mesh.ply"), std::string::npos);
}

}  // namespace
}  // namespace ptlab
