// Mitsuba's projector emitter: a pinhole that projects an image (irradiance on its virtual
// image plane z = 1) into the scene.
#pragma once

#include <cmath>

#include "engine/core/vec.h"
#include "engine/scene/emitter_tables.h"
#include "engine/texture/texture.h"

namespace ptlab {

/// The irradiance of projector i's image at image coordinates uv in [0, 1]² (v = 0 at the top,
/// u = 0 on the image's left, which is the projector's local +x side, as a camera's film).
/// Every lookup of the image goes through here: the constant `irradiance`, or the row's
/// texture at uv (Mitsuba's bitmap lookup: uv (0, 0) is the image's top-left corner).
inline Color3f ProjectorIrradiance(const ProjectorTable& t, const TextureTable& textures,
                                   uint32_t i, const Vec2f& uv) {
  if (t.texture.empty() || t.texture[i] == kNoTexture) return t.irradiance[i];
  return EvalTexture(textures, t.texture[i], TexturePoint{uv, t.position[i], 0});
}

/// What projector i sends to world point p: the factor that an estimator multiplies by
/// f·|cos θi| (the analogue of a point light's intensity / r²). False when p is outside the
/// frustum or behind the pinhole. With p_local = (x, y, z) in the projector's frame, r = |p -
/// position| and cos θ = z / r, it is E(uv) · π · scale / (z² cos θ): a plane at z = 1 facing
/// the projector receives exactly the image's irradiance π·scale·E(uv) (Mitsuba 3's
/// projector, src/emitters/projector.cpp, defines the π and the scale this way).
inline bool ProjectorRadianceAt(const ProjectorTable& t, const TextureTable& textures, uint32_t i,
                                const Vec3f& p, Color3f* radiance) {
  const Vec3f d = p - t.position[i];
  const Vec3f local = t.to_world[i].ToLocal(d);
  if (!(local.z > 0)) return false;
  const float inv_z = 1.0f / local.z;
  const Vec2f uv{0.5f - 0.5f * local.x * inv_z / t.tan_half_x[i],
                 0.5f - 0.5f * local.y * inv_z / t.tan_half_y[i]};
  if (!(uv.x >= 0 && uv.x <= 1 && uv.y >= 0 && uv.y <= 1)) return false;
  const float dist = Length(d);
  // 1 / (z² cos θ) = r / z³.
  const float geometry = dist * inv_z * inv_z * inv_z;
  *radiance = ProjectorIrradiance(t, textures, i, uv) * (kPi * t.scale[i] * geometry);
  return true;
}

}  // namespace ptlab
