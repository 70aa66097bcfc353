// simd::SampleAreaLightBatch against its oracle ptlab::SampleAreaLightBatch (SampleAreaLight
// per row): every output bit-identical on every compiled target, for 10^6 random rows per scene
// and the hard cases (grazing and coincident reference points, the CDF's edges, degenerate
// triangles, zero-area lights, batch tails), and no NaN or Inf out.
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/dispatched_target.h"
#include "simd/wavefront/area_light8.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/io/scene_file.h"
#include "engine/wavefront/area_light.h"
#include "tests/simd/for_each_target.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

struct Rows {
  std::vector<uint32_t> light;
  std::vector<float> ref_x, ref_y, ref_z, u_x, u_y;
  size_t size() const { return light.size(); }
  void Push(uint32_t l, const Vec3f& ref, float ux, float uy) {
    light.push_back(l), ref_x.push_back(ref.x), ref_y.push_back(ref.y), ref_z.push_back(ref.z);
    u_x.push_back(ux), u_y.push_back(uy);
  }
  AreaLightBatchInputs In() const {
    return {light.data(), ref_x.data(), ref_y.data(), ref_z.data(), u_x.data(), u_y.data()};
  }
};

// The outputs; with `le`, the radiance columns too (textured area lights).
struct Outputs {
  Outputs(size_t n, bool le = false) : col(le ? 13 : 10, std::vector<float>(n)) {}
  std::vector<std::vector<float>> col;
  AreaLightBatchOutputs Out() {
    const bool le = col.size() == 13;
    return {col[0].data(), col[1].data(), col[2].data(), col[3].data(), col[4].data(),
            col[5].data(), col[6].data(), col[7].data(), col[8].data(), col[9].data(),
            le ? col[10].data() : nullptr, le ? col[11].data() : nullptr,
            le ? col[12].data() : nullptr};
  }
};

// Textures on the scene's lights, every other light (from light 0) textured: a bitmap of
// random texels (5 × 3, repeat, bilinear), one of 1 × 1 (clamp, nearest), a checkerboard
// scaled in uv; the others keep their constant radiance.
void AddLightTextures(Scene* scene, Pcg32& rng) {
  TextureTable& t = scene->textures;
  const uint32_t bitmap = t.AddRow(TextureKind::kBitmap, 5, 3, 45);
  const uint32_t tiny = t.AddRow(TextureKind::kBitmap, 1, 1, 3);
  t.filter[tiny] = uint8_t(TextureFilter::kNearest), t.wrap[tiny] = uint8_t(TextureWrap::kClamp);
  const uint32_t checker = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  t.m00[checker] = 3.0f, t.m11[checker] = -2.0f, t.m02[checker] = 0.25f;
  for (float& x : t.data) x = 4.0f * rng.NextFloat();
  const uint32_t rows[] = {bitmap, tiny, checker};
  AreaLightTable& l = scene->area_lights;
  l.texture.assign(l.size(), kNoTexture);
  for (size_t i = 0; i < l.size(); i += 2) l.texture[i] = rows[(i / 2) % 3];
}

// The hard cases of the scene's lights: a zero-area light (a copy of light 0 with area 0) and
// one degenerate triangle (its third vertex moved onto the second) in a light of several.
void AddHardLights(Scene* scene) {
  AreaLightTable& l = scene->area_lights;
  l.radiance.push_back(l.radiance[0]), l.mesh.push_back(l.mesh[0]), l.area.push_back(0.0f);
  l.cdf_offset.push_back(l.cdf_offset[0]), l.guide_offset.push_back(l.guide_offset[0]);
  for (size_t i = 0; i < l.size(); ++i) {
    if (scene->meshes.triangle_count[l.mesh[i]] < 2) continue;
    const uint32_t tri = scene->meshes.first_triangle[l.mesh[i]];
    TriangleTable& t = scene->triangles;
    t.v2_x[tri] = t.v1_x[tri], t.v2_y[tri] = t.v1_y[tri], t.v2_z[tri] = t.v1_z[tri];
    break;
  }
}

