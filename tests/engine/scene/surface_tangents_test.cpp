// normal: TriangleTangents (engine/scene/surface_tangents.h): the linear map uv → p of a
// triangle, and Mitsuba's fallback (finite, orthonormal) where the uv map is degenerate.
#include "engine/scene/surface_tangents.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/frame.h"
#include "engine/core/rng.h"

namespace ptlab {
namespace {

Vec3f RandomPoint(Pcg32& rng) {
  return {rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1};
}

bool Finite(const Vec3f& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

TEST(SurfaceTangents, MapTheUvTriangleOntoThePositions) {
  Pcg32 rng(7, 1);
  for (int k = 0; k < 1000; ++k) {
    const Vec3f p0 = RandomPoint(rng), p1 = RandomPoint(rng), p2 = RandomPoint(rng);
    const Vec2f uv0{rng.NextFloat(), rng.NextFloat()}, uv1{rng.NextFloat(), rng.NextFloat()},
        uv2{rng.NextFloat(), rng.NextFloat()};
    const float det = (uv1.x - uv0.x) * (uv2.y - uv0.y) - (uv1.y - uv0.y) * (uv2.x - uv0.x);
    if (std::fabs(det) < 0.05f) continue;  // conditioning of the check
    Vec3f du, dv;
    TriangleTangents(p0, p1, p2, uv0, uv1, uv2, {0, 0, 1}, &du, &dv);
    // p(uv) = p0 + du (u − u0) + dv (v − v0) reproduces p1 and p2.
    for (const auto& [p, uv] : {std::pair{p1, uv1}, std::pair{p2, uv2}}) {
      const Vec3f q = p0 + du * (uv.x - uv0.x) + dv * (uv.y - uv0.y);
      EXPECT_NEAR(q.x, p.x, 1e-3f);
      EXPECT_NEAR(q.y, p.y, 1e-3f);
      EXPECT_NEAR(q.z, p.z, 1e-3f);
    }
  }
}

// Zero uv area (all corners at one uv, a pole's fan where two corners share a uv, collinear
// uvs), and uvs so close that 1/det overflows: the Duff basis around ng, finite.
TEST(SurfaceTangents, DegenerateUvMapsFallBackToTheBasisAroundTheNormal) {
  const Vec3f p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0}, ng{0, 0, 1};
  const Frame basis(ng);
  const Vec2f a{0.5f, 0.0f}, b{0.25f, 0.0f}, c{0.75f, 0.0f};
  struct Case {
    Vec2f uv0, uv1, uv2;
  };
  const Case cases[] = {{a, a, a}, {a, b, c}, {a, a, {0.3f, 0.1f}}, {{0.5f, 1.0f}, {0.5f, 1.0f}, {0.6f, 0.9f}},
                        {{0, 0}, {1e-30f, 0}, {0, 1e-30f}}};
  for (const Case& k : cases) {
    Vec3f du, dv;
    TriangleTangents(p0, p1, p2, k.uv0, k.uv1, k.uv2, ng, &du, &dv);
    ASSERT_TRUE(Finite(du) && Finite(dv));
    EXPECT_TRUE(du == basis.s);
    EXPECT_TRUE(dv == basis.t);
  }
}

}  // namespace
}  // namespace ptlab
