// The mean colour of a texture over its uv square: what a textured emitter's selection power
// uses.
#pragma once

#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// Mean linear RGB of texture `id` over one period of uv: a bitmap's texel mean, the two
/// colours' mean of a checkerboard. Mesh attributes have no uv square: black.
Color3f TextureMean(const TextureTable& t, uint32_t id);

}  // namespace ptlab
