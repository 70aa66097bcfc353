// Tests of LoadSerialized: Mitsuba's rectangle against the OBJ, versions 3 and 4, float and
// double, several shapes, and malformed files (errors with byte offsets, counts checked).
#include "engine/io/serialized_loader.h"

#include <gtest/gtest.h>

#include "tests/test_data.h"

#include <string>

#include "engine/io/obj_loader.h"
#include "tests/engine/io/mesh_file_writers.h"

namespace ptlab {
namespace {

const std::string kMitsubaData = ptlab::test_data::Path("mitsuba3");

void ExpectSameMesh(const MeshData& a, const MeshData& b) {
  ASSERT_EQ(a.indices, b.indices);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.normals.size(), b.normals.size());
  ASSERT_EQ(a.uvs.size(), b.uvs.size());
  for (size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_NEAR(a.positions[i].x, b.positions[i].x, 1e-6) << i;
    EXPECT_NEAR(a.positions[i].y, b.positions[i].y, 1e-6) << i;
    EXPECT_NEAR(a.positions[i].z, b.positions[i].z, 1e-6) << i;
  }
  for (size_t i = 0; i < a.normals.size(); ++i) {
    EXPECT_NEAR(a.normals[i].x, b.normals[i].x, 1e-6) << i;
    EXPECT_NEAR(a.normals[i].y, b.normals[i].y, 1e-6) << i;
    EXPECT_NEAR(a.normals[i].z, b.normals[i].z, 1e-6) << i;
  }
  for (size_t i = 0; i < a.uvs.size(); ++i) {
    EXPECT_NEAR(a.uvs[i].x, b.uvs[i].x, 1e-6) << i;
    EXPECT_NEAR(a.uvs[i].y, b.uvs[i].y, 1e-6) << i;
  }
}

TEST(SerializedLoader, MitsubaRectangleMatchesTheObj) {
  const StatusOr<MeshData> obj = LoadObj(kMitsubaData + "/tests/obj/rectangle_normals_uv.obj");
  ASSERT_TRUE(obj.ok()) << obj.status().message();
  const StatusOr<MeshData> m =
      LoadSerialized(kMitsubaData + "/tests/serialized/rectangle_normals_uv.serialized", 0);
  ASSERT_TRUE(m.ok()) << m.status().message();
  ExpectSameMesh(*m, *obj);
}

TEST(SerializedLoader, VersionsPrecisionsAndShapeIndices) {
  const MeshData a = test_util::GridMesh(3), b = test_util::GridMesh(5);
  for (int version : {3, 4}) {
    for (bool doubles : {false, true}) {
      const std::string bytes = test_util::SerializedBytes({a, b}, version, doubles, 0x0008);
      for (uint32_t index : {0u, 1u}) {
        const StatusOr<MeshData> m = LoadSerializedFromBytes(bytes, index, "m.serialized");
        ASSERT_TRUE(m.ok()) << m.status().message();
        ExpectSameMesh(*m, index == 0 ? a : b);
      }
      const StatusOr<MeshData> m = LoadSerializedFromBytes(bytes, 2, "m.serialized");
      ASSERT_FALSE(m.ok());
      EXPECT_NE(m.status().message().find("shape_index 2 out of range"), std::string::npos)
          << m.status().message();
    }
  }
  // Flag 0x0010 (face normals) drops the vertex normals.
  const StatusOr<MeshData> flat =
      LoadSerializedFromBytes(test_util::SerializedBytes({a}, 4, false, 0x0010), 0, "f");
  ASSERT_TRUE(flat.ok());
  EXPECT_TRUE(flat->normals.empty());
  EXPECT_EQ(flat->uvs.size(), a.uvs.size());
}

// The fuzz seeds are valid files (so that the fuzzer starts from meshes that load).
TEST(SerializedLoader, FuzzSeedsLoad) {
  const std::string dir = PTLAB_SOURCE_DIR "/tests/fuzz/seeds/serialized/";
  for (const auto& [name, shapes] :
       {std::pair{"two_v4.serialized", 2u}, std::pair{"one_v3_double.serialized", 1u}}) {
    for (uint32_t i = 0; i < shapes; ++i) {
      const StatusOr<MeshData> m = LoadSerialized(dir + name, i);
      ASSERT_TRUE(m.ok()) << m.status().message();
      EXPECT_GE(m->triangle_count(), 2u) << name;
    }
  }
}

std::string ErrorOf(const std::string& bytes, uint32_t index = 0) {
  const StatusOr<MeshData> m = LoadSerializedFromBytes(bytes, index, "bad.serialized");
  EXPECT_FALSE(m.ok());
  return m.ok() ? "" : m.status().message();
}

TEST(SerializedLoader, MalformedFiles) {
  const MeshData a = test_util::GridMesh(2);
  const std::string good = test_util::SerializedBytes({a}, 4, false);
  EXPECT_NE(ErrorOf("").find("bad.serialized: byte 0"), std::string::npos);
  EXPECT_NE(ErrorOf(std::string("\x1d\x04\x04\x00rest", 8)).find("0x041D"), std::string::npos);
  std::string v5 = good;
  v5[2] = 5;
  EXPECT_NE(ErrorOf(v5).find("format version 5; expected 3 or 4"), std::string::npos);
  // Truncated compressed stream.
  std::string e = ErrorOf(good.substr(0, 40));
  EXPECT_NE(e.find("the compressed stream ends inside"), std::string::npos) << e;
  EXPECT_NE(e.find("file byte"), std::string::npos) << e;
  // Corrupt compressed data.
  std::string corrupt = good;
  for (size_t i = 10; i < 30; ++i) corrupt[i] = char(0xA5);
  EXPECT_NE(ErrorOf(corrupt).find("bad.serialized: shape 0"), std::string::npos);
  // A tiny file that claims 3 billion vertices: refused before allocation.
  std::string raw;
  test_util::AppendValue(&raw, uint32_t(0x0003));
  raw += std::string("x") + '\0';
  test_util::AppendValue(&raw, uint64_t(3000000000));
  test_util::AppendValue(&raw, uint64_t(1000000000));
  uLongf size = compressBound(uLong(raw.size()));
  std::string packed(size, '\0');
  compress2(reinterpret_cast<Bytef*>(packed.data()), &size,
            reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 6);
  packed.resize(size);
  const std::string tiny = std::string("\x1c\x04\x04\x00", 4) + packed;
  e = ErrorOf(tiny);
  EXPECT_NE(e.find("compressed bytes left can hold"), std::string::npos) << e;
  // An index out of range.
  MeshData bad = a;
  bad.indices[4] = 99;
  e = ErrorOf(test_util::SerializedBytes({bad}, 4, false));
  EXPECT_NE(e.find("triangle 1: vertex index 99 out of range; expected 0 to 8"), std::string::npos)
      << e;
  // A dictionary pointing outside the file.
  std::string dict = test_util::SerializedBytes({a, a}, 4, false);
  dict[dict.size() - 12] = char(0x7f);
  e = ErrorOf(dict, 1);
  EXPECT_FALSE(e.empty());
}

}  // namespace
}  // namespace ptlab
