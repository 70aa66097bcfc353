// Texture evaluation, the scalar oracle (SIMD twin: simd/texture/texture8.h).
#include "engine/texture/texture.h"

#include <algorithm>
#include <cmath>

#include "engine/bvh/bvh.h"
#include "engine/bvh/sphere_intersect.h"

namespace ptlab {
namespace {

// A texel coordinate clamped to ±kMaxTexelCoordinate, NaN to the low end.
float ClampTexel(float x) {
  return x >= -kMaxTexelCoordinate ? std::min(x, kMaxTexelCoordinate) : -kMaxTexelCoordinate;
}

Color3f Texel(const TextureTable& t, uint32_t id, int32_t x, int32_t y) {
  const float* p = &t.data[t.offset[id] + (size_t(y) * t.width[id] + size_t(x)) * 3];
  return {p[0], p[1], p[2]};
}

Vec2f ToUv(const TextureTable& t, uint32_t id, const Vec2f& uv) {
  return {t.m00[id] * uv.x + t.m01[id] * uv.y + t.m02[id],
          t.m10[id] * uv.x + t.m11[id] * uv.y + t.m12[id]};
}

Color3f Bitmap(const TextureTable& t, uint32_t id, const Vec2f& uv) {
  const Vec2f st = ToUv(t, id, uv);
  const int32_t w = int32_t(t.width[id]), h = int32_t(t.height[id]);
  const TextureWrap wrap = TextureWrap(t.wrap[id]);
  if (TextureFilter(t.filter[id]) == TextureFilter::kNearest) {
    const float x = std::floor(ClampTexel(st.x * float(w))),
                y = std::floor(ClampTexel(st.y * float(h)));
    return Texel(t, id, WrapTexel(int32_t(x), w, wrap), WrapTexel(int32_t(y), h, wrap));
  }
  const float x = ClampTexel(st.x * float(w) - 0.5f), y = ClampTexel(st.y * float(h) - 0.5f);
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int32_t ix = int32_t(x0), iy = int32_t(y0);
  const int32_t xa = WrapTexel(ix, w, wrap), xb = WrapTexel(ix + 1, w, wrap);
  const int32_t ya = WrapTexel(iy, h, wrap), yb = WrapTexel(iy + 1, h, wrap);
  const Color3f t00 = Texel(t, id, xa, ya), t10 = Texel(t, id, xb, ya);
  const Color3f t01 = Texel(t, id, xa, yb), t11 = Texel(t, id, xb, yb);
  const float gx = 1.0f - fx, gy = 1.0f - fy;
  const auto blend = [&](float a00, float a10, float a01, float a11) {
    return (a00 * gx + a10 * fx) * gy + (a01 * gx + a11 * fx) * fy;
  };
  return {blend(t00.r, t10.r, t01.r, t11.r), blend(t00.g, t10.g, t01.g, t11.g),
          blend(t00.b, t10.b, t01.b, t11.b)};
}

Color3f Checkerboard(const TextureTable& t, uint32_t id, const Vec2f& uv) {
  const Vec2f st = ToUv(t, id, uv);
  const float u = ClampTexel(st.x), v = ClampTexel(st.y);
  const bool mu = u - std::floor(u) > 0.5f, mv = v - std::floor(v) > 0.5f;
  const float* c = &t.data[t.offset[id] + (mu == mv ? 0 : 3)];
  return {c[0], c[1], c[2]};
}

// The row's triangle index of prim, or -1 when prim is not one of its triangles.
int64_t AttributeRow(const TextureTable& t, uint32_t id, uint32_t prim) {
  if (IsSphereHit(prim) || prim < t.width[id] || prim - t.width[id] >= t.height[id]) return -1;
  return int64_t(prim - t.width[id]);
}

Color3f FaceAttribute(const TextureTable& t, uint32_t id, const TexturePoint& at) {
  const int64_t row = AttributeRow(t, id, at.prim);
  if (row < 0) return {};
  const float* c = &t.data[t.offset[id] + size_t(row) * 3];
  return {c[0], c[1], c[2]};
}

Color3f VertexAttribute(const TextureTable& t, uint32_t id, const TexturePoint& at) {
  const int64_t row = AttributeRow(t, id, at.prim);
  if (row < 0) return {};
  const float* c = &t.data[t.offset[id] + size_t(row) * kVertexAttributeFloats];
  const float dx = at.p.x - c[0], dy = at.p.y - c[1], dz = at.p.z - c[2];
  float out[3];
  for (int k = 0; k < 3; ++k) {
    const float* a = c + 3 + 4 * k;
    out[k] = a[0] + ((a[1] * dx + a[2] * dy) + a[3] * dz);
  }
  return {out[0], out[1], out[2]};
}

}  // namespace

int32_t WrapTexel(int32_t i, int32_t size, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::kClamp:
      return std::clamp(i, 0, size - 1);
    case TextureWrap::kRepeat: {
      const int32_t r = i % size;
      return r < 0 ? r + size : r;
    }
    case TextureWrap::kMirror: {
      int32_t r = i % (2 * size);
      if (r < 0) r += 2 * size;
      return r < size ? r : 2 * size - 1 - r;
    }
  }
  return 0;
}

Color3f EvalTexture(const TextureTable& t, uint32_t id, const TexturePoint& at) {
  switch (t.Kind(id)) {
    case TextureKind::kBitmap:
      return Bitmap(t, id, at.uv);
    case TextureKind::kCheckerboard:
      return Checkerboard(t, id, at.uv);
    case TextureKind::kFaceAttribute:
      return FaceAttribute(t, id, at);
    case TextureKind::kVertexAttribute:
      return VertexAttribute(t, id, at);
  }
  return {};
}

void EvalTextureBatch(const TextureTable& t, const uint32_t* id, const TexturePointArrays& at,
                      size_t n, float* r, float* g, float* b) {
  for (size_t i = 0; i < n; ++i) {
    const TexturePoint p{{at.u[i], at.v[i]}, {at.p_x[i], at.p_y[i], at.p_z[i]}, at.prim[i]};
    const Color3f c = EvalTexture(t, id[i], p);
    r[i] = c.r, g[i] = c.g, b[i] = c.b;
  }
}

}  // namespace ptlab
