// Mitsuba's sdfgrid in the loader: the .vol reader (header checks), the SdfGridTable rows a
// <shape type="sdfgrid"> and an instanced one make, and the errors of what is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/bvh/sdf_grid_intersect.h"
#include "engine/io/mitsuba_loader.h"
#include "engine/io/vol_grid.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

std::string VolBytes(int version, int encoding, int nx, int ny, int nz, int channels,
                     const std::vector<float>& values) {
  std::string b = "VOL";
  b.push_back(char(version));
  for (int v : {encoding, nx, ny, nz, channels}) b.append(reinterpret_cast<const char*>(&v), 4);
  const float box[6] = {0, 0, 0, 1, 1, 1};
  b.append(reinterpret_cast<const char*>(box), sizeof(box));
  b.append(reinterpret_cast<const char*>(values.data()), values.size() * 4);
  return b;
}

// A 2 x 3 x 2 grid: f = x − 0.5 over the box (values in x-fastest order).
std::vector<float> PlaneValues() {
  std::vector<float> v;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) v.push_back(i == 0 ? -0.5f : 0.5f + 0.1f * j + 0.01f * k);
  return v;
}

TEST(VolGrid, ParsesHeaderAndValues) {
  StatusOr<VolGrid> g = ParseVolGrid(VolBytes(3, 1, 2, 3, 2, 1, PlaneValues()), "a.vol");
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ(g->nx, 2u);
  EXPECT_EQ(g->ny, 3u);
  EXPECT_EQ(g->nz, 2u);
  EXPECT_EQ(g->channels, 1u);
  ASSERT_EQ(g->values.size(), 12u);
  EXPECT_EQ(g->values[1 + 2 * (2 + 3 * 1)], 0.5f + 0.2f + 0.01f);  // (i, j, k) = (1, 2, 1)
}

TEST(VolGrid, RejectsBadFiles) {
  const auto message = [](const std::string& bytes) {
    StatusOr<VolGrid> g = ParseVolGrid(bytes, "b.vol");
    EXPECT_FALSE(g.ok());
    return g.ok() ? std::string() : g.status().message();
  };
  EXPECT_NE(message("VOX").find("b.vol: not a Mitsuba volume file"), std::string::npos);
  EXPECT_NE(message(VolBytes(2, 1, 2, 3, 2, 1, PlaneValues())).find("version 2; expected 3"),
            std::string::npos);
  EXPECT_NE(message(VolBytes(3, 2, 2, 3, 2, 1, PlaneValues())).find("encoding 2; expected 1"),
            std::string::npos);
  EXPECT_NE(message(VolBytes(3, 1, 2, 3, 3, 1, PlaneValues())).find("data bytes"),
            std::string::npos);
  EXPECT_NE(message(VolBytes(3, 1, 0, 3, 2, 1, {})).find("expected each in [1, 4096]"),
            std::string::npos);
  std::vector<float> nan = PlaneValues();
  nan[5] = std::nanf("");
  EXPECT_NE(message(VolBytes(3, 1, 2, 3, 2, 1, nan)).find("value 5 is not finite"),
            std::string::npos);
}

class MitsubaSdfGrid : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ptlab_sdfgrid_" + std::string(::testing::UnitTest::GetInstance()
                                               ->current_test_info()
                                               ->name()));
    fs::create_directories(dir_);
    Write("plane.vol", VolBytes(3, 1, 2, 3, 2, 1, PlaneValues()));
    Write("rgb.vol", VolBytes(3, 1, 2, 2, 2, 3, std::vector<float>(24, 1.0f)));
    Write("positive.vol", VolBytes(3, 1, 2, 2, 2, 1, std::vector<float>(8, 1.0f)));
  }
  void TearDown() override { fs::remove_all(dir_); }
  void Write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
  }
  StatusOr<Scene> Load(const std::string& body) {
    return LoadMitsubaSceneFromString(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">"
        "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
        "</sensor>\n" + body + "\n</scene>\n",
        dir_.string(), "sdf.xml");
  }
  std::string Error(const std::string& body) {
    StatusOr<Scene> s = Load(body);
    EXPECT_FALSE(s.ok());
    return s.ok() ? "" : s.status().message();
  }
  fs::path dir_;
};

TEST_F(MitsubaSdfGrid, TopLevelAndInstancedRows) {
  StatusOr<Scene> s = Load(
      "<shape type=\"sdfgrid\"><string name=\"filename\" value=\"plane.vol\"/>"
      "<string name=\"normals\" value=\"analytic\"/>"
      "<transform name=\"to_world\"><scale value=\"2\"/></transform></shape>\n"
      "<shape type=\"shapegroup\" id=\"g\"><shape type=\"sdfgrid\">"
      "<string name=\"filename\" value=\"plane.vol\"/></shape></shape>\n"
      "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
      "<translate x=\"5\"/></transform></shape>\n"
      "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
      "<translate x=\"-5\"/></transform></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const SdfGridTable& g = s->sdf_grids;
  ASSERT_EQ(g.size(), 3u);  // the top-level grid, then one per instance (none for the group)
  EXPECT_EQ(g.normals[0], SdfNormals::kAnalytic);
  EXPECT_EQ(g.normals[1], SdfNormals::kSmooth);  // Mitsuba's default
  EXPECT_EQ(g.nx[1], 2u);
  EXPECT_EQ(g.ny[1], 3u);
  EXPECT_EQ(g.values.size(), 36u);
  EXPECT_FLOAT_EQ(g.to_world[0].ApplyPoint({1, 1, 1}).x, 2.0f);
  EXPECT_FLOAT_EQ(g.to_world[1].ApplyPoint({0, 0, 0}).x, 5.0f);
  EXPECT_FLOAT_EQ(g.to_world[2].ApplyPoint({0, 0, 0}).x, -5.0f);
  // The second instance's surface at y = z = 0.5 (j = 1, k = ½): f = −0.5 + 1.105 x, zero at
  // x = 0.5 / 1.105, world x = −5 + that.
  float t = 0;
  ASSERT_TRUE(IntersectSdfGrid1(g, 2, {{-10, 0.5f, 0.5f}, {1, 0, 0}}, 1e30f, &t));
  EXPECT_NEAR(t, 5.0 + 0.5 / 1.105, 1e-5);
}

TEST_F(MitsubaSdfGrid, Errors) {
  EXPECT_NE(Error("<shape type=\"sdfgrid\"><string name=\"filename\" value=\"plane.vol\"/>"
                  "<string name=\"normals\" value=\"flat\"/></shape>")
                .find("expected \"analytic\" or \"smooth\""),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"sdfgrid\"><string name=\"filename\" value=\"rgb.vol\"/></shape>")
                .find("3 channels; expected 1"),
            std::string::npos);
  EXPECT_NE(
      Error("<shape type=\"sdfgrid\"><string name=\"filename\" value=\"positive.vol\"/></shape>")
          .find("never change sign"),
      std::string::npos);
  EXPECT_NE(Error("<shape type=\"sdfgrid\"><string name=\"filename\" value=\"none.vol\"/></shape>")
                .find("none.vol"),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"sdfgrid\"/>").find("filename"), std::string::npos);
  EXPECT_NE(Error("<shape type=\"sdfgrid\"><string name=\"filename\" value=\"plane.vol\"/>"
                  "<emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>")
                .find("unsupported"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
