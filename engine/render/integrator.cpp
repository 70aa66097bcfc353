// Scalar integrators (the oracle): normals, direct_{ems,mats,mis}, whitted, path_{mats,ems,mis}.
#include "engine/render/integrator.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/light/area_light.h"
#include "engine/render/interaction.h"

namespace ptlab {
namespace {

using Type = IntegratorDesc::Type;

// Nori's Whitted integrator continues specular chains with probability 0.95.
constexpr float kWhittedContinuation = 0.95f;
// Recursion guard for the Whitted integrator (paths this long carry ~0.95^64 of the weight).
constexpr int kWhittedMaxDepth = 64;

Vec2f Next2D(Pcg32& rng) {
  const float a = rng.NextFloat();
  return {a, rng.NextFloat()};
}

// Origin of a ray leaving its.p toward direction w, pushed off the surface on w's side.
Vec3f SpawnOrigin(const SurfaceInteraction& its, const Vec3f& w) {
  return OffsetRayOrigin(its.p, Dot(its.ng, w) >= 0 ? its.ng : -its.ng);
}

bool Trace(const RenderContext& ctx, const Ray& ray, Hit* hit, RayCounters* c) {
  ++c->rays;
  return Intersect1(ctx.bvh, ray, hit);
}

// Radiance emitted by the surface at its toward direction w (unit, away from the surface).
Color3f Emitted(const Scene& scene, const SurfaceInteraction& its, const Vec3f& w) {
  if (!its.emitter.valid() || its.emitter.tag() != EmitterTag::kArea) return {};
  return AreaLightRadiance(scene.area_lights.radiance[its.emitter.index()], its.frame.n, w);
}

// Solid-angle density with which emitter sampling (one emitter chosen uniformly, a point
// uniform by area) produces the point `its` on a light seen from `from`.
float EmitterPdf(const Scene& scene, const SurfaceInteraction& its, const Vec3f& from) {
  if (!its.emitter.valid() || its.emitter.tag() != EmitterTag::kArea) return 0.0f;
  const Vec3f d = its.p - from;
  const float dist2 = Dot(d, d);
  const float cos_l = -Dot(its.frame.n, d) / std::sqrt(dist2);
  if (cos_l <= 0) return 0.0f;
  const float area = scene.area_lights.area[its.emitter.index()];
  return dist2 / (cos_l * area * float(scene.emitters.size()));
}

// MIS weight of a strategy with density pdf_a against one with density pdf_b (one sample
// each): the balance heuristic, or Veach's power heuristic with exponent 2.
float MisWeight(float pdf_a, float pdf_b, bool power) {
  if (power) {
    pdf_a *= pdf_a;
    pdf_b *= pdf_b;
  }
  const float sum = pdf_a + pdf_b;
  return sum > 0 ? pdf_a / sum : 0.0f;
}

// One emitter sample for the direct light at its (wo: local direction to the viewer).
// With mis, the sample is weighted against BSDF sampling (balance or power heuristic).
Color3f SampleEmitterDirect(const RenderContext& ctx, const SurfaceInteraction& its,
                            const Vec3f& wo, bool mis, Pcg32& rng, RayCounters* c) {
  const Scene& scene = ctx.scene;
  const size_t n = scene.emitters.size();
  if (n == 0) return {};
  const size_t k = std::min(n - 1, size_t(rng.NextFloat() * float(n)));
  const float u_tri = rng.NextFloat();
  const Vec2f u = Next2D(rng);
  const EmitterRef emitter = scene.emitters[k];
  if (emitter.tag() != EmitterTag::kArea) return {};
  const AreaLightSample ls = SampleAreaLight(scene, emitter.index(), u_tri, u);
  const Vec3f d = ls.p - its.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0) || !(ls.pdf_area > 0)) return {};
  const Vec3f wi = d / std::sqrt(dist2);
  const float cos_l = -Dot(ls.n, wi);
  if (cos_l <= 0) return {};
  const Vec3f wi_local = its.frame.ToLocal(wi);
  const Color3f f = BsdfEval(scene.materials, its.material, wo, wi_local);
  if (IsBlack(f)) return {};
  // Shadow ray between the two offset points; d is not normalised, so t runs over [0, 1).
  Ray shadow;
  shadow.o = SpawnOrigin(its, wi);
  const Vec3f target = OffsetRayOrigin(ls.p, Dot(ls.ng, wi) <= 0 ? ls.ng : -ls.ng);
  shadow.d = target - shadow.o;
  shadow.t_min = 0.0f;
  shadow.t_max = 1.0f;
  ++c->rays;
  if (Occluded1(ctx.bvh, shadow)) return {};
  const float pdf_light = ls.pdf_area * dist2 / (cos_l * float(n));
  float weight = 1.0f;
  if (mis) {
    const float pdf_bsdf = BsdfPdf(scene.materials, its.material, wo, wi_local);
    weight = MisWeight(pdf_light, pdf_bsdf, scene.integrator.power_heuristic);
  }
  return f * ls.radiance * (AbsCosTheta(wi_local) * weight / pdf_light);
}

