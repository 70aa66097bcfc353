// simd::AddAreaEmissions against its oracle ptlab::AddAreaEmissions (the shading stage's light
// from the area lights that rays hit): every path's L bit-identical on every compiled target,
// for a million random rows and the hard cases (rays of length 0, tiny and huge; normals facing
// away and perpendicular; black, negative, Inf and NaN radiance; light areas 0, negative and
// NaN; the vertex before at the hit point; pdfs 0, Inf and NaN; throughputs and L of 0, Inf and
// NaN; hits that are no area light; every combination of nee, mis and the heuristic; uniform
// and power selection, pmf 0; batch sizes 0 to 2 vectors and more), the paths not in the batch
// untouched.
#include "simd/wavefront/emission8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/core/check.h"
#include "engine/core/rng.h"
#include "engine/wavefront/emission.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"
#include "tests/simd/row_checks.h"

namespace ptlab {
namespace {

using test::kInf;
using test::kNaN;

/// A scene of `lights` area lights (emitters in table order) with `selection`; light l has
/// radiance (l + 1) · (1, 0.5, 0.25) and area 0.5 + l unless `hard`, which mixes in black,
/// negative, Inf and NaN radiance and areas 0, negative and NaN, and a pmf of 0.
Scene AreaLightScene(Pcg32& rng, uint32_t lights, LightSelection selection, bool power, bool hard) {
  static const float kRadiance[] = {0.0f, -1.0f, kInf, kNaN, 1e-30f, 2.0f};
  static const float kAreas[] = {0.0f, -1.0f, kNaN, 1e-30f, 1e30f, 4.0f};
  Scene scene;
  scene.integrator.light_selection = selection;
  scene.integrator.power_heuristic = power;
  AreaLightTable& t = scene.area_lights;
  EmitterSelectionTable& s = scene.emitter_selection;
  for (uint32_t l = 0; l < lights; ++l) {
    const float k = float(l + 1);
    Color3f radiance{k, 0.5f * k, 0.25f * k};
    float area = 0.5f + float(l);
    if (hard && rng.NextUint() % 2 == 0) {
      radiance = {kRadiance[rng.NextUint() % 6], kRadiance[rng.NextUint() % 6],
                  kRadiance[rng.NextUint() % 6]};
      area = kAreas[rng.NextUint() % 6];
    }
    t.radiance.push_back(radiance);
    t.area.push_back(area);
    t.mesh.push_back(l);
    scene.emitters.push_back(EmitterRef::Make(EmitterTag::kArea, l));
    s.slot_area.push_back(lights - 1 - l);  // the selection's order reversed
    s.pmf.push_back(hard && l == 0 ? 0.0f : 1.0f / float(lights));
  }
  return scene;
}

/// A wave: rays, owners and shading points by queue entry, path state by path, and the batch's
/// rows (distinct queue entries in random order, so each of a different path).
struct Wave {
  std::vector<RayPacket8> rays;
  std::vector<uint32_t> owner;
  std::vector<SurfaceInteraction> its;
  std::vector<Color3f> throughput, L;
  std::vector<uint32_t> specular;
  std::vector<float> prev_pdf;
  std::vector<Vec3f> prev_p;
  std::vector<uint32_t> entries;
};

Vec3f RandomDirection(Pcg32& rng) {
  return {rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1};
}

Wave RandomWave(Pcg32& rng, uint32_t lights, size_t queue, size_t n, bool hard) {
  static const float kScales[] = {0.0f, 1e-30f, 1e-20f, 1.0f, 1e20f};
  static const float kValues[] = {0.0f, -0.0f, 1e-40f, 0.5f, 1e30f, kInf, kNaN};
  const auto odd = [&rng, hard] { return hard && rng.NextUint() % 3 == 0; };
  const auto value = [&](float plain) { return odd() ? kValues[rng.NextUint() % 7] : plain; };
  // Bounded for the compiler too: without it GCC 12 warns (-Walloc-size-larger-than) that
  // queue + 5 could wrap.
  PTLAB_CHECK(n <= queue && queue < (size_t{1} << 24));
  Wave w;
  const size_t paths = queue + 5;
  w.rays.resize((queue + kPacketWidth - 1) / kPacketWidth);
  w.owner.resize(queue), w.its.resize(queue);
  const std::vector<uint32_t> perm = test::Shuffled(rng, paths);
  for (size_t q = 0; q < queue; ++q) {
    RayPacket8& p = w.rays[q / kPacketWidth];
    const size_t j = q % kPacketWidth;
    Vec3f d = RandomDirection(rng);
    if (odd()) d = d * kScales[rng.NextUint() % 5];
    p.org_x[j] = rng.NextFloat(), p.org_y[j] = rng.NextFloat(), p.org_z[j] = rng.NextFloat();
    p.dir_x[j] = d.x, p.dir_y[j] = d.y, p.dir_z[j] = d.z;
    p.t_min[j] = 0.0f, p.t_max[j] = kInf;
    w.owner[q] = perm[q];
    SurfaceInteraction& s = w.its[q];
    s.p = {rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4};
    Vec3f n = Normalize(RandomDirection(rng) + Vec3f{0, 0, 0.01f});
    // Hard: the normal perpendicular to the ray (cos exactly 0 when it is exact) or against it.
    if (odd()) n = rng.NextUint() % 2 ? Vec3f{-d.y, d.x, 0.0f} : d;
    s.ng = n;
    s.frame.n = n;
    s.prim = rng.NextUint() % 1000;
    const uint32_t kind = rng.NextUint() % 10;
    s.emitter = kind < 8   ? EmitterRef::Make(EmitterTag::kArea, rng.NextUint() % lights)
                : kind < 9 ? EmitterRef::None()
                           : EmitterRef::Make(EmitterTag::kPoint, 0x0fffffffu);
  }
  w.throughput.resize(paths), w.L.resize(paths), w.specular.resize(paths);
  w.prev_pdf.resize(paths), w.prev_p.resize(paths);
  for (size_t i = 0; i < paths; ++i) {
    w.throughput[i] = {value(rng.NextFloat()), value(rng.NextFloat()), value(rng.NextFloat())};
    w.L[i] = {value(rng.NextFloat()), value(rng.NextFloat()), value(rng.NextFloat())};
    w.specular[i] = rng.NextUint() % 3 == 0;
    w.prev_pdf[i] = value(rng.NextFloat() * 4);
    w.prev_p[i] = {rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4};
  }
  w.entries = test::DistinctRows(rng, queue, n);
  if (hard) {
    // The vertex before at the hit point itself (dist² = 0) for some rows.
    for (size_t k = 0; k < n; k += 5) w.prev_p[w.owner[w.entries[k]]] = w.its[w.entries[k]].p;
  }
  return w;
}

/// The same bits in every channel, except that a NaN may have another payload or sign: where a
/// sum or product has two NaN operands, which one x86 returns depends on the operands' order,
/// which the compiler may swap. A NaN L is a dropped sample either way.
bool SameBitsOrBothNaN(const Color3f& a, const Color3f& b) {
  for (int c = 0; c < 3; ++c) {
    const float x = c == 0 ? a.r : c == 1 ? a.g : a.b, y = c == 0 ? b.r : c == 1 ? b.g : b.b;
    if (std::isnan(x) && std::isnan(y)) continue;
    if (std::memcmp(&x, &y, sizeof(float)) != 0) return false;
  }
  return true;
}

void ExpectSameAsOracle(const Scene& scene, const EmissionBatchRules& rules, const Wave& wave,
                        const char* what) {
  SCOPED_TRACE(what);
  Wave want = wave, got = wave;
  const auto run = [&](Wave& w, bool simd) {
    const EmissionBatchInputs in{w.entries.data(), w.rays.data(), w.owner.data(), w.its.data()};
    const EmissionBatchPaths paths{w.throughput.data(), w.specular.data(), w.prev_pdf.data(),
                                   w.prev_p.data(), w.L.data()};
    if (simd) {
      simd::AddAreaEmissions(scene, rules, w.entries.size(), in, paths);
    } else {
      ptlab::AddAreaEmissions(scene, rules, w.entries.size(), in, paths);
    }
  };
  run(want, false);
  run(got, true);
  // Every path's L, those not in the batch included.
  for (size_t i = 0; i < want.L.size(); ++i) {
    EXPECT_TRUE(SameBitsOrBothNaN(want.L[i], got.L[i])) << "path " << i;
  }
  // The batch adds light: some row changed L (unless nothing can emit).
  if (wave.entries.size() >= 64) {
    EXPECT_FALSE(test::SameBytes(want.L, wave.L));
  }
}

TEST(Emission8, MatchesOracleOnRandomRows) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(17, 4);
    size_t rows = 0;
    for (int round = 0; round < 32; ++round) {
      for (int variant = 0; variant < 8; ++variant) {
        const uint32_t lights = 1 + rng.NextUint() % 6;
        const Scene scene = AreaLightScene(
            rng, lights, (variant & 4) ? LightSelection::kPower : LightSelection::kUniform,
            (variant & 2) != 0, /*hard=*/false);
        const EmissionBatchRules rules{.nee = (variant & 1) != 0 || round % 2 == 0,
                                       .mis = (variant & 1) != 0};
        const size_t n = 800 + rng.NextUint() % 400;
        ExpectSameAsOracle(scene, rules, RandomWave(rng, lights, n + 300, n, false), "random");
        rows += n;
        if (HasFatalFailure()) return;
      }
    }
    EXPECT_GE(rows, size_t(250000));  // per target; four targets: 10^6 rows
  });
}

