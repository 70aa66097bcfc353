// Emission sampling for light subpaths (see emission.h).
#include "engine/light/emission.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/frame.h"
#include "engine/light/area_light.h"
#include "engine/light/infinite_light.h"
#include "engine/light/projector.h"
#include "engine/light/spot_light.h"
#include "engine/render/interaction.h"
#include "engine/sampling/warp.h"
#include "engine/scene/world_bounds.h"

namespace ptlab {
namespace {

// Uniform density over a spot's cone of half-angle acos(cos_half), in solid angle.
float ConePdf(float cos_half) { return 1.0f / (2.0f * kPi * std::max(1e-7f, 1.0f - cos_half)); }

// The point where a ray of direction w from an infinitely distant emitter starts: on the disk
// of the scene sphere perpendicular to w, one radius back towards the emitter.
Vec3f DiskOrigin(const SceneSphere& sphere, const Vec3f& w, const Vec2f& u) {
  const Frame frame(-w);
  const Vec2f d = SampleConcentricDisk(u);
  return sphere.center + (frame.n + frame.s * d.x + frame.t * d.y) * sphere.radius;
}

float DiskPdf(const SceneSphere& sphere) {
  return 1.0f / (kPi * sphere.radius * sphere.radius);
}

// The projector's frustum direction w (world, unit) in its frame: false outside.
bool ProjectorLocal(const ProjectorTable& t, uint32_t i, const Vec3f& w, Vec3f* local) {
  *local = t.to_world[i].ToLocal(w);
  return local->z > 0 && std::abs(local->x) <= local->z * t.tan_half_x[i] &&
         std::abs(local->y) <= local->z * t.tan_half_y[i];
}

}  // namespace

SceneSphere BoundingSphereOf(const Scene& scene) {
  SceneSphere s;
  Vec3f lo, hi;
  if (!WorldBounds(scene, &lo, &hi)) return s;
  s.center = (lo + hi) * 0.5f;
  // A little margin, so that the disk lies outside every surface it shines on.
  s.radius = std::max(1e-3f, 0.5f * Length(hi - lo) * 1.001f);
  return s;
}

Color3f DeltaLightIntensity(const Scene& scene, EmitterRef e, const Vec3f& w) {
  const uint32_t i = e.index();
  if (e.tag() == EmitterTag::kPoint) return scene.point_lights.power[i] * (0.25f * kInvPi);
  if (e.tag() == EmitterTag::kSpot) return SpotIntensity(scene, i, w);
  if (e.tag() != EmitterTag::kProjector) return {};
  // ProjectorRadianceAt's E π scale / (z² cos θ) is I / r² with I = E π scale / cos³ θ.
  const ProjectorTable& t = scene.projectors;
  Vec3f local;
  if (!ProjectorLocal(t, i, w, &local)) return {};
  const float inv_z = 1.0f / local.z;
  const Vec2f uv{0.5f - 0.5f * local.x * inv_z / t.tan_half_x[i],
                 0.5f - 0.5f * local.y * inv_z / t.tan_half_y[i]};
  return ProjectorIrradiance(t, scene.textures, i, uv) *
         (kPi * t.scale[i] * inv_z * inv_z * inv_z);
}

bool SampleEmission(const Scene& scene, const SceneSphere& sphere, EmitterRef e,
                    const Vec2f& u_pos, const Vec2f& u_dir, EmissionSample* out) {
  if (!e.valid()) return false;
  *out = EmissionSample{};
  const uint32_t i = e.index();
  switch (e.tag()) {
    case EmitterTag::kArea: {
      const AreaLightTable& lights = scene.area_lights;
      if (!(lights.area[i] > 0) || IsBlack(lights.radiance[i])) return false;
      const AreaLightTrianglePick pick = PickAreaLightTriangle(scene, i, u_pos.x);
      const TriangleTable& t = scene.triangles;
      const Vec2f b = SampleUniformTriangle({pick.u_x, u_pos.y});
      out->p = t.V0(pick.tri) * (1.0f - b.x - b.y) + t.V1(pick.tri) * b.x + t.V2(pick.tri) * b.y;
      out->n = ShadingNormalAt(scene, pick.tri, b.x, b.y);
      const Vec3f ng = Cross(t.V1(pick.tri) - t.V0(pick.tri), t.V2(pick.tri) - t.V0(pick.tri));
      out->ng = Length(ng) > 0 ? Normalize(ng) : out->n;
      out->prim = pick.tri;
      const Vec3f local = SampleCosineHemisphere(u_dir);
      if (!(local.z > 0)) return false;
      out->w = Frame(out->n).ToWorld(local);
      out->radiance =
          AreaLightRadianceAt(scene, i, TexturePoint{SurfaceUvAt(scene, pick.tri, b.x, b.y),
                                                     out->p, pick.tri});
      out->pdf_pos = 1.0f / lights.area[i];
      out->pdf_dir = local.z * kInvPi;
      return true;
    }
    case EmitterTag::kPoint:
    case EmitterTag::kSpot: {
      const bool spot = e.tag() == EmitterTag::kSpot;
      out->p = spot ? scene.spot_lights.position[i] : scene.point_lights.position[i];
      out->delta_position = true;
      out->pdf_pos = 1.0f;
      if (!spot) {
        out->w = SampleUniformSphere(u_dir);
        out->pdf_dir = kInv4Pi;
      } else {
        // Uniform in cos θ over [cos_half, 1]: uniform over the cone's solid angle.
        const float cos_half = scene.spot_lights.cos_half_angle[i];
        const float cos_t = 1.0f - u_dir.x * (1.0f - cos_half);
        const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
        const float phi = 2.0f * kPi * u_dir.y;
        out->w = Frame(scene.spot_lights.axis[i])
                     .ToWorld({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
        out->pdf_dir = ConePdf(cos_half);
      }
      out->radiance = DeltaLightIntensity(scene, e, out->w);
      return !IsBlack(out->radiance);
    }
    case EmitterTag::kDirectional: {
      out->w = scene.directional_lights.direction[i];
      out->radiance = scene.directional_lights.radiance[i];
      out->p = DiskOrigin(sphere, out->w, u_pos);
      out->pdf_pos = DiskPdf(sphere);
      out->pdf_dir = 1.0f;
      out->infinite = out->delta_direction = true;
      return !IsBlack(out->radiance);
    }
    case EmitterTag::kEnvironment:
    case EmitterTag::kDistantDisk: {
      EnvironmentSample es;
      if (!SampleInfiniteLight(scene, e, u_dir, &es) || !(es.pdf > 0)) return false;
      out->w = -es.wi;
      out->radiance = es.radiance;
      out->p = DiskOrigin(sphere, out->w, u_pos);
      out->pdf_pos = DiskPdf(sphere);
      out->pdf_dir = es.pdf;
      out->infinite = true;
      return !IsBlack(out->radiance);
    }
    case EmitterTag::kProjector: {
      // A point uniform on the image window at z = 1, (±tan_half_x, ±tan_half_y): density
      // 1 / (4 tan_half_x tan_half_y) there, 1 / (4 tan_half_x tan_half_y cos³ θ) in solid angle.
      const ProjectorTable& t = scene.projectors;
      out->p = t.position[i];
      out->n = t.to_world[i].n;
      out->delta_position = true;
      out->pdf_pos = 1.0f;
      const Vec3f local{(2.0f * u_dir.x - 1.0f) * t.tan_half_x[i],
                        (2.0f * u_dir.y - 1.0f) * t.tan_half_y[i], 1.0f};
      out->w = t.to_world[i].ToWorld(Normalize(local));
      float pdf_pos;
      EmissionPdf(scene, sphere, e, out->n, out->w, &pdf_pos, &out->pdf_dir);
      out->radiance = DeltaLightIntensity(scene, e, out->w);
      return out->pdf_dir > 0 && !IsBlack(out->radiance);
    }
  }
  return false;
}

void EmissionPdf(const Scene& scene, const SceneSphere& sphere, EmitterRef e, const Vec3f& n,
                 const Vec3f& w, float* pdf_pos, float* pdf_dir) {
  *pdf_pos = *pdf_dir = 0.0f;
  if (!e.valid()) return;
  const uint32_t i = e.index();
  switch (e.tag()) {
    case EmitterTag::kArea: {
      if (!(scene.area_lights.area[i] > 0)) return;
      *pdf_pos = 1.0f / scene.area_lights.area[i];
      *pdf_dir = std::max(0.0f, Dot(n, w)) * kInvPi;
      return;
    }
    case EmitterTag::kPoint:
      *pdf_pos = 1.0f;
      *pdf_dir = kInv4Pi;
      return;
    case EmitterTag::kSpot:
      *pdf_pos = 1.0f;
      *pdf_dir = Dot(w, scene.spot_lights.axis[i]) > scene.spot_lights.cos_half_angle[i]
                     ? ConePdf(scene.spot_lights.cos_half_angle[i])
                     : 0.0f;
      return;
    case EmitterTag::kDirectional:
      *pdf_pos = DiskPdf(sphere);
      *pdf_dir = 1.0f;
      return;
    case EmitterTag::kEnvironment:
    case EmitterTag::kDistantDisk:
      *pdf_pos = DiskPdf(sphere);
      *pdf_dir = InfiniteLightPdf(scene, e, -w);
      return;
    case EmitterTag::kProjector: {
      const ProjectorTable& t = scene.projectors;
      Vec3f local;
      *pdf_pos = 1.0f;
      if (!ProjectorLocal(t, i, w, &local)) return;
      const float cos3 = local.z * local.z * local.z;  // w is unit: z = cos θ
      *pdf_dir = 1.0f / (4.0f * t.tan_half_x[i] * t.tan_half_y[i] * cos3);
      return;
    }
  }
}

}  // namespace ptlab
