// Mitsuba's surface coordinates of a rotated sphere (uv in the sphere's own frame, also through
// an instance) and of its cube (each face's uv orientation), as Mitsuba 3 lays them out.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/bvh/sphere_intersect.h"
#include "engine/io/mitsuba_loader.h"
#include "engine/io/mitsuba_meshes.h"
#include "engine/render/interaction.h"

namespace ptlab {
namespace {

StatusOr<Scene> Load(const std::string& body) {
  return LoadMitsubaSceneFromString(
      "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">"
      "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
      "</sensor>\n" + body + "\n</scene>\n",
      ".", "uv.xml");
}

// The uv where a ray from (0, 5, 0) along −y meets sphere row `row` (centre on the y axis).
Vec2f UvFromAbove(const Scene& s, uint32_t row) {
  const Ray ray{{s.spheres.center_x[row], s.spheres.center_y[row] + 5, s.spheres.center_z[row]},
                {0, -1, 0}};
  const Hit hit{5.0f - s.spheres.radius[row], 0, 0, kSphereHitBit | row};
  return MakeInteraction(s, ray, hit).uv;
}

TEST(MitsubaShapeUv, RotatedSphereTurnsItsUv) {
  // Mitsuba: uv from to_object · p. Turned 90° about z, the world +y pole direction is the
  // sphere's +x: φ = 0, θ = π/2.
  StatusOr<Scene> s = Load(
      "<shape type=\"sphere\"><bsdf type=\"diffuse\"/>"
      "<transform name=\"to_world\"><scale value=\"2\"/><rotate z=\"1\" angle=\"90\"/></transform>"
      "</shape>\n<shape type=\"sphere\"><bsdf type=\"diffuse\"/>"
      "<transform name=\"to_world\"><translate x=\"10\"/></transform></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->spheres.size(), 2u);
  const Vec2f turned = UvFromAbove(*s, 0);
  EXPECT_NEAR(turned.x, 0.0f, 1e-6f);
  EXPECT_NEAR(turned.y, 0.5f, 1e-6f);
  const Vec2f plain = UvFromAbove(*s, 1);  // unrotated: +y is φ = π/2
  EXPECT_NEAR(plain.x, 0.25f, 1e-6f);
  EXPECT_NEAR(plain.y, 0.5f, 1e-6f);
}

TEST(MitsubaShapeUv, InstancedSphereComposesGroupAndInstanceTurns) {
  // 90° in the group and 90° by the instance: +y in the world is the sphere's −y, φ = 3π/2.
  StatusOr<Scene> s = Load(
      "<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"><bsdf type=\"diffuse\"/>"
      "<transform name=\"to_world\">"
      "<rotate z=\"1\" angle=\"90\"/></transform></shape></shape>\n"
      "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
      "<rotate z=\"1\" angle=\"90\"/><scale value=\"3\"/></transform></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->spheres.size(), 1u);
  const Vec2f uv = UvFromAbove(*s, 0);
  EXPECT_NEAR(uv.x, 0.75f, 1e-6f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
}

TEST(MitsubaShapeUv, CubeFacesHaveMitsubasUvOrientation) {
  const MeshData cube = MakeMitsubaCube();
  ASSERT_EQ(cube.positions.size(), 24u);
  ASSERT_EQ(cube.indices.size(), 36u);
  const auto uv_at = [&](const Vec3f& n, const Vec3f& p) {
    for (size_t i = 0; i < cube.positions.size(); ++i)
      if (cube.normals[i].x == n.x && cube.normals[i].y == n.y && cube.normals[i].z == n.z &&
          cube.positions[i].x == p.x && cube.positions[i].y == p.y && cube.positions[i].z == p.z)
        return cube.uvs[i];
    ADD_FAILURE() << "no vertex";
    return Vec2f{-1, -1};
  };
  // Per face: the corners with uv (0, 0), (1, 0) and (0, 1) (Mitsuba 3's cube.cpp table).
  struct Expect {
    Vec3f n, c00, c10, c01;
  };
  const Expect faces[6] = {
      {{0, -1, 0}, {-1, -1, -1}, {-1, -1, 1}, {1, -1, -1}},
      {{0, 1, 0}, {1, 1, 1}, {-1, 1, 1}, {1, 1, -1}},
      {{1, 0, 0}, {1, -1, 1}, {1, 1, 1}, {1, -1, -1}},
      {{0, 0, 1}, {-1, -1, 1}, {-1, 1, 1}, {1, -1, 1}},
      {{-1, 0, 0}, {-1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}},
      {{0, 0, -1}, {-1, 1, -1}, {-1, -1, -1}, {1, 1, -1}},
  };
  for (const Expect& f : faces) {
    const Vec2f a = uv_at(f.n, f.c00), b = uv_at(f.n, f.c10), c = uv_at(f.n, f.c01);
    EXPECT_EQ(a.x, 0.0f);
    EXPECT_EQ(a.y, 0.0f);
    EXPECT_EQ(b.x, 1.0f);
    EXPECT_EQ(b.y, 0.0f);
    EXPECT_EQ(c.x, 0.0f);
    EXPECT_EQ(c.y, 1.0f);
  }
  // Every triangle faces out along its vertices' normal.
  for (size_t t = 0; t < cube.indices.size(); t += 3) {
    const Vec3f p0 = cube.positions[cube.indices[t]], p1 = cube.positions[cube.indices[t + 1]],
                p2 = cube.positions[cube.indices[t + 2]];
    EXPECT_GT(Dot(Cross(p1 - p0, p2 - p0), cube.normals[cube.indices[t]]), 0.0f) << t;
  }
}

}  // namespace
}  // namespace ptlab
