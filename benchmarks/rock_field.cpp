// The benchmarks' rock field: small displaced spheres scattered over a ground quad.
#include "benchmarks/rock_field.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/core/rng.h"
#include "engine/core/transform.h"

namespace ptlab {
namespace {

constexpr int kSlices = 12;
constexpr int kRings = 8;  // rings of vertices, the two poles included
// Two caps of kSlices triangles, and two triangles a slice in each band between rings.
static_assert(kRockTriangles == 2 * kSlices + 2 * kSlices * (kRings - 3));

// The rock's vertices on the unit sphere, displaced radially: the poles, then ring by ring.
std::vector<Vec3f> RockVertices(Pcg32& rng) {
  std::vector<Vec3f> v;
  v.push_back({0, 0, 1 + 0.3f * (2 * rng.NextFloat() - 1)});
  for (int r = 1; r < kRings - 1; ++r) {
    const float theta = std::numbers::pi_v<float> * float(r) / float(kRings - 1);
    for (int s = 0; s < kSlices; ++s) {
      const float phi = 2 * std::numbers::pi_v<float> * float(s) / float(kSlices);
      const float k = 1 + 0.3f * (2 * rng.NextFloat() - 1);
      v.push_back({k * std::sin(theta) * std::cos(phi), k * std::sin(theta) * std::sin(phi),
                   k * std::cos(theta)});
    }
  }
  v.push_back({0, 0, -(1 + 0.3f * (2 * rng.NextFloat() - 1))});
  return v;
}

}  // namespace

TriangleTable MakeRockField(uint32_t rocks) {
  TriangleTable t;
  const float g = 1.2f, z0 = -0.2f;
  t.Append({-g, -g, z0}, {g, -g, z0}, {g, g, z0});
  t.Append({-g, -g, z0}, {g, g, z0}, {-g, g, z0});
  Pcg32 rng(20261208, 11);
  const uint32_t south = 1 + kSlices * (kRings - 2);
  const auto ring = [](int r, int s) { return uint32_t(1 + (r - 1) * kSlices + s % kSlices); };
  for (uint32_t i = 0; i < rocks; ++i) {
    const Vec3f centre{2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1,
                       -0.2f + 0.7f * rng.NextFloat()};
    const float radius = 0.01f + 0.03f * rng.NextFloat();
    const Vec3f stretch{0.6f + 0.8f * rng.NextFloat(), 0.6f + 0.8f * rng.NextFloat(),
                        0.6f + 0.8f * rng.NextFloat()};
    const Vec3f axis = Normalize(
        Vec3f{2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 0.9f});
    const Transform to_world = Transform::Translate(centre) *
                               Transform::Rotate(axis, 360 * rng.NextFloat()) *
                               Transform::Scale(stretch * radius);
    std::vector<Vec3f> v = RockVertices(rng);
    for (Vec3f& p : v) p = to_world.ApplyPoint(p);
    for (int s = 0; s < kSlices; ++s) {  // the caps, then the bands between rings
      t.Append(v[0], v[ring(1, s)], v[ring(1, s + 1)]);
      t.Append(v[south], v[ring(kRings - 2, s + 1)], v[ring(kRings - 2, s)]);
    }
    for (int r = 1; r < kRings - 2; ++r) {
      for (int s = 0; s < kSlices; ++s) {
        t.Append(v[ring(r, s)], v[ring(r + 1, s)], v[ring(r + 1, s + 1)]);
        t.Append(v[ring(r, s)], v[ring(r + 1, s + 1)], v[ring(r, s + 1)]);
      }
    }
  }
  return t;
}

}  // namespace ptlab