// Copies of the scene's lights (the same meshes and CDFs) until it has `lights` rows: a scene
// of many lights, whose per-light values the kernel gathers instead of holding in registers.
void AddLightCopies(Scene* scene, size_t lights) {
  AreaLightTable& l = scene->area_lights;
  for (size_t i = 0; l.size() < lights; ++i) {
    l.radiance.push_back(l.radiance[i]), l.mesh.push_back(l.mesh[i]), l.area.push_back(l.area[i]);
    l.cdf_offset.push_back(l.cdf_offset[i]), l.guide_offset.push_back(l.guide_offset[i]);
  }
}

// `random` rows of random lights, reference points in the scene's box and numbers, then the
// hard cases: reference points on the lights' vertices and planes (grazing), numbers on the
// CDF's entries and the ends of [0, 1).
Rows MakeRows(const Scene& scene, size_t random, Pcg32& rng) {
  Rows r;
  const TriangleTable& t = scene.triangles;
  Vec3f lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (size_t i = 0; i < t.v0_x.size(); ++i) {
    for (const Vec3f& v : {t.V0(i), t.V1(i), t.V2(i)}) lo = Min(lo, v), hi = Max(hi, v);
  }
  const uint32_t lights = uint32_t(scene.area_lights.size());
  const auto in_box = [&] {
    return Vec3f{lo.x + (hi.x - lo.x) * rng.NextFloat(), lo.y + (hi.y - lo.y) * rng.NextFloat(),
                 lo.z + (hi.z - lo.z) * rng.NextFloat()};
  };
  for (size_t i = 0; i < random; ++i) {
    // Named draws: a call's arguments are evaluated in an unspecified order.
    const uint32_t light = rng.NextUint() % lights;
    const Vec3f p = in_box();
    const float u_x = rng.NextFloat(), u_y = rng.NextFloat();
    r.Push(light, p, u_x, u_y);
  }
  const float edges[] = {0.0f, 0x1.fffffep-1f, 0.5f, 1e-30f};
  for (uint32_t l = 0; l < lights; ++l) {
    const uint32_t mesh = scene.area_lights.mesh[l];
    const uint32_t first = scene.meshes.first_triangle[mesh];
    const uint32_t count = scene.meshes.triangle_count[mesh];
    const float* cdf = scene.area_lights.triangle_cdf.data() + scene.area_lights.cdf_offset[l];
    for (uint32_t k = 0; k < count && k < 64; ++k) {
      const uint32_t tri = first + k;
      const Vec3f v0 = t.V0(tri), v1 = t.V1(tri), v2 = t.V2(tri);
      const Vec3f mid = (v0 + v1) * 0.5f, centre = (v0 + v1 + v2) * (1.0f / 3.0f);
      // On the triangle's plane, outside it: every point of it is seen at grazing angle.
      const Vec3f grazing = centre + (v1 - v0) * 3.0f + (v2 - v0) * 2.0f;
      for (const Vec3f& ref : {v0, v1, v2, mid, centre, grazing}) {
        for (const float u : edges) r.Push(l, ref, u, rng.NextFloat());
        r.Push(l, ref, cdf[k], rng.NextFloat());
        r.Push(l, ref, std::nextafter(cdf[k], 0.0f), 1.0f - rng.NextFloat());
        if (k > 0) r.Push(l, ref, cdf[k - 1], 0.0f);
      }
    }
  }
  return r;
}