Color3f LiNormals(const RenderContext& ctx, const Ray& ray, RayCounters* c) {
  Hit hit;
  if (!Trace(ctx, ray, &hit, c)) return {};
  const Vec3f n = Abs(MakeInteraction(ctx.scene, hit).frame.n);
  return {n.x, n.y, n.z};
}

// Direct illumination: Le at the first hit plus one bounce of emitter and/or BSDF sampling.
Color3f LiDirect(const RenderContext& ctx, const Ray& ray, Type type, Pcg32& rng,
                 RayCounters* c) {
  const Scene& scene = ctx.scene;
  Hit hit;
  if (!Trace(ctx, ray, &hit, c)) return {};
  const SurfaceInteraction its = MakeInteraction(scene, hit);
  const Vec3f wo_world = -ray.d / Length(ray.d);
  Color3f L = Emitted(scene, its, wo_world);
  const Vec3f wo = its.frame.ToLocal(wo_world);
  const bool mis = type == Type::kDirectMis;
  if (type != Type::kDirectMats) L += SampleEmitterDirect(ctx, its, wo, mis, rng, c);
  if (type == Type::kDirectEms) return L;

  BsdfSample bs;
  const float u1 = rng.NextFloat();
  if (!BsdfSampleDirection(scene.materials, its.material, wo, u1, Next2D(rng), &bs)) return L;
  const Vec3f wi = its.frame.ToWorld(bs.wi);
  Ray next{SpawnOrigin(its, wi), wi, 0.0f, 1e30f};
  Hit hit2;
  if (!Trace(ctx, next, &hit2, c)) return L;
  const SurfaceInteraction light = MakeInteraction(scene, hit2);
  const Color3f Le = Emitted(scene, light, -wi);
  if (IsBlack(Le)) return L;
  float weight = 1.0f;
  if (mis && !bs.delta) {
    const float pdf_light = EmitterPdf(scene, light, its.p);
    weight = MisWeight(bs.pdf, pdf_light, scene.integrator.power_heuristic);
  }
  return L + bs.weight * Le * weight;
}

// Whitted: emitter sampling on non-specular surfaces, recursion through delta lobes with
// Russian roulette (continuation 0.95, Nori's definition).
Color3f LiWhitted(const RenderContext& ctx, const Ray& ray, int depth, Pcg32& rng,
                  RayCounters* c) {
  const Scene& scene = ctx.scene;
  Hit hit;
  if (!Trace(ctx, ray, &hit, c)) return {};
  const SurfaceInteraction its = MakeInteraction(scene, hit);
  const Vec3f wo_world = -ray.d / Length(ray.d);
  const Color3f Le = Emitted(scene, its, wo_world);
  const Vec3f wo = its.frame.ToLocal(wo_world);
  if (!IsDeltaMaterial(its.material.tag())) {
    return Le + SampleEmitterDirect(ctx, its, wo, /*mis=*/false, rng, c);
  }
  if (depth >= kWhittedMaxDepth || rng.NextFloat() >= kWhittedContinuation) return Le;
  BsdfSample bs;
  const float u1 = rng.NextFloat();
  if (!BsdfSampleDirection(scene.materials, its.material, wo, u1, Next2D(rng), &bs)) return Le;
  const Vec3f wi = its.frame.ToWorld(bs.wi);
  const Ray next{SpawnOrigin(its, wi), wi, 0.0f, 1e30f};
  return Le + bs.weight * LiWhitted(ctx, next, depth + 1, rng, c) * (1.0f / kWhittedContinuation);
}

