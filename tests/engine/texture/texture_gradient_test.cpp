// normal: EvalTextureGradient (engine/texture/texture_gradient.h) against central differences
// of EvalTexture's luminance inside a texel cell, and its zero cases.
#include "engine/texture/texture_gradient.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

uint32_t AddRandomBitmap(TextureTable* t, uint32_t w, uint32_t h, Pcg32& rng) {
  const uint32_t id = t->AddRow(TextureKind::kBitmap, w, h, size_t(3) * w * h);
  for (size_t i = 0; i < size_t(3) * w * h; ++i) t->data[t->offset[id] + i] = rng.NextFloat();
  return id;
}

float LuminanceAt(const TextureTable& t, uint32_t id, float u, float v) {
  return Luminance(EvalTexture(t, id, {{u, v}, {0, 0, 0}, 0}));
}

// Points inside a cell of the bilinear blend (between texel centres), where the blend is
// smooth: the gradient equals central differences of the value to float accuracy.
TEST(TextureGradient, MatchesCentralDifferencesInsideACell) {
  Pcg32 rng(3, 5);
  for (const TextureWrap wrap : {TextureWrap::kRepeat, TextureWrap::kClamp, TextureWrap::kMirror}) {
    for (int scaled = 0; scaled < 2; ++scaled) {
      TextureTable t;
      const uint32_t w = 7, h = 5;
      const uint32_t id = AddRandomBitmap(&t, w, h, rng);
      t.wrap[id] = uint8_t(wrap);
      if (scaled != 0) t.m00[id] = 2.0f, t.m11[id] = 3.0f, t.m02[id] = 0.25f;  // to_uv
      const float su = scaled ? 2.0f : 1.0f, sv = scaled ? 3.0f : 1.0f;
      for (int k = 0; k < 200; ++k) {
        // A cell (cx, cy) of texel centres and a point well inside it, in uv.
        const int cx = int(rng.NextFloat() * (w - 1)), cy = int(rng.NextFloat() * (h - 1));
        const float fx = 0.2f + 0.6f * rng.NextFloat(), fy = 0.2f + 0.6f * rng.NextFloat();
        const float up = (float(cx) + 0.5f + fx) / float(w), vp = (float(cy) + 0.5f + fy) / float(h);
        const float u = (up - (scaled ? 0.25f : 0.0f)) / su, v = vp / sv;
        const Vec2f g = EvalTextureGradient(t, id, {{u, v}, {0, 0, 0}, 0});
        const float eu = 0.05f / (float(w) * su), ev = 0.05f / (float(h) * sv);
        const double du = (double(LuminanceAt(t, id, u + eu, v)) - LuminanceAt(t, id, u - eu, v)) / (2.0 * eu);
        const double dv = (double(LuminanceAt(t, id, u, v + ev)) - LuminanceAt(t, id, u, v - ev)) / (2.0 * ev);
        const double scale = std::max(1.0, std::fabs(du) + std::fabs(dv));
        EXPECT_NEAR(g.x, du, 2e-3 * scale) << k;
        EXPECT_NEAR(g.y, dv, 2e-3 * scale) << k;
      }
    }
  }
}

TEST(TextureGradient, HandValuesOfARamp) {
  // A 2 x 1 bitmap: luminance 0 and 1 (grey texels); between the centres f = x − 0.5 texels:
  // ∂f/∂u = width = 2, ∂f/∂v = 0 (clamp: one row).
  TextureTable t;
  const uint32_t id = t.AddRow(TextureKind::kBitmap, 2, 1, 6);
  for (int c = 0; c < 3; ++c) t.data[t.offset[id] + 3 + c] = 1.0f;
  t.wrap[id] = uint8_t(TextureWrap::kClamp);
  const Vec2f g = EvalTextureGradient(t, id, {{0.5f, 0.5f}, {0, 0, 0}, 0});
  EXPECT_NEAR(g.x, 2.0f, 1e-5f);
  EXPECT_EQ(g.y, 0.0f);
}

TEST(TextureGradient, ZeroForNearestCheckerboardAndAttributes) {
  Pcg32 rng(1, 1);
  TextureTable t;
  const uint32_t bitmap = AddRandomBitmap(&t, 4, 4, rng);
  t.filter[bitmap] = uint8_t(TextureFilter::kNearest);
  const uint32_t checker = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  t.data[t.offset[checker]] = 1.0f;
  const uint32_t face = t.AddRow(TextureKind::kFaceAttribute, 0, 0, 0);
  for (const uint32_t id : {bitmap, checker, face}) {
    const Vec2f g = EvalTextureGradient(t, id, {{0.3f, 0.6f}, {0, 0, 0}, 0});
    EXPECT_EQ(g.x, 0.0f);
    EXPECT_EQ(g.y, 0.0f);
  }
}

TEST(TextureGradient, FiniteForAdversarialUv) {
  Pcg32 rng(2, 2);
  TextureTable t;
  const uint32_t id = AddRandomBitmap(&t, 3, 3, rng);
  for (const float u : {0.0f, -0.0f, 1.0f, -1e30f, 1e30f, 1e-45f, NAN, INFINITY, -INFINITY}) {
    const Vec2f g = EvalTextureGradient(t, id, {{u, 0.5f}, {0, 0, 0}, 0});
    EXPECT_TRUE(std::isfinite(g.x) && std::isfinite(g.y)) << u;
  }
}

}  // namespace
}  // namespace ptlab