TEST(Emission8, MatchesOracleOnHardCases) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(3, 8);
    for (int variant = 0; variant < 16; ++variant) {
      const uint32_t lights = 1 + uint32_t(variant) % 4;
      Scene scene = AreaLightScene(
          rng, lights, (variant & 4) ? LightSelection::kPower : LightSelection::kUniform,
          (variant & 2) != 0, /*hard=*/true);
      // Solid-angle sampling of the light triangles (the oracle's branch) in some variants,
      // over triangles the hits' rows (prim < 1000) name.
      if (variant & 8) {
        scene.integrator.triangle_sampling = TriangleSampling::kSolidAngle;
        for (int t = 0; t < 1000; ++t) {
          const Vec3f a = RandomDirection(rng) * 4.0f;
          scene.triangles.Append(a, a + RandomDirection(rng), a + RandomDirection(rng));
        }
      }
      for (const bool nee : {false, true}) {
        for (const bool mis : {false, true}) {
          // Batch sizes around whole vectors of every target (1, 2, 4, 8 rows), and empty.
          for (const size_t n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33, 257}) {
            ExpectSameAsOracle(scene, {.nee = nee, .mis = mis},
                               RandomWave(rng, lights, n + 40, n, /*hard=*/true), "hard");
            if (HasFatalFailure()) return;
          }
        }
      }
    }
  });
}