// `lights`: the scene's lights are copied up to that many first (0: as loaded). `textured`:
// textures on every other light (AddLightTextures) unless the scene has its own, and the
// radiance columns compared too.
void ExpectBatchMatchesOracle(const std::string& path, size_t lights = 0, bool textured = false,
                              size_t random_rows = 1000003) {
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Scene> loaded = LoadSceneFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  ASSERT_GT(scene.area_lights.size(), 0u);
  AddLightCopies(&scene, lights);
  AddHardLights(&scene);
  Pcg32 rng(7, 11);
  if (textured && scene.area_lights.texture.empty()) AddLightTextures(&scene, rng);
  if (!scene.area_lights.texture.empty())
    scene.area_lights.texture.resize(scene.area_lights.size(), kNoTexture);
  Rows rows = MakeRows(scene, random_rows, rng);
  for (const TriangleSampling mode : {TriangleSampling::kArea, TriangleSampling::kSolidAngle}) {
    SCOPED_TRACE(mode == TriangleSampling::kArea ? "area" : "solid angle");
    const size_t n =
        mode == TriangleSampling::kArea ? rows.size() : std::min<size_t>(rows.size(), 100003);
    Outputs want(n, textured);
    SampleAreaLightBatch(scene, mode, n, rows.In(), want.Out());
    // A sampled point as the reference point (the distance is 0): 1 row in 1000.
    if (mode == TriangleSampling::kArea) {
      Rows again = rows;
      for (size_t i = 0; i < n; i += 1000)
        again.ref_x[i] = want.col[0][i], again.ref_y[i] = want.col[1][i],
        again.ref_z[i] = want.col[2][i];
      rows = again;
      SampleAreaLightBatch(scene, mode, n, rows.In(), want.Out());
    }
    size_t valid = 0;
    for (size_t i = 0; i < n; ++i) valid += want.col[9][i] > 0;
    EXPECT_GT(valid, n / 4);  // the inputs are not all degenerate
    const simd::TriangleRows tri_rows = simd::BuildTriangleRows(scene);
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
      // Every tail length: batches of n, and of n - 1 ... n - 7 rows.
      for (size_t cut = 0; cut < 8; ++cut) {
        const size_t m = n - cut;
        Outputs got(m, textured);
        simd::SampleAreaLightBatch(scene, tri_rows, mode, m, rows.In(), got.Out());
        size_t differ = 0, nonfinite = 0, first = m;
        for (size_t c = 0; c < got.col.size(); ++c) {
          for (size_t i = 0; i < m; ++i) {
            const float g = got.col[c][i];
            nonfinite += !std::isfinite(g);
            if (std::bit_cast<uint32_t>(g) != std::bit_cast<uint32_t>(want.col[c][i])) {
              ++differ;
              first = std::min(first, i);
            }
          }
        }
        EXPECT_EQ(differ, 0u) << "first differing row " << first << " of " << m;
        EXPECT_EQ(nonfinite, 0u);
        if (cut == 0 && mode == TriangleSampling::kSolidAngle) break;
      }
    });
  }
}

const std::string kSharedData = test_data::Dir();

TEST(Emitter8, AreaLightBatchMatchesOracleOnCbox) {
  ExpectBatchMatchesOracle(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
}

TEST(Emitter8, AreaLightBatchMatchesOracleOnVeach) {  // sphere lights with vertex normals
  ExpectBatchMatchesOracle(kSharedData + "nori/epfl/scenes/pa5/veach_mi/veach_mis.xml");
}

// More lights than the kernel holds in registers (simd/wavefront/area_light8-inl.h, kRegisterLights = 8):
// the gathered per-light values, which the loaded scenes' few lights no longer reach.
TEST(Emitter8, AreaLightBatchMatchesOracleWithManyLights) {
  ExpectBatchMatchesOracle(kSharedData + "nori/epfl/scenes/pa5/veach_mi/veach_mis.xml", 17);
}

TEST(Emitter8, AreaLightBatchMatchesOracleOnTable) {
  ExpectBatchMatchesOracle(kSharedData + "nori/epfl/scenes/pa5/table/table_mis.xml");
}

// Textured area lights: the radiance columns, the texture at the point's surface uv. On cbox
// (meshes without uvs: uv = the barycentrics) with hand-made textures on every other light,
// and on Mitsuba's various_emitters scene (its own bitmap on a rectangle and OBJ meshes with
// uvs, beside an untextured light).
TEST(Emitter8, AreaLightBatchMatchesOracleWithTextures) {
  ExpectBatchMatchesOracle(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml", 0, true, 100003);
  ExpectBatchMatchesOracle(
      kSharedData + "mitsuba3/tests/scenes/various_emitters/test_various_emitters_ptracer.xml", 0,
      true, 100003);
}

}  // namespace
}  // namespace ptlab
