// Delta emitters (point, directional, spot lights, projectors): the one direction each lights a
// point from.
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/core/vec.h"
#include "engine/light/projector.h"
#include "engine/light/spot_light.h"
#include "engine/scene/refs.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// True for the emitters that BSDF sampling can never reach (their pdf in solid angle is a
/// Dirac delta): they are sampled without MIS, weighted by the probability of choosing them.
constexpr bool IsDeltaLight(EmitterRef e) {
  return e.valid() && (e.tag() == EmitterTag::kPoint || e.tag() == EmitterTag::kDirectional ||
                       e.tag() == EmitterTag::kSpot || e.tag() == EmitterTag::kProjector);
}

/// The light a delta emitter sends to a point: from direction wi (world, unit, towards the
/// light), `radiance` = what an estimator multiplies by f·|cos θi| (intensity / r² for point and
/// spot lights, the directional light's radiance). A finite light sits at `position`; an
/// infinitely distant one (directional) has `infinite` set and no position.
struct DeltaLightSample {
  Vec3f wi;
  Color3f radiance;
  Vec3f position;
  bool infinite = false;
};

/// The sample of delta emitter e at world point p. False when it sends p nothing (p on the
/// light, outside a spot's cone or a projector's frustum) or for any other emitter.
inline bool SampleDeltaLight(const Scene& scene, EmitterRef e, const Vec3f& p,
                             DeltaLightSample* out) {
  const uint32_t i = e.index();
  switch (e.tag()) {
    case EmitterTag::kDirectional:
      out->wi = -scene.directional_lights.direction[i];
      out->radiance = scene.directional_lights.radiance[i];
      out->infinite = true;
      return true;
    case EmitterTag::kPoint:
    case EmitterTag::kSpot: {
      const bool spot = e.tag() == EmitterTag::kSpot;
      out->position = spot ? scene.spot_lights.position[i] : scene.point_lights.position[i];
      const Vec3f d = out->position - p;
      const float dist2 = Dot(d, d);
      if (!(dist2 > 0)) return false;
      out->wi = d / std::sqrt(dist2);
      out->infinite = false;
      if (!spot) {
        const Color3f intensity = scene.point_lights.power[i] * (0.25f * kInvPi);
        out->radiance = intensity * (1.0f / dist2);
        return true;
      }
      out->radiance = SpotIntensity(scene, i, -out->wi) * (1.0f / dist2);
      return !IsBlack(out->radiance);
    }
    case EmitterTag::kProjector: {
      const ProjectorTable& t = scene.projectors;
      out->position = t.position[i];
      const Vec3f d = out->position - p;
      const float dist2 = Dot(d, d);
      if (!(dist2 > 0) || !ProjectorRadianceAt(t, scene.textures, i, p, &out->radiance))
        return false;
      out->wi = d / std::sqrt(dist2);
      out->infinite = false;
      return true;
    }
    case EmitterTag::kArea:
    case EmitterTag::kEnvironment:
    case EmitterTag::kDistantDisk:
      return false;
  }
  return false;  // an invalid ref
}

}  // namespace ptlab