// Textured area lights (AreaLightRadianceAt at the hit's uv): every other light textured (a
// 4 × 3 bitmap of random texels, bilinear and repeat; a 1 × 1 one, nearest and mirror; a
// checkerboard scaled in uv), the hits' uv random in [-3, 3]² and on texel borders, the other
// lights constant. The SIMD kernel's texture lanes (EvalTexture8) against the oracle.
TEST(Emission8, MatchesOracleWithTexturedLights) {
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Pcg32 rng(29, 5);
    for (int variant = 0; variant < 16; ++variant) {
      const uint32_t lights = 1 + uint32_t(variant) % 5;
      Scene scene = AreaLightScene(
          rng, lights, (variant & 4) ? LightSelection::kPower : LightSelection::kUniform,
          (variant & 2) != 0, /*hard=*/(variant & 8) != 0);
      TextureTable& t = scene.textures;
      const uint32_t bitmap = t.AddRow(TextureKind::kBitmap, 4, 3, 36);
      const uint32_t tiny = t.AddRow(TextureKind::kBitmap, 1, 1, 3);
      t.filter[tiny] = uint8_t(TextureFilter::kNearest);
      t.wrap[tiny] = uint8_t(TextureWrap::kMirror);
      const uint32_t checker = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
      t.m00[checker] = 2.0f, t.m11[checker] = 3.0f;
      for (float& x : t.data) x = 5.0f * rng.NextFloat();
      const uint32_t rows[] = {bitmap, tiny, checker};
      scene.area_lights.texture.assign(lights, kNoTexture);
      for (uint32_t l = 0; l < lights; l += 2) scene.area_lights.texture[l] = rows[(l / 2) % 3];
      for (const bool nee : {false, true}) {
        for (const bool mis : {false, true}) {
          for (const size_t n : {1, 7, 8, 9, 17, 257, 1000}) {
            Wave wave = RandomWave(rng, lights, n + 40, n, /*hard=*/(variant & 8) != 0);
            for (SurfaceInteraction& s : wave.its) {
              s.uv = {rng.NextFloat() * 6 - 3, rng.NextFloat() * 6 - 3};
              // Texel borders and centres of the 4 × 3 bitmap.
              if (rng.NextUint() % 4 == 0)
                s.uv = {float(rng.NextUint() % 9) / 8.0f, float(rng.NextUint() % 7) / 6.0f};
            }
            ExpectSameAsOracle(scene, {.nee = nee, .mis = mis}, wave, "textured");
            if (HasFatalFailure()) return;
          }
        }
      }
    }
  });
}

}  // namespace
}  // namespace ptlab
