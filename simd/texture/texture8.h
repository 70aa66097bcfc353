// Vectorized texture lookup (plain API): the SIMD twin of EvalTexture (engine/texture/texture.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/texture/texture.h"

namespace ptlab::simd {

/// ptlab::EvalTextureBatch eight rows per vector (hn::CappedTag<float, 8>), each row its own
/// texture (kind, wrap and filter per lane; the texels, colors and attribute values gathered).
/// Rows with id kNoTexture get 0 (the oracle may not be called with them). Contract:
/// bit-identical to the oracle on every compiled target, for any finite uv and p (uv far
/// outside [0, 1], negative, on texel borders; 1×1 bitmaps): the same float operations in
/// the same order, products rounded before each add, and the integer wrap computed exactly.
/// tests/simd/texture/texture8_test.cpp.
void EvalTextureBatch(const TextureTable& t, const uint32_t* id, const TexturePointArrays& at,
                      size_t n, float* r, float* g, float* b);

}  // namespace ptlab::simd
