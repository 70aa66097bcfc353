// simd::SpawnRayBatch against its oracle ptlab::SpawnRayBatch (SpawnRayAt per row): every packet
// bit-identical on every compiled target, for random rows and the hard cases (points at and
// around zero, on both sides of OffsetRayOrigin's 1/32 switch, tiny, huge and negative; normals
// along the axes, with -0 components and n = -z; grazing and axis-aligned directions; batch
// tails), the lanes after the last row zero, and no NaN or Inf out but t_max's +inf. Plus the
// oracle against the scalar path's own construction (Frame::ToWorld, SpawnOrigin).
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/dispatched_target.h"
#include "simd/wavefront/spawn8.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/rng.h"
#include "engine/render/integrator_common.h"
#include "engine/wavefront/spawn.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

/// Shading points as the interaction stage writes them: SurfaceInteraction rows whose frame
/// is Frame(n).
struct Points {
  std::vector<SurfaceInteraction> rows;
  size_t size() const { return rows.size(); }
  void Push(const Vec3f& p, const Vec3f& ng, const Vec3f& n) {
    SurfaceInteraction its;
    its.p = p, its.ng = ng, its.frame = Frame(n);
    rows.push_back(its);
  }
  const SurfaceInteraction* View() const { return rows.data(); }
};

/// The spawn rows: shading-point entry and local direction.
struct Rows {
  std::vector<uint32_t> entry;
  std::vector<float> wi_x, wi_y, wi_z;
  size_t size() const { return entry.size(); }
  void Push(uint32_t q, const Vec3f& wi) {
    entry.push_back(q), wi_x.push_back(wi.x), wi_y.push_back(wi.y), wi_z.push_back(wi.z);
  }
  SpawnInputs In(size_t from = 0) const {
    return {entry.data() + from, wi_x.data() + from, wi_y.data() + from, wi_z.data() + from};
  }
};

Vec3f RandomUnit(Pcg32& rng) {
  for (;;) {
    const Vec3f v{2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1};
    const float l = Length(v);
    if (l > 1e-3f && l <= 1.0f) return v / l;
  }
}

// Coordinates that exercise OffsetRayOrigin: zero of both signs, the 1/32 switch and its
// neighbours, tiny (normal and subnormal), ordinary and huge, of both signs.
std::vector<float> HardCoordinates() {
  const float origin = 1.0f / 32.0f;
  std::vector<float> v = {0.0f,
                          1e-30f,
                          1e-40f,
                          origin,
                          std::nextafter(origin, 0.0f),
                          std::nextafter(origin, 1.0f),
                          0.5f,
                          1.0f,
                          3.75f,
                          1234.5f,
                          1e7f,
                          1e30f};
  const size_t n = v.size();
  for (size_t i = 0; i < n; ++i) v.push_back(-v[i]);
  return v;
}

std::vector<Vec3f> HardNormals() {
  std::vector<Vec3f> v = {{1, 0, 0},      {-1, 0, 0},          {0, 1, 0},         {0, -1, 0},
                          {0, 0, 1},      {0, 0, -1},          {-0.0f, 0, -1.0f}, {1.0f, 0, -0.0f},
                          {0, -1, -0.0f}, {-0.0f, -0.0f, 1.0f}};
  const float s = 1.0f / std::sqrt(3.0f), h = std::sqrt(0.5f);
  v.push_back({s, -s, s}), v.push_back({-s, s, -s}), v.push_back({h, 0, -h});
  v.push_back({0, h, h}), v.push_back({1e-7f, 0, -1.0f}), v.push_back({0, -1e-7f, 1.0f});
  return v;
}

// Local directions: along the axes, grazing (z = ±0, ±1e-7), random.
std::vector<Vec3f> HardDirections(Pcg32& rng) {
  std::vector<Vec3f> v = {{0, 0, 1},        {0, 0, -1},        {1, 0, 0},       {-1, 0, 0},
                          {0, 1, 0},        {0, -1, 0},        {1, 0, -0.0f},   {0, -1, 0.0f},
                          {1.0f, 0, 1e-7f}, {0, 1.0f, -1e-7f}, {0.6f, 0.8f, 0}, {-0.8f, 0.6f, 0}};
  for (int i = 0; i < 8; ++i) {
    Vec3f w = RandomUnit(rng);
    w.z = (i & 1) ? 1e-7f : -1e-7f;  // grazing, off-axis
    v.push_back(w);
  }
  return v;
}

