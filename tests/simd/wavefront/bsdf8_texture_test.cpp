// simd::ShadeBatch on diffuse rows with textured albedo against the oracle ptlab::ShadeBatch on
// every compiled Highway target: the textured albedo is bit-identical, so f (albedo / π) is
// bit-identical and so is the sample weight (the albedo itself) wherever both sample.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

TEST(Bsdf8Texture, TexturedDiffuseMatchesTheOracleBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-3.0f, 4.0f);
  Scene scene;  // only its textures
  TextureTable& t = scene.textures;
  const uint32_t bitmap = t.AddRow(TextureKind::kBitmap, 5, 3, 45);
  for (int k = 0; k < 45; ++k) t.data[t.offset[bitmap] + k] = unit(rng);
  const uint32_t nearest = t.AddRow(TextureKind::kBitmap, 2, 2, 12);
  for (int k = 0; k < 12; ++k) t.data[t.offset[nearest] + k] = unit(rng);
  t.filter[nearest] = uint8_t(TextureFilter::kNearest), t.wrap[nearest] = uint8_t(TextureWrap::kMirror);
  const uint32_t checker = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  for (int k = 0; k < 6; ++k) t.data[t.offset[checker] + k] = unit(rng);
  const uint32_t face = t.AddRow(TextureKind::kFaceAttribute, 3, 4, 12);
  for (int k = 0; k < 12; ++k) t.data[t.offset[face] + k] = wide(rng);  // some < 0: clamped
  MaterialTables m;
  m.AddDiffuse({0.2f, 0.4f, 0.6f});
  for (const uint32_t id : {bitmap, nearest, checker, face}) m.AddTexturedDiffuse(id);
  m.AddDiffuse({0.9f, 0.1f, 0.3f});
  constexpr size_t n = 1003;
  std::vector<SurfaceInteraction> its(2 * n);
  std::vector<uint32_t> index(n), entry(n);
  std::vector<float> wo_x(n), wo_y(n), wo_z(n), wl_x(n), wl_y(n), wl_z(n), ul(n), ux(n), uy(n);
  std::uniform_int_distribution<uint32_t> row(0, uint32_t(m.diffuse.size() - 1)), prim(0, 9);
  for (size_t i = 0; i < n; ++i) {
    index[i] = row(rng);
    entry[i] = uint32_t(2 * i + (i % 2));  // the shading points are not in row order
    SurfaceInteraction& s = its[entry[i]];
    s.uv = {wide(rng), i % 13 == 0 ? float(i % 5) / 5.0f : wide(rng)};
    s.p = {wide(rng), wide(rng), wide(rng)};
    s.prim = prim(rng);
    const float a = unit(rng) * 6.28f, z = unit(rng);
    const float r = std::sqrt(1 - z * z);
    wo_x[i] = r * std::cos(a), wo_y[i] = r * std::sin(a), wo_z[i] = i % 11 == 0 ? -z : z;
    wl_x[i] = -wo_y[i], wl_y[i] = wo_x[i], wl_z[i] = std::abs(wo_z[i]);
    ul[i] = unit(rng), ux[i] = unit(rng), uy[i] = unit(rng);
  }
  ShadeInputs in;
  in.wo = {wo_x.data(), wo_y.data(), wo_z.data()};
  in.wl = {wl_x.data(), wl_y.data(), wl_z.data()};
  in.u_lobe = ul.data(), in.u_x = ux.data(), in.u_y = uy.data();
  in.texture = {&scene.textures, its.data(), entry.data()};
  struct Out {
    std::vector<float> c[12];
    explicit Out(size_t size) {
      for (auto& v : c) v.assign(size, -1.0f);
    }
    ShadeOutputs View() {
      ShadeOutputs o;
      o.f = {c[0].data(), c[1].data(), c[2].data()};
      o.pdf_l = c[3].data();
      o.wi = {c[4].data(), c[5].data(), c[6].data()};
      o.weight = {c[7].data(), c[8].data(), c[9].data()};
      o.pdf = c[10].data(), o.eta = c[11].data();
      return o;
    }
  };
  Out want(n);
  ShadeBatch(m, MaterialTag::kDiffuse, index.data(), n, in, want.View());
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Out got(n);
    simd::ShadeBatch(m, MaterialTag::kDiffuse, index.data(), n, in, got.View());
    int failures = 0;
    for (size_t i = 0; i < n && failures < 10; ++i) {
      bool same = true;
      for (int c : {0, 1, 2})  // f
        same &= std::bit_cast<uint32_t>(got.c[c][i]) == std::bit_cast<uint32_t>(want.c[c][i]);
      if (want.c[10][i] > 0 && got.c[10][i] > 0)
        for (int c : {7, 8, 9})  // the weight: the albedo
          same &= std::bit_cast<uint32_t>(got.c[c][i]) == std::bit_cast<uint32_t>(want.c[c][i]);
      if (same) continue;
      ++failures;
      ADD_FAILURE() << "row " << i << " material " << index[i] << ": f " << got.c[0][i] << " vs "
                    << want.c[0][i] << ", weight " << got.c[7][i] << " vs " << want.c[7][i];
    }
  });
}

}  // namespace
}  // namespace ptlab
