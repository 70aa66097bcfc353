// Scalar integrators (the oracle): normals, direct_{ems,mats,mis}, whitted, path_{mats,ems,mis}.
#include "engine/render/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "engine/core/check.h"
#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/light/area_light.h"
#include "engine/light/infinite_light.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"

namespace ptlab {
namespace {

using Type = IntegratorDesc::Type;
using namespace integrator;  // the per-vertex pieces shared with the packet path

bool Trace(const RenderContext& ctx, const Ray& ray, Hit* hit, RayCounters* c) {
  ++c->rays;
  return Intersect1(ctx.bvh, ray, hit);
}

// One emitter sample for the direct light at its (wo: local direction to the viewer).
// With mis, the sample is weighted against BSDF sampling (balance or power heuristic).
Color3f SampleEmitterDirect(const RenderContext& ctx, const SurfaceInteraction& its,
                            const Vec3f& wo, bool mis, PathSampler& sampler, int depth,
                            RayCounters* c, uint32_t sub = 0, uint32_t sub_count = 1) {
  const EmitterSampleRequest req =
      PrepareEmitterSample(ctx.scene, its, wo, mis, sampler, depth, sub, sub_count);
  if (!req.traced) return {};
  ++c->rays;
  return EmitterSampleResult(req, Occluded1(ctx.bvh, req.shadow));
}

Color3f LiNormals(const RenderContext& ctx, const Ray& ray, RayCounters* c) {
  Hit hit;
  if (!Trace(ctx, ray, &hit, c)) return {};
  const Vec3f n = Abs(MakeInteraction(ctx.scene, ray, hit).frame.n);
  return {n.x, n.y, n.z};
}

// Direct illumination: Le at the first hit plus one bounce of emitter and/or BSDF sampling.
Color3f LiDirect(const RenderContext& ctx, const Ray& ray, Type type, PathSampler& sampler,
                 RayCounters* c) {
  const Scene& scene = ctx.scene;
  const bool hide = scene.integrator.hide_emitters;
  Hit hit;
  if (!Trace(ctx, ray, &hit, c))
    return hide ? Color3f{} : Escaped(scene, ray.d / Length(ray.d), false, 0.0f);
  const SurfaceInteraction its = MakeInteraction(scene, ray, hit);
  const Vec3f wo_world = -ray.d / Length(ray.d);
  Color3f L = hide ? Color3f{} : Emitted(scene, its, wo_world);
  const Vec3f wo = its.frame.ToLocal(wo_world);
  const bool mis = type == Type::kDirectMis;
  if (type != Type::kDirectMats) L += SampleEmitterDirect(ctx, its, wo, mis, sampler, 0, c);
  if (type == Type::kDirectEms) return L;

  BsdfSample bs;
  if (!SampleBsdf(scene, its, wo, sampler, 0, &bs)) return L;
  const Vec3f wi = its.frame.ToWorld(bs.wi);
  Ray next{SpawnOrigin(its, wi), wi, 0.0f, kInfinity};
  // The ray's direction renormalised, as LiPath and the wavefront see every ray (ToWorld's
  // result can be an ulp off unit length, which moves an environment-map lookup).
  const Vec3f w = next.d / Length(next.d);
  Hit hit2;
  if (!Trace(ctx, next, &hit2, c)) {
    if (type == Type::kDirectMats) return L + bs.weight * Escaped(scene, w, false, 0.0f);
    return L + bs.weight * Escaped(scene, w, mis && !bs.delta, bs.pdf);
  }
  const SurfaceInteraction light = MakeInteraction(scene, next, hit2);
  const Color3f Le = Emitted(scene, light, -w);
  if (IsBlack(Le)) return L;
  float weight = 1.0f;
  if (mis && !bs.delta) {
    const float pdf_light = EmitterPdf(scene, light, its.p);
    weight = MisWeight(bs.pdf, pdf_light, scene.integrator.power_heuristic);
  }
  return L + bs.weight * Le * weight;
}

// Whitted: emitter sampling on non-specular surfaces, specular chains continued through delta
// lobes with Russian roulette (continuation 0.95, Nori's definition). Iterative: the throughput
// of the chain carries each delta weight divided by the continuation probability.
Color3f LiWhitted(const RenderContext& ctx, Ray ray, PathSampler& sampler, RayCounters* c) {
  const Scene& scene = ctx.scene;
  Color3f L, throughput{1, 1, 1};
  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!Trace(ctx, ray, &hit, c)) {
      L += throughput * Escaped(scene, ray.d / Length(ray.d), false, 0.0f);
      break;
    }
    const SurfaceInteraction its = MakeInteraction(scene, ray, hit);
    const Vec3f wo_world = -ray.d / Length(ray.d);
    L += throughput * Emitted(scene, its, wo_world);
    const Vec3f wo = its.frame.ToLocal(wo_world);
    if (!IsDeltaMaterial(its.material.tag())) {
      L += throughput * SampleEmitterDirect(ctx, its, wo, /*mis=*/false, sampler, depth, c);
      break;
    }
    if (depth >= kWhittedMaxDepth ||
        sampler.Get1D(DecisionDimension(depth, Decision::kRoulette)) >= kWhittedContinuation)
      break;
    BsdfSample bs;
    if (!SampleBsdf(scene, its, wo, sampler, depth, &bs)) break;
    throughput *= bs.weight * (1.0f / kWhittedContinuation);
    const Vec3f wi = its.frame.ToWorld(bs.wi);
    ray = Ray{SpawnOrigin(its, wi), wi, 0.0f, kInfinity};
  }
  return L;
}

