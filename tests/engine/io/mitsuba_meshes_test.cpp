// Mitsuba's disk and cylinder meshes: positions, winding, normals and Mitsuba's uvs, checked
// against the circle and the (r, φ/2π) and (φ/2π, z) parameterisations computed here.
#include "engine/io/mitsuba_meshes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <string>

#include "engine/io/mitsuba_loader.h"
#include "engine/io/shapes.h"

namespace ptlab {
namespace {

constexpr double kTwoPiD = 6.283185307179586476925;

double Angle01(double x, double y) {
  double phi = std::atan2(y, x) / kTwoPiD;
  return phi < 0 ? phi + 1 : phi;
}

// The disk's triangles are MakeDisk's, bit for bit (so untextured scenes render as before);
// its uvs at each triangle's centroid are Mitsuba's (r, φ/2π) within the tessellation's error.
TEST(MitsubaMeshes, DiskKeepsItsTrianglesAndHasPolarUvs) {
  for (const int n : {3, 16, 1024}) {
    const MeshData a = MakeDisk(n), b = MakeMitsubaDisk(n);
    ASSERT_EQ(a.triangle_count(), b.triangle_count());
    for (size_t k = 0; k < a.indices.size(); ++k) {
      const Vec3f pa = a.positions[a.indices[k]], pb = b.positions[b.indices[k]];
      ASSERT_EQ(std::bit_cast<uint32_t>(pa.x), std::bit_cast<uint32_t>(pb.x)) << n << " " << k;
      ASSERT_EQ(std::bit_cast<uint32_t>(pa.y), std::bit_cast<uint32_t>(pb.y)) << n << " " << k;
      ASSERT_EQ(pb.z, 0.0f);
    }
    ASSERT_EQ(b.uvs.size(), b.positions.size());
    for (size_t t = 0; t < b.triangle_count(); ++t) {
      Vec3f c{0, 0, 0};
      Vec2f uv{0, 0};
      for (int k = 0; k < 3; ++k) {
        c = c + b.positions[b.indices[3 * t + k]] * (1.0f / 3);
        uv = {uv.x + b.uvs[b.indices[3 * t + k]].x / 3, uv.y + b.uvs[b.indices[3 * t + k]].y / 3};
      }
      const double r = std::hypot(double(c.x), double(c.y));
      // The centroid lies at 2/3 of the way to the chord: r within the chord's sag of 2/3.
      EXPECT_NEAR(uv.x, r, 1.0 - std::cos(kTwoPiD / (2 * n)) + 1e-6) << n << " " << t;
      EXPECT_NEAR(uv.y, Angle01(c.x, c.y), 1e-5) << n << " " << t;
    }
  }
}

TEST(MitsubaMeshes, CylinderIsOpenOutwardAndHasMitsubasUvs) {
  const int n = 64;
  const MeshData m = MakeMitsubaCylinder(n);
  ASSERT_EQ(m.triangle_count(), size_t(2 * n));
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  double area = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3f p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]],
                p2 = m.positions[m.indices[3 * t + 2]];
    const Vec3f face = Cross(p1 - p0, p2 - p0);
    area += 0.5 * double(Length(face));
    const Vec3f c = (p0 + p1 + p2) * (1.0f / 3);
    // Outward: the face normal points away from the axis, and is horizontal.
    EXPECT_GT(face.x * c.x + face.y * c.y, 0.0f) << t;
    EXPECT_NEAR(face.z, 0.0f, 1e-6f) << t;
    Vec2f uv{0, 0};
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.indices[3 * t + k];
      uv = {uv.x + m.uvs[v].x / 3, uv.y + m.uvs[v].y / 3};
      // Every vertex on the unit circle at z = 0 or 1, its normal radial.
      const Vec3f p = m.positions[v];
      EXPECT_NEAR(std::hypot(p.x, p.y), 1.0f, 1e-6f);
      EXPECT_TRUE(p.z == 0.0f || p.z == 1.0f);
      EXPECT_NEAR(m.normals[v].x, p.x, 1e-7f);
      EXPECT_NEAR(m.normals[v].y, p.y, 1e-7f);
      EXPECT_EQ(m.normals[v].z, 0.0f);
    }
    EXPECT_NEAR(uv.x, Angle01(c.x, c.y), 1e-5) << t;
    EXPECT_NEAR(uv.y, c.z, 1e-6) << t;
  }
  const double x = kTwoPiD / (2 * n);
  EXPECT_NEAR(area, kTwoPiD * std::sin(x) / x, 1e-5);
}

// The loader's cylinder: radius, p0 and p1 (then to_world) place it; flip_normals turns it.
TEST(MitsubaMeshes, LoaderPlacesTheCylinderAlongP0P1) {
  const std::string xml =
      "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">"
      "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
      "</sensor><shape type=\"cylinder\"><float name=\"radius\" value=\"0.5\"/>"
      "<point name=\"p0\" x=\"1\" y=\"1\" z=\"1\"/><point name=\"p1\" x=\"3\" y=\"1\" z=\"1\"/>"
      "<transform name=\"to_world\"><translate z=\"2\"/></transform></shape></scene>";
  StatusOr<Scene> s = LoadMitsubaSceneFromString(xml, ".", "cyl.xml");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const TriangleTable& tri = s->triangles;
  ASSERT_EQ(tri.size(), 2048u);
  for (uint32_t t = 0; t < tri.size(); t += 97) {
    for (const Vec3f v : {tri.V0(t), tri.V1(t), tri.V2(t)}) {
      // Axis from (1, 1, 3) to (3, 1, 3).
      EXPECT_NEAR(std::hypot(v.y - 1.0f, v.z - 3.0f), 0.5f, 1e-5f);
      EXPECT_TRUE(std::fabs(v.x - 1.0f) < 1e-5f || std::fabs(v.x - 3.0f) < 1e-5f) << v.x;
    }
  }
  const std::string bad =
      "<scene version=\"3.0.0\"><sensor type=\"perspective\"/><shape type=\"cylinder\">"
      "<point name=\"p1\" x=\"0\" y=\"0\" z=\"0\"/></shape></scene>";
  StatusOr<Scene> b = LoadMitsubaSceneFromString(bad, ".", "cyl.xml");
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("the cylinder's axis p1 - p0 must have a length"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
