// Spot lights: the radiant intensity a spot sends in a direction (cone, Mitsuba's linear
// falloff ramp, and its projected texture).
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/core/vec.h"
#include "engine/scene/scene.h"
#include "engine/texture/texture.h"

namespace ptlab {

/// The uv at which spot i's texture is read for unit direction w (world, leaving the light):
/// 0.5 + 0.5 (x, y) / (z tan cutoff) with (x, y, z) = w in the light's texture_frame (Mitsuba
/// 3's spot, src/emitters/spot.cpp: the cone inscribed in the texture's square). Requires a
/// textured row and z > 0.
inline Vec2f SpotTextureUv(const SpotLightTable& t, uint32_t i, const Vec3f& w) {
  const Vec3f local = t.texture_frame[i].ToLocal(w);
  const float scale = 0.5f / (local.z * std::tan(t.cutoff[i]));
  return {0.5f + local.x * scale, 0.5f + local.y * scale};
}

/// Radiant intensity (W/sr per channel) of spot i towards unit direction w (world, leaving
/// the light): intensity · cos(θ)^exponent · ramp(θ) · texture(uv) inside the cone, black
/// outside (SpotLightTable). Every evaluation of a spot's emission goes through here.
inline Color3f SpotIntensity(const Scene& scene, uint32_t i, const Vec3f& w) {
  const SpotLightTable& t = scene.spot_lights;
  const float cos_theta = Dot(w, t.axis[i]);
  if (!(cos_theta > t.cos_half_angle[i])) return {};
  float falloff = std::pow(cos_theta, t.exponent[i]);
  if (cos_theta < t.cos_beam[i])
    falloff *= std::max((t.cutoff[i] - std::acos(cos_theta)) * t.inv_transition[i], 0.0f);
  Color3f intensity = t.intensity[i] * falloff;
  if (!t.texture.empty() && t.texture[i] != kNoTexture)
    intensity = intensity * EvalTexture(scene.textures, t.texture[i],
                                        TexturePoint{SpotTextureUv(t, i, w), t.position[i], 0});
  return intensity;
}

}  // namespace ptlab
