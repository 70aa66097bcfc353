// OffsetRayOrigin: rays leaving a surface from their own hit point do not hit it again.
#include "engine/bvh/ray_offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/bvh/bvh.h"
#include "engine/bvh/intersect1.h"
#include "engine/core/rng.h"
#include "tests/engine/bvh/test_meshes.h"

namespace ptlab {
namespace {

using bvh_test::Uniform;
using bvh_test::UniformSphereDirection;

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(BvhRayOffset, MovesAlongTheNormalByAFewUlps) {
  const Vec3f n = Normalize(Vec3f{1, -2, 0.5f});
  for (float mag : {1e-3f, 1.0f, 1e5f}) {
    const Vec3f p{mag, -0.7f * mag, 0.3f * mag};
    const Vec3f q = OffsetRayOrigin(p, n);
    const Vec3f delta = q - p;
    EXPECT_GT(Dot(delta, n), 0.0f) << mag;
    // Far from zero: at most 256 ULPs per coordinate, i.e. a relative move below 1e-4.
    if (mag >= 1.0f) {
      EXPECT_LT(Length(delta), 1e-4f * Length(p)) << mag;
    }
    const Vec3f back = OffsetRayOrigin(p, -n);
    EXPECT_LT(Dot(back - p, n), 0.0f) << mag;
  }
  // Near the origin a fixed float offset replaces ULP steps (which would be denormal).
  const Vec3f q = OffsetRayOrigin({0, 0, 0}, {0, 0, 1});
  EXPECT_EQ(q.x, 0.0f);
  EXPECT_EQ(q.y, 0.0f);
  EXPECT_EQ(q.z, 1.0f / 65536.0f);
}

// For surfaces placed at |p| from 1e-3 to 1e5 (tilted and axis-aligned), hit a quad of two
// coplanar triangles, rebuild the hit point from barycentrics, offset it to the side the new
// ray leaves on (reflection and transmission) and check that the quad is not hit again.
TEST(BvhRayOffset, NoSelfIntersectionAcrossMagnitudes) {
  Pcg32 rng(8, 8);
  int primary_hits = 0, rays = 0, self_hits = 0;
  for (float mag = 1e-3f; mag <= 1.5e5f; mag *= 10.0f) {
    for (int scene = 0; scene < 40; ++scene) {
      const Vec3f centre = UniformSphereDirection(rng) * mag;
      const float size = mag * std::pow(10.0f, Uniform(rng, -2.0f, 0.0f));
      Vec3f t1, t2;
      if (scene % 3 == 0) {
        // Axis-aligned plane through the centre.
        const int axis = scene % 9 / 3;
        t1[(axis + 1) % 3] = 1.0f;
        t2[(axis + 2) % 3] = 1.0f;
      } else {
        const Vec3f n = UniformSphereDirection(rng);
        t1 = Normalize(Cross(n, UniformSphereDirection(rng)));
        t2 = Cross(n, t1);
      }
      const Vec3f v0 = centre - t1 * size - t2 * size, v1 = centre + t1 * size - t2 * size;
      const Vec3f v2 = centre - t1 * size + t2 * size, v3 = centre + t1 * size + t2 * size;
      TriangleTable quad;
      quad.Append(v0, v1, v2);
      quad.Append(v1, v3, v2);
      const Bvh bvh = BuildBvh(quad);
      ASSERT_EQ(bvh.prim_id.size(), 2u);
      for (int i = 0; i < 500; ++i) {
        // Primary ray toward a random point of the quad.
        const Vec3f target = centre + t1 * (size * Uniform(rng, -0.99f, 0.99f)) +
                             t2 * (size * Uniform(rng, -0.99f, 0.99f));
        const Vec3f d = UniformSphereDirection(rng);
        const Ray primary{target - d * (size * Uniform(rng, 0.1f, 10.0f)), d, 0.0f, kInf};
        Hit hit;
        if (!Intersect1(bvh, primary, &hit)) continue;
        ++primary_hits;
        const Vec3f a = quad.V0(hit.prim), b = quad.V1(hit.prim), c = quad.V2(hit.prim);
        const Vec3f p = a * (1.0f - hit.b1 - hit.b2) + b * hit.b1 + c * hit.b2;
        const Vec3f ng = Normalize(Cross(b - a, c - a));
        const Vec3f toward_origin = Dot(ng, d) < 0.0f ? ng : -ng;
        for (const Vec3f& side : {toward_origin, -toward_origin}) {
          Vec3f w = UniformSphereDirection(rng);
          if (Dot(w, side) < 0.0f) w = -w;
          const Ray next{OffsetRayOrigin(p, side), w, 0.0f, kInf};
          ++rays;
          if (Occluded1(bvh, next) && ++self_hits <= 5) {
            ADD_FAILURE() << "self-hit at |p| ~ " << mag << " size " << size << " p=(" << p.x << ","
                          << p.y << "," << p.z << ") w.n=" << Dot(w, side);
          }
        }
      }
    }
  }
  EXPECT_EQ(self_hits, 0);
  EXPECT_GT(primary_hits, 8 * 40 * 500 / 2);
  EXPECT_EQ(rays, 2 * primary_hits);
}

}  // namespace
}  // namespace ptlab
