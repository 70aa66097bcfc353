// normal: the uv gradient of a texture's luminance (Mitsuba 3's eval_1_grad).
#include "engine/texture/texture_gradient.h"

#include <algorithm>
#include <cmath>

namespace ptlab {
namespace {

float ClampTexelCoordinate(float x) {
  return x >= -kMaxTexelCoordinate ? std::min(x, kMaxTexelCoordinate) : -kMaxTexelCoordinate;
}

float TexelLuminance(const TextureTable& t, uint32_t id, int32_t x, int32_t y) {
  const float* p = &t.data[t.offset[id] + (size_t(y) * t.width[id] + size_t(x)) * 3];
  return Luminance({p[0], p[1], p[2]});
}

}  // namespace

Vec2f EvalTextureGradient(const TextureTable& t, uint32_t id, const TexturePoint& at) {
  if (t.Kind(id) != TextureKind::kBitmap || TextureFilter(t.filter[id]) != TextureFilter::kBilinear)
    return {0, 0};
  const float m00 = t.m00[id], m01 = t.m01[id], m10 = t.m10[id], m11 = t.m11[id];
  const Vec2f st{m00 * at.uv.x + m01 * at.uv.y + t.m02[id],
                 m10 * at.uv.x + m11 * at.uv.y + t.m12[id]};
  const int32_t w = int32_t(t.width[id]), h = int32_t(t.height[id]);
  const TextureWrap wrap = TextureWrap(t.wrap[id]);
  const float x = ClampTexelCoordinate(st.x * float(w) - 0.5f),
              y = ClampTexelCoordinate(st.y * float(h) - 0.5f);
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int32_t ix = int32_t(x0), iy = int32_t(y0);
  const int32_t xa = WrapTexel(ix, w, wrap), xb = WrapTexel(ix + 1, w, wrap);
  const int32_t ya = WrapTexel(iy, h, wrap), yb = WrapTexel(iy + 1, h, wrap);
  const float f00 = TexelLuminance(t, id, xa, ya), f10 = TexelLuminance(t, id, xb, ya);
  const float f01 = TexelLuminance(t, id, xa, yb), f11 = TexelLuminance(t, id, xb, yb);
  const float df_dx = (1.0f - fy) * (f10 - f00) + fy * (f11 - f01);
  const float df_dy = (1.0f - fx) * (f01 - f00) + fx * (f11 - f10);
  // x = w (m00 u + m01 v + m02), y = h (m10 u + m11 v + m12).
  const float gx = df_dx * float(w), gy = df_dy * float(h);
  return {gx * m00 + gy * m10, gx * m01 + gy * m11};
}

}  // namespace ptlab