void ExpectSameAsOracle(Points& points, const Rows& rows, size_t from, size_t n) {
  const size_t packets = (n + kPacketWidth - 1) / kPacketWidth;
  // Garbage in the packets first: both must write every lane of every packet they get.
  std::vector<RayPacket8> want(packets), got(packets);
  if (packets > 0) {  // memset must not get the null data() of an empty vector (UBSan)
    std::memset(want.data(), 0xab, packets * sizeof(RayPacket8));
    std::memset(got.data(), 0xcd, packets * sizeof(RayPacket8));
  }
  SpawnRayBatch(points.View(), n, rows.In(from), want.data());
  simd::SpawnRayBatch(points.View(), n, rows.In(from), got.data());
  for (size_t k = 0; k < packets; ++k) {
    for (int j = 0; j < int(kPacketWidth); ++j) {
      const Ray w = GetLaneRay(want[k], j), g = GetLaneRay(got[k], j);
      const size_t row = k * kPacketWidth + size_t(j);
      SCOPED_TRACE(testing::Message() << "row " << row << " of " << n);
      ASSERT_EQ(std::memcmp(&w, &g, sizeof(Ray)), 0)
          << "o (" << w.o.x << " " << w.o.y << " " << w.o.z << ") vs (" << g.o.x << " " << g.o.y
          << " " << g.o.z << "), d (" << w.d.x << " " << w.d.y << " " << w.d.z << ") vs (" << g.d.x
          << " " << g.d.y << " " << g.d.z << ")";
      if (row >= n) {
        const Ray zero{{}, {}, 0.0f, 0.0f};
        ASSERT_EQ(std::memcmp(&g, &zero, sizeof(Ray)), 0);
        continue;
      }
      ASSERT_TRUE(std::isfinite(g.o.x) && std::isfinite(g.o.y) && std::isfinite(g.o.z));
      ASSERT_TRUE(std::isfinite(g.d.x) && std::isfinite(g.d.y) && std::isfinite(g.d.z));
      ASSERT_EQ(g.t_min, 0.0f);
      ASSERT_EQ(g.t_max, std::numeric_limits<float>::infinity());
    }
  }
}

// The oracle is the scalar path's ray: its.frame.ToWorld(wi) from SpawnOrigin(its, wi).
TEST(Spawn8, OracleIsTheScalarPathsRay) {
  Pcg32 rng(7, 1);
  Points points;
  for (int i = 0; i < 1000; ++i) {
    const float scale = std::pow(10.0f, float(int(rng.NextUint() % 12)) - 4.0f);
    const Vec3f p{scale * (2 * rng.NextFloat() - 1), scale * (2 * rng.NextFloat() - 1),
                  scale * (2 * rng.NextFloat() - 1)};
    points.Push(p, RandomUnit(rng), RandomUnit(rng));
  }
  for (uint32_t q = 0; q < points.size(); ++q) {
    const SurfaceInteraction& its = points.rows[q];
    const Vec3f wi_local = RandomUnit(rng);
    const Vec3f wi = its.frame.ToWorld(wi_local);
    const Ray want{integrator::SpawnOrigin(its, wi), wi, 0.0f, integrator::kInfinity};
    const Ray got = SpawnRayAt(its, wi_local);
    ASSERT_EQ(std::memcmp(&want, &got, sizeof(Ray)), 0) << "row " << q;
  }
}

TEST(Spawn8, MatchesOracleOnRandomRows) {
  Pcg32 rng(11, 3);
  Points points;
  for (int i = 0; i < 4096; ++i) {
    // Magnitudes from 1e-6 to 1e6, both signs, so both sides of the 1/32 switch come up.
    const auto coordinate = [&] {
      const float scale = std::pow(10.0f, 12.0f * rng.NextFloat() - 6.0f);
      return (rng.NextUint() & 1) ? scale : -scale;
    };
    points.Push({coordinate(), coordinate(), coordinate()}, RandomUnit(rng), RandomUnit(rng));
  }
  Rows rows;
  for (int i = 0; i < 100003; ++i) {
    rows.Push(rng.NextUint() % uint32_t(points.size()), RandomUnit(rng));
  }
  test::ForEachTarget(simd::DispatchedTargetName,
                      [&](const char*) { ExpectSameAsOracle(points, rows, 0, rows.size()); });
}

TEST(Spawn8, MatchesOracleOnHardCases) {
  Pcg32 rng(5, 9);
  Points points;
  const std::vector<float> coordinates = HardCoordinates();
  const std::vector<Vec3f> normals = HardNormals();
  // Every hard coordinate on every axis, with hard and random normals (geometric and shading).
  for (size_t i = 0; i < coordinates.size(); ++i) {
    for (size_t a = 0; a < normals.size(); ++a) {
      const float c = coordinates[i];
      const float o = coordinates[(i + a) % coordinates.size()];
      const Vec3f ng = normals[a], n = normals[(a * 7 + i) % normals.size()];
      points.Push({c, o, -c}, ng, n);
      points.Push({o, c, c}, n, ng);
      points.Push({-o, -c, o}, RandomUnit(rng), n);
      points.Push({c, c, o}, ng, RandomUnit(rng));
    }
  }
  const std::vector<Vec3f> directions = HardDirections(rng);
  Rows rows;
  for (uint32_t q = 0; q < points.size(); ++q) {
    for (const Vec3f& wi : directions) rows.Push(q, wi);
  }
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    ExpectSameAsOracle(points, rows, 0, rows.size());
    // Batch tails and offsets: every count from 0 to 17 rows, starting off a packet boundary.
    for (size_t n = 0; n <= 17; ++n) ExpectSameAsOracle(points, rows, 3, n);
  });
}

}  // namespace
}  // namespace ptlab
