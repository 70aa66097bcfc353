// normal: the uv gradient of a texture's luminance, what a bump map reads (Mitsuba 3's
// eval_1_grad of its bitmap).
#pragma once

#include <cstdint>

#include "engine/core/vec.h"
#include "engine/texture/texture.h"

namespace ptlab {

/// (∂f/∂u, ∂f/∂v) of f = Luminance(EvalTexture(t, id, at)) at at.uv, as Mitsuba 3's bitmap
/// eval_1_grad: for a bilinear bitmap the derivative of the bilinear blend inside the texel
/// cell (the four texels' luminances f00, f10, f01, f11 and fractions fx, fy of EvalTexture):
///   ∂f/∂x = (1 − fy)(f10 − f00) + fy (f11 − f01),  ∂f/∂y = (1 − fx)(f01 − f00) + fx (f11 − f10)
/// in texels, then through x = width · u', y = height · v' and uv' = to_uv(uv) (the chain rule;
/// Mitsuba scales after the transpose of to_uv, the same for every to_uv without rotation or
/// shear). Zero for a nearest-filtered bitmap (piecewise constant), a checkerboard (constant
/// a.e.) and the mesh attributes (not functions of uv). Finite in, finite out.
Vec2f EvalTextureGradient(const TextureTable& t, uint32_t id, const TexturePoint& at);

}  // namespace ptlab
