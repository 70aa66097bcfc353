// simd::ShadeBatch on two-sided diffuse rows with a textured albedo against the oracle on every
// compiled Highway target: the two-sided copies keep the rows' shading points, so f is
// bit-identical (before the fix the textured rows read their constant albedo, 0).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/wavefront/bsdf8.h"
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

TEST(TwoSided8Texture, TexturedTwoSidedDiffuseMatchesTheOracle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-3.0f, 4.0f);
  Scene scene;
  TextureTable& t = scene.textures;
  const uint32_t bitmap = t.AddRow(TextureKind::kBitmap, 5, 3, 45);
  for (int k = 0; k < 45; ++k) t.data[t.offset[bitmap] + k] = 0.1f + unit(rng);
  MaterialTables m;
  m.AddDiffuse({0.2f, 0.4f, 0.6f});
  m.two_sided.Set(m.AddTexturedDiffuse(bitmap));
  m.two_sided.Set(m.AddDiffuse({0.7f, 0.1f, 0.3f}));
  constexpr size_t n = 601;
  std::vector<SurfaceInteraction> its(n);
  std::vector<uint32_t> index(n), entry(n);
  std::vector<float> wo_x(n), wo_y(n), wo_z(n), wl_x(n), wl_y(n), wl_z(n);
  for (size_t i = 0; i < n; ++i) {
    index[i] = uint32_t(i % 3);
    entry[i] = uint32_t(n - 1 - i);
    its[entry[i]].uv = {wide(rng), wide(rng)};
    const float a = unit(rng) * 6.28f, z = 0.05f + 0.9f * unit(rng), r = std::sqrt(1 - z * z);
    const float sign = i % 2 == 0 ? 1.0f : -1.0f;  // both sides
    wo_x[i] = r * std::cos(a), wo_y[i] = r * std::sin(a), wo_z[i] = sign * z;
    wl_x[i] = -wo_y[i], wl_y[i] = wo_x[i], wl_z[i] = wo_z[i];
  }
  ShadeInputs in;
  in.wo = {wo_x.data(), wo_y.data(), wo_z.data()};
  in.wl = {wl_x.data(), wl_y.data(), wl_z.data()};
  in.texture = {&scene.textures, its.data(), entry.data()};
  std::vector<float> want[4], got[4];
  for (auto* v : {want, got})
    for (int c = 0; c < 4; ++c) v[c].assign(n, -1.0f);
  const auto view = [](std::vector<float>* c) {
    ShadeOutputs o;
    o.f = {c[0].data(), c[1].data(), c[2].data()};
    o.pdf_l = c[3].data();
    return o;
  };
  ShadeBatch(m, MaterialTag::kDiffuse, index.data(), n, in, view(want));
  int textured_lit = 0;
  for (size_t i = 0; i < n; ++i) textured_lit += index[i] == 1 && want[0][i] > 0;
  EXPECT_GT(textured_lit, 150);  // the textured rows are lit on both sides
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    ShadeBatch(m, MaterialTag::kDiffuse, index.data(), n, in, view(want));
    simd::ShadeBatch(m, MaterialTag::kDiffuse, index.data(), n, in, view(got));
    int failures = 0;
    for (size_t i = 0; i < n && failures < 10; ++i) {
      bool same = true;
      for (int c = 0; c < 4; ++c)
        same &= std::bit_cast<uint32_t>(got[c][i]) == std::bit_cast<uint32_t>(want[c][i]);
      if (same) continue;
      ++failures;
      ADD_FAILURE() << "row " << i << " material " << index[i] << ": f " << got[0][i] << " vs "
                    << want[0][i];
    }
  });
}

}  // namespace
}  // namespace ptlab
