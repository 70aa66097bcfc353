// simd::EvalTextureBatch against the oracle ptlab::EvalTextureBatch on every compiled Highway
// target: bit-identical on random and adversarial inputs (uv far outside [0, 1], negative,
// -0, exactly on texel borders, 1×1 and 1×n bitmaps, every filter and wrap, checkerboards,
// mesh attributes with prims inside, outside and on spheres).
#include "simd/texture/texture8.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/bvh/sphere_intersect.h"
#include "engine/texture/texture.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"

namespace ptlab {
namespace {

TextureTable MakeTable(std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), coef(-3.0f, 3.0f);
  TextureTable t;
  const uint32_t sizes[][2] = {{1, 1}, {1, 3}, {3, 1}, {5, 2}, {7, 7}, {16, 9}};
  for (const auto& s : sizes)
    for (const TextureFilter f : {TextureFilter::kBilinear, TextureFilter::kNearest})
      for (const TextureWrap w : {TextureWrap::kRepeat, TextureWrap::kMirror, TextureWrap::kClamp}) {
        const uint32_t id = t.AddRow(TextureKind::kBitmap, s[0], s[1], size_t(3) * s[0] * s[1]);
        for (size_t k = 0; k < size_t(3) * s[0] * s[1]; ++k) t.data[t.offset[id] + k] = unit(rng);
        t.filter[id] = uint8_t(f), t.wrap[id] = uint8_t(w);
        if (id % 3 == 1) {  // some with a to_uv
          t.m00[id] = coef(rng), t.m01[id] = coef(rng), t.m02[id] = coef(rng);
          t.m10[id] = coef(rng), t.m11[id] = coef(rng), t.m12[id] = coef(rng);
        }
      }
  for (int k = 0; k < 3; ++k) {
    const uint32_t id = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    for (int c = 0; c < 6; ++c) t.data[t.offset[id] + c] = unit(rng);
    if (k == 1) t.m00[id] = 4, t.m11[id] = -2.5f, t.m12[id] = 0.25f;
  }
  const uint32_t face = t.AddRow(TextureKind::kFaceAttribute, 10, 20, 60);
  for (int c = 0; c < 60; ++c) t.data[t.offset[face] + c] = unit(rng);
  const uint32_t vertex =
      t.AddRow(TextureKind::kVertexAttribute, 25, 8, 8 * kVertexAttributeFloats);
  for (uint32_t c = 0; c < 8 * kVertexAttributeFloats; ++c)
    t.data[t.offset[vertex] + c] = coef(rng);
  return t;
}

float Adversarial(std::mt19937& rng) {
  static const float kValues[] = {0.0f,   -0.0f,  1.0f,    -1.0f, 0.5f,  0.25f,   1.0f / 3,
                                  2.0f / 7, 1e-30f, -1e-30f, 1e6f,  -1e6f, 1e30f,   -1e30f,
                                  7.5f,   -7.5f,  0.9999999f, 16777216.0f, -16777216.0f};
  std::uniform_int_distribution<int> pick(0, 2 * int(std::size(kValues)));
  std::uniform_real_distribution<float> wide(-4.0f, 5.0f);
  std::uniform_int_distribution<int> texel(-40, 40), size(1, 16);
  const int k = pick(rng);
  if (k < int(std::size(kValues))) return kValues[k];
  if (k % 2 == 0) return float(texel(rng)) / float(size(rng));  // on a texel border
  return wide(rng);
}

TEST(Texture8, BitIdenticalToTheOracleOnEveryTarget) {
  std::mt19937 rng(20261206);
  const TextureTable t = MakeTable(rng);
  constexpr size_t n = 20003;  // not a multiple of 8: the padded last vector too
  std::vector<uint32_t> id(n), prim(n);
  std::vector<float> u(n), v(n), px(n), py(n), pz(n);
  std::uniform_int_distribution<uint32_t> row(0, uint32_t(t.size()));  // size() = none
  std::uniform_int_distribution<uint32_t> tri(0, 40);
  std::uniform_real_distribution<float> pos(-2.0f, 2.0f);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t r = row(rng);
    id[i] = r == t.size() ? kNoTexture : r;
    u[i] = Adversarial(rng), v[i] = Adversarial(rng);
    px[i] = pos(rng), py[i] = pos(rng), pz[i] = pos(rng);
    prim[i] = tri(rng) | (i % 17 == 0 ? kSphereHitBit : 0u);
  }
  const TexturePointArrays at{u.data(), v.data(), px.data(), py.data(), pz.data(), prim.data()};
  std::vector<float> want_r(n), want_g(n), want_b(n);
  for (size_t i = 0; i < n; ++i) {
    if (id[i] == kNoTexture) continue;
    EvalTextureBatch(t, &id[i], {&u[i], &v[i], &px[i], &py[i], &pz[i], &prim[i]}, 1, &want_r[i],
                     &want_g[i], &want_b[i]);
  }
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    std::vector<float> r(n, -1.0f), g(n, -1.0f), b(n, -1.0f);
    simd::EvalTextureBatch(t, id.data(), at, n, r.data(), g.data(), b.data());
    size_t mismatches = 0;
    for (size_t i = 0; i < n && mismatches < 10; ++i) {
      const bool same = std::bit_cast<uint32_t>(r[i]) == std::bit_cast<uint32_t>(want_r[i]) &&
                        std::bit_cast<uint32_t>(g[i]) == std::bit_cast<uint32_t>(want_g[i]) &&
                        std::bit_cast<uint32_t>(b[i]) == std::bit_cast<uint32_t>(want_b[i]);
      if (same) continue;
      ++mismatches;
      ADD_FAILURE() << "row " << i << " texture " << id[i] << " uv (" << u[i] << ", " << v[i]
                    << ") prim " << prim[i] << ": simd " << r[i] << " " << g[i] << " " << b[i]
                    << ", oracle " << want_r[i] << " " << want_g[i] << " " << want_b[i];
    }
  });
}

TEST(Texture8, EmptyTableAndNoTextureRowsGiveZero) {
  const TextureTable empty;
  const uint32_t id[3] = {kNoTexture, kNoTexture, kNoTexture}, prim[3] = {0, 1, 2};
  const float z[3] = {0.5f, 0.5f, 0.5f};
  float r[3] = {1, 1, 1}, g[3] = {1, 1, 1}, b[3] = {1, 1, 1};
  simd::EvalTextureBatch(empty, id, {z, z, z, z, z, prim}, 3, r, g, b);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(r[i], 0.0f);
    EXPECT_EQ(g[i], 0.0f);
    EXPECT_EQ(b[i], 0.0f);
  }
}

}  // namespace
}  // namespace ptlab
