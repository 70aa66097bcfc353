// Tests of the procedural shapes: counts, orientation, watertightness, area.
#include "engine/io/shapes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace ptlab {
namespace {

using Key = std::array<float, 3>;
Key KeyOf(const Vec3f& p) { return {p.x, p.y, p.z}; }

// Every undirected edge, compared by exact position, is shared by exactly two triangles.
bool IsWatertight(const MeshData& mesh) {
  std::map<std::pair<Key, Key>, int> edges;
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      Key a = KeyOf(mesh.positions[mesh.indices[3 * t + e]]);
      Key b = KeyOf(mesh.positions[mesh.indices[3 * t + (e + 1) % 3]]);
      if (b < a) std::swap(a, b);
      ++edges[{a, b}];
    }
  for (const auto& [edge, count] : edges)
    if (count != 2) return false;
  return true;
}

Vec3f GeometricNormal(const MeshData& mesh, size_t t, double* area) {
  const Vec3f a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
              c = mesh.positions[mesh.indices[3 * t + 2]];
  const Vec3f n = Cross(b - a, c - a);
  *area = 0.5 * double(Length(n));
  return n;
}

Vec3f Centroid(const MeshData& mesh, size_t t) {
  return (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
          mesh.positions[mesh.indices[3 * t + 2]]) /
         3.0f;
}

void ExpectValidAttributes(const MeshData& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  for (const Vec3f& n : mesh.normals) EXPECT_NEAR(Length(n), 1.0f, 1e-6f);
  for (const uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
}

TEST(SceneLoaderShapes, SphereIsAWatertightOutwardUvSphere) {
  const Vec3f center{1, -2, 3};
  const float radius = 2.5f;
  const MeshData mesh = MakeSphere(center, radius);
  ExpectValidAttributes(mesh);
  EXPECT_EQ(mesh.triangle_count(), size_t(2 * kSphereSegments * (kSphereRings - 1)));
  EXPECT_EQ(mesh.triangle_count(), 3968u);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f d = mesh.positions[i] - center;
    EXPECT_NEAR(Length(d), radius, 1e-5f);
    EXPECT_GT(Dot(d, mesh.normals[i]), 0.9999f * radius);
  }
  double total = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    double area = 0;
    const Vec3f n = GeometricNormal(mesh, t, &area);
    ASSERT_GT(area, 0.0) << "degenerate triangle " << t;
    EXPECT_GT(Dot(n, Centroid(mesh, t) - center), 0.0f) << "inward triangle " << t;
    total += area;
  }
  const double sphere = 4 * 3.14159265358979 * radius * radius;
  EXPECT_LT(total, sphere);
  EXPECT_GT(total, 0.995 * sphere);
  EXPECT_TRUE(IsWatertight(mesh));
}

TEST(SceneLoaderShapes, RectangleFacesPlusZ) {
  const MeshData mesh = MakeRectangle();
  ExpectValidAttributes(mesh);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  double total = 0;
  for (size_t t = 0; t < 2; ++t) {
    double area = 0;
    const Vec3f n = GeometricNormal(mesh, t, &area);
    EXPECT_GT(n.z, 0.0f);
    EXPECT_EQ(n.x, 0.0f);
    EXPECT_EQ(n.y, 0.0f);
    total += area;
  }
  EXPECT_DOUBLE_EQ(total, 4.0);
  for (const Vec3f& n : mesh.normals) EXPECT_EQ(n.z, 1.0f);
  for (const Vec3f& p : mesh.positions) EXPECT_EQ(p.z, 0.0f);
}

TEST(SceneLoaderShapes, CubeIsClosedWithOutwardFlatNormals) {
  const MeshData mesh = MakeCube();
  ExpectValidAttributes(mesh);
  ASSERT_EQ(mesh.triangle_count(), 12u);
  double total = 0;
  for (size_t t = 0; t < 12; ++t) {
    double area = 0;
    const Vec3f n = GeometricNormal(mesh, t, &area);
    const Vec3f c = Centroid(mesh, t);
    EXPECT_GT(Dot(n, c), 0.0f);
    // Flat: the vertex normals equal the face normal.
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.normals[mesh.indices[3 * t + k]], n / Length(n));
    total += area;
  }
  EXPECT_DOUBLE_EQ(total, 24.0);
  for (const Vec3f& p : mesh.positions) EXPECT_EQ(MaxComponent(Abs(p)), 1.0f);
  EXPECT_TRUE(IsWatertight(mesh));
}

TEST(SceneLoaderShapes, DiskIsAnInscribedPolygonFacingPlusZ) {
  const MeshData mesh = MakeDisk();
  ExpectValidAttributes(mesh);
  ASSERT_EQ(mesh.triangle_count(), size_t(kDiskSegments));
  double total = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    double area = 0;
    EXPECT_GT(GeometricNormal(mesh, t, &area).z, 0.0f);
    total += area;
  }
  EXPECT_NEAR(total, 0.5 * kDiskSegments * std::sin(2 * 3.14159265358979 / kDiskSegments), 1e-5);
  for (const Vec3f& p : mesh.positions) EXPECT_LE(Length(p), 1.0f + 1e-6f);
}

}  // namespace
}  // namespace ptlab