// Path tracing with BSDF sampling only (mats), next-event estimation (ems), or both combined
// by MIS. Russian roulette as in Nori: after 3 bounces continue with probability
// min(max(throughput) η², 0.99). max_depth follows CS184: 0 = emitted light only,
// 1 = direct lighting, ...; negative = unbounded.
Color3f LiPath(const RenderContext& ctx, Ray ray, Type type, Pcg32& rng, RayCounters* c) {
  const Scene& scene = ctx.scene;
  const IntegratorDesc& desc = scene.integrator;
  const bool nee = type != Type::kPathMats, mis = type == Type::kPathMis;
  Color3f L, throughput{1, 1, 1};
  float eta = 1.0f;
  bool specular_bounce = true;  // the camera ray counts as specular: emission is always seen
  float prev_pdf = 0.0f;        // BSDF pdf of the bounce that produced `ray`
  Vec3f prev_p;
  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!Trace(ctx, ray, &hit, c)) break;
    const SurfaceInteraction its = MakeInteraction(scene, hit);
    const Vec3f wo_world = -ray.d / Length(ray.d);
    const Color3f Le = Emitted(scene, its, wo_world);
    if (!IsBlack(Le)) {
      float w = 1.0f;
      if (nee && !specular_bounce) {
        // Emitter sampling already counted this light from the previous vertex.
        w = mis ? MisWeight(prev_pdf, EmitterPdf(scene, its, prev_p), desc.power_heuristic)
                : 0.0f;
      }
      L += throughput * Le * w;
    }
    if (desc.max_depth >= 0 && depth >= desc.max_depth) break;
    const Vec3f wo = its.frame.ToLocal(wo_world);
    const bool delta = IsDeltaMaterial(its.material.tag());
    if (nee && !delta) {
      Color3f direct;
      const int n = std::max(1, desc.light_samples);
      for (int i = 0; i < n; ++i) direct += SampleEmitterDirect(ctx, its, wo, mis, rng, c);
      L += throughput * direct * (1.0f / float(n));
    }
    if (depth >= 3) {
      const float q = std::min(MaxComponent(throughput) * eta * eta, 0.99f);
      if (!(rng.NextFloat() < q)) break;
      throughput *= 1.0f / q;
    }
    BsdfSample bs;
    const float u1 = rng.NextFloat();
    if (!BsdfSampleDirection(scene.materials, its.material, wo, u1, Next2D(rng), &bs)) break;
    throughput *= bs.weight;
    eta *= bs.eta;
    if (IsBlack(throughput)) break;
    specular_bounce = bs.delta;
    prev_pdf = bs.pdf;
    prev_p = its.p;
    const Vec3f wi = its.frame.ToWorld(bs.wi);
    ray = Ray{SpawnOrigin(its, wi), wi, 0.0f, 1e30f};
  }
  return L;
}

}  // namespace

Color3f Li(const RenderContext& ctx, const Ray& ray, Pcg32& rng, RayCounters* counters) {
  switch (ctx.scene.integrator.type) {
    case Type::kNormals: return LiNormals(ctx, ray, counters);
    case Type::kDirectEms:
    case Type::kDirectMats:
    case Type::kDirectMis: return LiDirect(ctx, ray, ctx.scene.integrator.type, rng, counters);
    case Type::kWhitted: return LiWhitted(ctx, ray, 0, rng, counters);
    case Type::kPathMats:
    case Type::kPathEms:
    case Type::kPathMis: return LiPath(ctx, ray, ctx.scene.integrator.type, rng, counters);
  }
  return {};
}

std::string UnsupportedFeature(const Scene& scene) {
  const char* names[kMaterialTagCount] = {"diffuse", "mirror", "dielectric", "roughconductor",
                                          "microfacet"};
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MaterialTag tag = scene.meshes.material[i].tag();
    if (!IsSupportedMaterial(tag))
      return std::string("bsdf '") + names[int(tag)] + "' (on '" + scene.meshes.name[i] +
             "') is not supported yet";
  }
  return "";
}

}  // namespace ptlab