// Path tracing with BSDF sampling only (mats), next-event estimation (ems), or both combined
// by MIS. Russian roulette as in Nori: after 3 bounces continue with probability
// min(max(throughput) η², 0.99). max_depth follows CS184: 0 = emitted light only,
// 1 = direct lighting, ...; negative = unbounded.
Color3f LiPath(const RenderContext& ctx, Ray ray, Type type, PathSampler& sampler,
               RayCounters* c) {
  const Scene& scene = ctx.scene;
  const IntegratorDesc& desc = scene.integrator;
  const bool nee = type != Type::kPathMats, mis = type == Type::kPathMis;
  Color3f L, throughput{1, 1, 1};
  float eta = 1.0f;
  bool specular_bounce = true;  // the camera ray counts as specular: emission is always seen
  float prev_pdf = 0.0f;        // BSDF pdf of the bounce that produced `ray`
  Vec3f prev_p;
  for (int depth = 0;; ++depth) {
    // hide_emitters: the camera ray's emitted light is not counted.
    const bool hidden = depth == 0 && desc.hide_emitters;
    Hit hit;
    if (!Trace(ctx, ray, &hit, c)) {
      // Escaped: environment light, counted unless emitter sampling already did (ems after a
      // non-specular bounce), MIS-weighted for path_mis.
      const Vec3f w = ray.d / Length(ray.d);
      if (hidden) break;
      if (!nee || specular_bounce) L += throughput * Escaped(scene, w, false, 0.0f);
      else if (mis) L += throughput * Escaped(scene, w, true, prev_pdf);
      break;
    }
    const SurfaceInteraction its = MakeInteraction(scene, ray, hit);
    const Vec3f wo_world = -ray.d / Length(ray.d);
    const Color3f Le = hidden ? Color3f{} : Emitted(scene, its, wo_world);
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
      for (int i = 0; i < n; ++i)
        direct += SampleEmitterDirect(ctx, its, wo, mis, sampler, depth, c, uint32_t(i),
                                      uint32_t(n));
      L += throughput * direct * (1.0f / float(n));
    }
    if (depth >= 3) {
      const float q = NoriContinuation(throughput, eta);
      if (!(sampler.Get1D(DecisionDimension(depth, Decision::kRoulette)) < q)) break;
      throughput *= 1.0f / q;
    }
    BsdfSample bs;
    if (!SampleBsdf(scene, its, wo, sampler, depth, &bs)) break;
    throughput *= bs.weight;
    eta *= bs.eta;
    if (IsBlack(throughput)) break;
    specular_bounce = bs.delta;
    prev_pdf = bs.pdf;
    prev_p = its.p;
    const Vec3f wi = its.frame.ToWorld(bs.wi);
    ray = Ray{SpawnOrigin(its, wi), wi, 0.0f, kInfinity};
  }
  return L;
}

}  // namespace

Color3f Li(const RenderContext& ctx, const Ray& ray, PathSampler& sampler,
           RayCounters* counters) {
  switch (ctx.scene.integrator.type) {
    case Type::kNormals: return LiNormals(ctx, ray, counters);
    case Type::kDirectEms:
    case Type::kDirectMats:
    case Type::kDirectMis: return LiDirect(ctx, ray, ctx.scene.integrator.type, sampler, counters);
    case Type::kWhitted: return LiWhitted(ctx, ray, sampler, counters);
    case Type::kPathMats:
    case Type::kPathEms:
    case Type::kPathMis: return LiPath(ctx, ray, ctx.scene.integrator.type, sampler, counters);
    case Type::kBdpt:
    case Type::kPtracer:
      // They splat into other pixels: LiBidirectional (bdpt.h), called by RenderTileScalar.
      PTLAB_CHECK(false && "bdpt and ptracer run through LiBidirectional");
      return {};
  }
  return {};
}

std::string UnsupportedFeature(const Scene& scene) {
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MaterialRef m = scene.meshes.material[i];
    if (!m.valid())
      return "the material of '" + scene.meshes.name[i] + "' is not supported yet";
  }
  return "";
}

}  // namespace ptlab
