// Texture evaluation, the scalar oracle (SIMD twin: simd/texture/texture8.h): the value of a
// texture row of TextureTable at a shading point.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// Where a texture is evaluated: the shading point's surface coordinates, world position and
/// primitive (SurfaceInteraction's uv, p and prim).
struct TexturePoint {
  Vec2f uv;
  Vec3f p;
  uint32_t prim = 0;
};

/// Texel coordinates beyond ±kMaxTexelCoordinate (uv' × size) are clamped there (uv that far
/// out is already meaningless in float: its fraction is gone); NaN counts as −kMaxTexelCoordinate.
inline constexpr float kMaxTexelCoordinate = 16777216.0f;  // 2^24

/// The texel index `i` (any int32) of a texture `size` texels wide under `wrap`: repeat = i mod
/// size, clamp to [0, size − 1], mirror = i mod 2·size folded back (size ≤ i' < 2·size →
/// 2·size − 1 − i').
int32_t WrapTexel(int32_t i, int32_t size, TextureWrap wrap);

/// Value of texture `id` at `at` (linear RGB, Mitsuba 3's semantics):
/// - bitmap: uv' = to_uv(uv); x = u'·width, y = v'·height, texel (0, 0) at the image's top left
///   (Mitsuba flips OBJ's v when it loads the mesh, not here). Nearest: texel (⌊x⌋, ⌊y⌋)
///   wrapped. Bilinear: x − 0.5, y − 0.5 split into ⌊·⌋ and fraction f; the four wrapped
///   texels t00, t10 (x + 1), t01 (y + 1), t11 blended as
///   (t00 (1 − fx) + t10 fx) (1 − fy) + (t01 (1 − fx) + t11 fx) fy.
/// - checkerboard: uv' = to_uv(uv); color0 where (frac u' > ½) == (frac v' > ½), else color1.
/// - face attribute: the triangle's value; vertex attribute: the plane through the corners'
///   values at p (the barycentric interpolation, exact up to rounding). 0 on a triangle
///   outside the row's mesh or a sphere.
/// Finite in, finite out (the table's data is finite: the loaders replace NaN/Inf texels by 0).
Color3f EvalTexture(const TextureTable& t, uint32_t id, const TexturePoint& at);

/// SoA view of n texture points (SIMD batch form).
struct TexturePointArrays {
  const float* u = nullptr;
  const float* v = nullptr;
  const float* p_x = nullptr;
  const float* p_y = nullptr;
  const float* p_z = nullptr;
  const uint32_t* prim = nullptr;
};

/// r, g, b[i] = EvalTexture(t, id[i], point i): the oracle of simd::EvalTextureBatch.
void EvalTextureBatch(const TextureTable& t, const uint32_t* id, const TexturePointArrays& at,
                      size_t n, float* r, float* g, float* b);

}  // namespace ptlab
