// Textured parameters: a material parameter that a per-row texture-id column may drive.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/check.h"
#include "engine/core/frame.h"  // normal
#include "engine/texture/texture.h"

namespace ptlab {

/// The scene's textures at one shading point; textures == nullptr in a scene without textures
/// (then no textured parameter exists and none is read).
struct TextureSite {
  const TextureTable* textures = nullptr;
  TexturePoint at;
  // normal: the shading point's frame and unit geometric normal (world, from its
  // SurfaceInteraction), which a row's normal or bump map reads (engine/bsdf/perturbed_frame.h);
  // frame_perturbed: the call is already inside that wrapper (the nested row's own BSDF).
  const Frame* frame = nullptr;
  const Vec3f* ng = nullptr;
  bool frame_perturbed = false;
};

/// Row i's value of a color parameter that may be textured: `constant` unless the parameter's
/// texture-id column (empty while no row of the table is textured) names a texture for row i;
/// then that texture at `site`, each channel clamped to ≥ 0 (a textured parameter is never
/// negative). The pattern every textured BSDF parameter follows (docs/materials.md).
inline Color3f TexturedColor(const AlignedVector<uint32_t>& texture, size_t i,
                             const Color3f& constant, const TextureSite& site) {
  if (texture.empty() || texture[i] == kNoTexture) return constant;
  PTLAB_CHECK(site.textures != nullptr);
  const Color3f c = EvalTexture(*site.textures, texture[i], site.at);
  return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
}

/// Row i's value of a scalar parameter that may be textured (roughness, opacity, a blend
/// weight, ...): `constant` unless the texture-id column names a texture for row i; then the
/// luminance of that texture at `site` (Mitsuba 3's `eval_1`: a one-channel texture stored as
/// equal r = g = b gives its value, since the luminance weights sum to 1), clamped to ≥ 0.
inline float TexturedFloat(const AlignedVector<uint32_t>& texture, size_t i, float constant,
                           const TextureSite& site) {
  if (texture.empty() || texture[i] == kNoTexture) return constant;
  PTLAB_CHECK(site.textures != nullptr);
  return std::max(Luminance(EvalTexture(*site.textures, texture[i], site.at)), 0.0f);
}

// mask: a scalar parameter in [0, 1] (a mask's opacity, a blend's weight): TexturedFloat
// clipped to [0, 1] as Mitsuba clips them (NaN → 1).
inline float TexturedUnitFloat(const AlignedVector<uint32_t>& texture, size_t i, float constant,
                               const TextureSite& site) {
  const float v = TexturedFloat(texture, i, constant, site);
  return v < 1.0f ? (v > 0.0f ? v : 0.0f) : 1.0f;
}

}  // namespace ptlab
