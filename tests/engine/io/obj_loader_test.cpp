// Tests of LoadObj: fan triangulation, vertex deduplication, and one test per malformed input.
#include "engine/io/obj_loader.h"
#include "tests/test_data.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace ptlab {
namespace {

std::string Fixture(const std::string& name) {
  return PTLAB_SOURCE_DIR "/tests/data/scene/meshes/" + name;
}

std::string NoriDir() { return test_data::Path("nori"); }

// The error names `file`, then `line` as "file:line:", and contains every word of `words`.
void ExpectObjError(const StatusOr<MeshData>& result, const std::string& file, int line,
                    const std::vector<std::string>& words) {
  ASSERT_FALSE(result.ok()) << "expected an error for " << file;
  const std::string& message = result.status().message();
  const std::string prefix = line > 0 ? file + ":" + std::to_string(line) + ": " : file + ":";
  EXPECT_EQ(message.rfind(prefix, 0), 0u)
      << "message does not start with '" << prefix << "': " << message;
  for (const std::string& w : words)
    EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' missing from: " << message;
}

std::vector<uint32_t> Indices(const MeshData& mesh) { return mesh.indices; }

TEST(ObjLoader, FanTriangulatesPolygonsInFileOrder) {
  const StatusOr<MeshData> mesh = LoadObj(Fixture("fan.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  // Pentagon 1..5 -> (1,2,3) (1,3,4) (1,4,5); then (5,4,1). Vertices numbered by first use.
  EXPECT_EQ(Indices(*mesh), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 0}));
  ASSERT_EQ(mesh->positions.size(), 5u);
  EXPECT_EQ(mesh->positions[3].y, 2.0f);
  EXPECT_EQ(mesh->positions[3].x, 0.5f);
  EXPECT_TRUE(mesh->normals.empty());
  EXPECT_TRUE(mesh->uvs.empty());
}

TEST(ObjLoader, DeduplicatesPositionUvNormalTriples) {
  const StatusOr<MeshData> mesh = LoadObj(Fixture("dedup.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  // (1/1/1) (2/2/1) (3/3/1) are new; (1/1/2) is new; (3/3/1) and (2/2/1) are reused.
  EXPECT_EQ(Indices(*mesh), (std::vector<uint32_t>{0, 1, 2, 3, 2, 1}));
  ASSERT_EQ(mesh->positions.size(), 4u);
  ASSERT_EQ(mesh->normals.size(), 4u);
  ASSERT_EQ(mesh->uvs.size(), 4u);
  EXPECT_EQ(mesh->positions[3].x, 0.0f);
  EXPECT_EQ(mesh->normals[0].z, 1.0f);
  EXPECT_EQ(mesh->normals[3].z, -1.0f);
  EXPECT_EQ(mesh->uvs[1].x, 1.0f);
  EXPECT_EQ(mesh->uvs[2].y, 1.0f);
}

TEST(ObjLoader, NegativeIndicesCrlfAndIgnoredStatements) {
  const StatusOr<MeshData> mesh = LoadObj(Fixture("quad_crlf.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(Indices(*mesh), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(mesh->positions[2].x, 1.0f);
  EXPECT_EQ(mesh->positions[2].y, 1.0f);
}

TEST(ObjLoader, ForwardReferencesResolveLikeNori) {
  const StatusOr<MeshData> mesh = LoadObj(Fixture("forward.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->triangle_count(), 1u);
  EXPECT_EQ(mesh->positions[1].x, 1.0f);
}

TEST(ObjLoader, NoriMeshes) {
  PTLAB_REQUIRE_DATA(NoriDir());
  const StatusOr<MeshData> bunny = LoadObj(NoriDir() + "/epfl/scenes/pa1/bunny.obj");
  ASSERT_TRUE(bunny.ok()) << bunny.status().message();
  EXPECT_EQ(bunny->triangle_count(), 2000u);
  EXPECT_EQ(bunny->normals.size(), bunny->positions.size());
  EXPECT_TRUE(bunny->uvs.empty());

  const StatusOr<MeshData> light = LoadObj(NoriDir() + "/epfl/scenes/pa4/cbox/meshes/light.obj");
  ASSERT_TRUE(light.ok()) << light.status().message();
  EXPECT_EQ(light->triangle_count(), 2u);
  EXPECT_EQ(light->positions.size(), 4u);
  EXPECT_EQ(light->uvs.size(), 4u);
  EXPECT_TRUE(light->normals.empty());

  // 35 quads and two convex 36-gons: 35·2 + 2·34 triangles.
  const StatusOr<MeshData> floor = LoadObj(NoriDir() + "/epfl/scenes/pa4/motto/meshes/floor.obj");
  ASSERT_TRUE(floor.ok()) << floor.status().message();
  EXPECT_EQ(floor->triangle_count(), 138u);
}

std::string BadInput(const std::string& name) { return PTLAB_SOURCE_DIR "/tests/data/bad/" + name; }

// Issue 12, finding 1: a lone '\r' ends a line for both the line checker and tinyobjloader
// (it used to crash the loader, which read past a buffer).
TEST(ObjLoader, ClassicMacLineEndsAreLines) {
  const StatusOr<MeshData> mesh = LoadObj(BadInput("quad_cr_only.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(Indices(*mesh), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(mesh->positions[2].y, 1.0f);
}

// The error of a CR-only file names the right line.
TEST(ObjLoader, ClassicMacLineEndsErrorLine) {
  const std::string path = BadInput("cr_only_bad_index.obj");
  ExpectObjError(LoadObj(path), path, 4, {"position", "7", "expected an index in 1..3"});
}

// Issue 12, finding 6: devices are refused before reading (the same check guards every input).
TEST(ObjLoader, DeviceInsteadOfFile) {
  ExpectObjError(LoadObj("/dev/zero"), "/dev/zero", 0, {"cannot read", "not a regular file"});
}

TEST(ObjLoader, MissingFile) {
  const std::string path = Fixture("does_not_exist.obj");
  ExpectObjError(LoadObj(path), path, 0, {"cannot read", "No such file"});
}

TEST(ObjLoader, DirectoryInsteadOfFile) {
  const std::string path = PTLAB_SOURCE_DIR "/tests/data/scene/meshes";
  ExpectObjError(LoadObj(path), path, 0, {"cannot read", "directory"});
}

TEST(ObjLoader, FaceRefersToMissingPosition) {
  const std::string path = Fixture("bad_position_index.obj");
  ExpectObjError(LoadObj(path), path, 6, {"position", "5", "expected an index in 1..4"});
}

TEST(ObjLoader, FaceRefersToMissingNormal) {
  const std::string path = Fixture("bad_normal_index.obj");
  ExpectObjError(LoadObj(path), path, 5, {"normal", "expected an index in 1..1"});
}

TEST(ObjLoader, FaceRefersToMissingUv) {
  const std::string path = Fixture("bad_uv_index.obj");
  ExpectObjError(LoadObj(path), path, 7, {"uv", "expected an index in 1..2"});
}

TEST(ObjLoader, NegativeIndexBeyondDefinedElements) {
  const std::string path = Fixture("bad_negative_index.obj");
  ExpectObjError(LoadObj(path), path, 4, {"position", "-4", "expected an index in -3..-1"});
}

TEST(ObjLoader, ZeroIndex) {
  const std::string path = Fixture("zero_index.obj");
  ExpectObjError(LoadObj(path), path, 4, {"malformed", "'0'", "expected a non-zero integer"});
}

TEST(ObjLoader, MalformedNumberInFile) {
  const std::string path = Fixture("bad_number.obj");
  ExpectObjError(LoadObj(path), path, 3, {"malformed number '1.2.3'", "expected"});
}

TEST(ObjLoader, MalformedNumbers) {
  for (const char* bad :
       {"1.2.3", "abc", "nan", "inf", "-inf", "1x", "1e", "0x10", "1e999", "+-1", "--1", "1,5"}) {
    const std::string text = std::string("v 0 0 0\nv 1 0 0\nv 0 ") + bad + " 0\nf 1 2 3\n";
    ExpectObjError(LoadObjFromString(text, "mem.obj"), "mem.obj", 3,
                   {"malformed number '" + std::string(bad) + "'"});
  }
  for (const char* bad : {"1.5", "x", "1e2", "+"}) {
    const std::string text = std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 ") + bad + "\n";
    ExpectObjError(LoadObjFromString(text, "mem.obj"), "mem.obj", 4,
                   {"malformed position ('v') index '" + std::string(bad) + "'"});
  }
  // Accepted spellings.
  const StatusOr<MeshData> ok =
      LoadObjFromString("v +1 -.5 2.\nv 1e2 0.25E-1 0\nv 0 1 0\nf +1 2 3\n", "mem.obj");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_EQ(ok->positions[0].y, -0.5f);
  EXPECT_EQ(ok->positions[1].x, 100.0f);
  EXPECT_EQ(ok->positions[1].y, 0.025f);
}

TEST(ObjLoader, WrongCoordinateCount) {
  const std::string path = Fixture("short_vertex.obj");
  ExpectObjError(LoadObj(path), path, 1, {"expected v x y z", "found 2"});
  ExpectObjError(LoadObjFromString("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1 2 3\n", "m.obj"),
                 "m.obj", 4, {"expected vn x y z", "found 2"});
  ExpectObjError(LoadObjFromString("v 0 0 0\nvt 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj"), "m.obj",
                 2, {"expected vt u v", "found 1"});
  ExpectObjError(LoadObjFromString("v 0 0 0 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj"), "m.obj", 1,
                 {"expected", "found 5"});
}

TEST(ObjLoader, FaceWithTooFewVertices) {
  const std::string path = Fixture("short_face.obj");
  ExpectObjError(LoadObj(path), path, 4, {"at least 3 vertices", "found 2"});
}

TEST(ObjLoader, MalformedFaceVertex) {
  for (const char* bad : {"1/", "1/1/", "1/1/1/1", "/1", "1//"}) {
    const std::string text =
        std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1 2 ") + bad + "\n";
    ExpectObjError(LoadObjFromString(text, "mem.obj"), "mem.obj", 6, {"malformed"});
  }
}

TEST(ObjLoader, MixedFaceVertexFormats) {
  const std::string path = Fixture("mixed_format.obj");
  ExpectObjError(LoadObj(path), path, 7, {"written p", "expected p//n", "line 6"});
}

TEST(ObjLoader, ZeroNormal) {
  const std::string path = Fixture("zero_normal.obj");
  ExpectObjError(LoadObj(path), path, 4, {"expected a non-zero normal"});
}

TEST(ObjLoader, UnknownStatement) {
  const std::string path = Fixture("unknown_statement.obj");
  ExpectObjError(LoadObj(path), path, 4, {"unknown OBJ statement 'vp'", "expected v, vn, vt, f"});
}

TEST(ObjLoader, NoFaces) {
  const std::string path = Fixture("no_faces.obj");
  ExpectObjError(LoadObj(path), path, 4, {"without a face", "expected at least one 'f' line"});
}

TEST(ObjLoader, EmptyFile) {
  const std::string path = Fixture("empty.obj");
  ExpectObjError(LoadObj(path), path, 1, {"expected at least one 'f' line"});
}

}  // namespace
}  // namespace ptlab
