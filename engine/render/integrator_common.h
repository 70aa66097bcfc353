// Per-vertex pieces of the integrators (emission, MIS weights, emitter samples with a deferred
// shadow test), shared by the scalar integrators and the 8-wide wavefront (engine/wavefront/).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/ray_offset.h"
#include "engine/core/ray.h"
#include "engine/light/area_light.h"
#include "engine/light/delta_light.h"
#include "engine/light/infinite_light.h"
#include "engine/light/light_selection.h"
#include "engine/sampling/sampler.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"

// Both callers run these same functions, so the wavefront with the oracle's kernel table
// produces the scalar path's bits; tests/simd/traverse8_test.cpp (Traverse8Render*) checks it.
namespace ptlab::integrator {

/// Nori's Whitted integrator continues specular chains with probability 0.95.
inline constexpr float kWhittedContinuation = 0.95f;
/// Nori's path_* Russian roulette (from depth 3): the probability that a path with this
/// throughput and accumulated relative index of refraction η goes on, min(max component ·
/// η², 0.99). One formula for the scalar integrators and the wavefront's vertices slot's
/// oracle (simd/wavefront/vertices8 repeats its operations in this order).
inline float NoriContinuation(const Color3f& throughput, float eta) {
  return std::min(MaxComponent(throughput) * eta * eta, 0.99f);
}
/// Recursion guard for the Whitted integrator (paths this long carry ~0.95^64 of the weight).
inline constexpr int kWhittedMaxDepth = 64;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Origin of a ray leaving its.p toward direction w, pushed off the surface on w's side.
inline Vec3f SpawnOrigin(const SurfaceInteraction& its, const Vec3f& w) {
  return OffsetRayOrigin(its.p, Dot(its.ng, w) >= 0 ? its.ng : -its.ng);
}

/// Radiance emitted by the surface at its toward direction w (unit, away from the surface).
inline Color3f Emitted(const Scene& scene, const SurfaceInteraction& its, const Vec3f& w) {
  if (!its.emitter.valid() || its.emitter.tag() != EmitterTag::kArea) return {};
  const uint32_t light = its.emitter.index();
  if (!scene.area_lights.Textured(light))
    return AreaLightRadiance(scene.area_lights.radiance[light], its.frame.n, w);
  if (!(Dot(its.frame.n, w) > 0)) return {};
  return AreaLightRadianceAt(scene, light, TexturePoint{its.uv, its.p, its.prim});
}

/// Solid-angle density with which emitter sampling (an emitter chosen by the scene's light
/// selection, a point by its triangle sampling) produces the point `its` on a light seen from
/// `from`.
inline float EmitterPdf(const Scene& scene, const SurfaceInteraction& its, const Vec3f& from) {
  if (!its.emitter.valid() || its.emitter.tag() != EmitterTag::kArea) return 0.0f;
  return EmitterSelectionPmf(scene, its.emitter) *
         AreaLightPdf(scene, its.emitter.index(), its.prim, its.p, its.frame.n, from,
                      scene.integrator.triangle_sampling);
}

/// MIS weight of a strategy with density pdf_a against one with density pdf_b (one sample
/// each): the balance heuristic, or Veach's power heuristic with exponent 2.
inline float MisWeight(float pdf_a, float pdf_b, bool power) {
  if (power) {
    pdf_a *= pdf_a;
    pdf_b *= pdf_b;
  }
  const float sum = pdf_a + pdf_b;
  return sum > 0 ? pdf_a / sum : 0.0f;
}

/// Radiance of the infinite emitters along an escaping ray of direction w. With mis, each
/// emitter's share is weighted against its own emitter-sampling density (times the probability
/// that light selection picks it), bsdf_pdf being the density of the BSDF sample that made w.
inline Color3f Escaped(const Scene& scene, const Vec3f& w, bool mis, float bsdf_pdf) {
  if (scene.environment_maps.size() + scene.distant_disks.size() == 0) return {};
  if (!mis) return EscapedRadiance(scene, w);
  Color3f L;
  for (const EmitterRef e : scene.emitters) {
    if (!IsInfiniteLight(e)) continue;
    Color3f Le;
    const float pdf = InfiniteLightRadianceAndPdf(scene, e, w, &Le);
    if (IsBlack(Le)) continue;
    L += Le * MisWeight(bsdf_pdf, pdf * EmitterSelectionPmf(scene, e),
                        scene.integrator.power_heuristic);
  }
  return L;
}

/// f(wo, wi_local) of an emitter sample's shading point and, for MIS, *pdf_bsdf = BsdfPdf of
/// the same directions (one BsdfEvalPdf; without mis only BsdfEval, *pdf_bsdf = 0).
inline Color3f EmitterSampleBsdf(const Scene& scene, const SurfaceInteraction& its,
                                 const Vec3f& wo, const Vec3f& wi_local, bool mis,
                                 float* pdf_bsdf) {
  const TextureSite site = TextureSiteOf(scene, its);
  if (!mis) {
    *pdf_bsdf = 0.0f;
    return BsdfEval(scene.materials, its.material, wo, wi_local, site);
  }
  return BsdfEvalPdf(scene.materials, its.material, wo, wi_local, pdf_bsdf, site);
}

/// f·Le·|cos θi| / pdf_light of one emitter sample (solid-angle pdf_light, emitter choice
/// included; for a delta light, the probability of choosing it), weighted with MIS against
/// BSDF sampling of wi_local (density pdf_bsdf, EmitterSampleBsdf) when mis is set.
inline Color3f LightSampleContribution(const Scene& scene, const Vec3f& wi_local, const Color3f& f,
                                       float pdf_bsdf, const Color3f& radiance, float pdf_light,
                                       bool mis) {
  float weight = 1.0f;
  if (mis) weight = MisWeight(pdf_light, pdf_bsdf, scene.integrator.power_heuristic);
  return f * radiance * (AbsCosTheta(wi_local) * weight / pdf_light);
}

/// One emitter sample for the direct light at its (wo: local direction to the viewer), with
/// the shadow test left to the caller: when `traced`, the sample adds `contribution` unless
/// `shadow` is occluded; otherwise it adds nothing and no ray is traced. Always draws its three
/// numbers first (light pick, then the point: the Decision dimensions of vertex `depth`,
/// sub-sample `sub` of `sub_count`), so an independent stream stays in step whatever happens.
struct EmitterSampleRequest {
  bool traced = false;
  Ray shadow;
  Color3f contribution;
};

/// The rest of PrepareEmitterSampleWith once area light sample ls is drawn (the light picked
/// with probability pick_pmf): the shadow ray and the contribution, if any. The wavefront draws
/// its area-light samples as a batch (SampleAreaLightBatch, engine/wavefront/area_light.h) and finishes each with this.
inline EmitterSampleRequest AreaEmitterSampleRequest(const Scene& scene,
                                                     const SurfaceInteraction& its,
                                                     const Vec3f& wo, bool mis,
                                                     const AreaLightSample& ls, float pick_pmf) {
  EmitterSampleRequest req;
  if (!(ls.pdf > 0)) return req;
  const Vec3f d = ls.p - its.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return req;
  const Vec3f wi = d / std::sqrt(dist2);
  if (!(Dot(ls.n, wi) < 0)) return req;
  const Vec3f wi_local = its.frame.ToLocal(wi);
  float pdf_bsdf;
  const Color3f f = EmitterSampleBsdf(scene, its, wo, wi_local, mis, &pdf_bsdf);
  if (IsBlack(f)) return req;
  // Shadow ray between the two offset points; d is not normalised, so t runs over [0, 1).
  req.shadow.o = SpawnOrigin(its, wi);
  const Vec3f target = OffsetRayOrigin(ls.p, Dot(ls.ng, wi) <= 0 ? ls.ng : -ls.ng);
  req.shadow.d = target - req.shadow.o;
  req.shadow.t_min = 0.0f;
  req.shadow.t_max = 1.0f;
  req.contribution =
      LightSampleContribution(scene, wi_local, f, pdf_bsdf, ls.radiance, ls.pdf * pick_pmf, mis);
  req.traced = true;
  return req;
}

/// The rest of PrepareEmitterSampleWith once the infinite light's sample es is drawn (the
/// light picked with probability pick_pmf): the shadow ray and the contribution, if any. The
/// wavefront draws its environment-map samples as a batch (SampleEnvironmentBatch) and
/// finishes each returned one with this.
inline EmitterSampleRequest InfiniteEmitterSampleRequest(const Scene& scene,
                                                         const SurfaceInteraction& its,
                                                         const Vec3f& wo, bool mis,
                                                         const EnvironmentSample& es,
                                                         float pick_pmf) {
  EmitterSampleRequest req;
  const Vec3f wi_local = its.frame.ToLocal(es.wi);
  float pdf_bsdf;
  const Color3f f = EmitterSampleBsdf(scene, its, wo, wi_local, mis, &pdf_bsdf);
  if (IsBlack(f)) return req;
  req.shadow = Ray{SpawnOrigin(its, es.wi), es.wi, 0.0f, kInfinity};
  req.contribution =
      LightSampleContribution(scene, wi_local, f, pdf_bsdf, es.radiance, es.pdf * pick_pmf, mis);
  req.traced = true;
  return req;
}

/// The request of emitter `emitter`, picked with probability pick_pmf > 0, sampled with u.
inline EmitterSampleRequest PrepareEmitterSampleFrom(const Scene& scene,
                                                     const SurfaceInteraction& its,
                                                     const Vec3f& wo, bool mis,
                                                     EmitterRef emitter, float pick_pmf,
                                                     const Vec2f& u) {
  EmitterSampleRequest req;
  if (IsInfiniteLight(emitter)) {
    EnvironmentSample es;
    if (!SampleInfiniteLight(scene, emitter, u, &es)) return req;
    return InfiniteEmitterSampleRequest(scene, its, wo, mis, es, pick_pmf);
  }
  if (IsDeltaLight(emitter)) {
    // Picked with probability pick_pmf; no MIS (BSDF sampling never reaches a delta light).
    DeltaLightSample ls;
    if (!SampleDeltaLight(scene, emitter, its.p, &ls)) return req;
    const Vec3f wi_local = its.frame.ToLocal(ls.wi);
    const Color3f f = BsdfEval(scene.materials, its.material, wo, wi_local, TextureSiteOf(scene, its));
    if (IsBlack(f)) return req;
    req.shadow.o = SpawnOrigin(its, ls.wi);
    // A finite light: t over [0, 1) up to the light itself; a directional one: to infinity.
    req.shadow.d = ls.infinite ? ls.wi : ls.position - req.shadow.o;
    req.shadow.t_min = 0.0f;
    req.shadow.t_max = ls.infinite ? kInfinity : 1.0f;
    req.contribution = LightSampleContribution(scene, wi_local, f, /*pdf_bsdf=*/0.0f, ls.radiance,
                                               pick_pmf, /*mis=*/false);
    req.traced = true;
    return req;
  }
  if (emitter.tag() != EmitterTag::kArea) return req;
  return AreaEmitterSampleRequest(
      scene, its, wo, mis,
      SampleAreaLight(scene, emitter.index(), its.p, scene.integrator.triangle_sampling, u),
      pick_pmf);
}

/// The numbers of an emitter sample. With the independent sampler, `pick` picks the emitter and
/// `point` the point on it. The Sobol' sampler has no pick number of its own (folded): point.x
/// picks the emitter and is then stretched back to [0, 1) over the emitter's interval, so the
/// stratified 2-D points of a pixel that land on each emitter are themselves stratified.
struct EmitterNumbers {
  float pick = 0.0f;
  Vec2f point;
  bool folded = false;
};

/// The emitter of an emitter sample with these numbers (the scene must have one), *pmf its
/// probability; leaves in n->point the numbers of the point on it.
inline EmitterRef PickEmitter(const Scene& scene, EmitterNumbers* n, float* pmf) {
  if (n->folded) return SelectEmitter(scene, n->point.x, pmf, &n->point.x);
  return SelectEmitter(scene, n->pick, pmf);
}

/// PrepareEmitterSample with its numbers given.
inline EmitterSampleRequest PrepareEmitterSampleWith(const Scene& scene,
                                                     const SurfaceInteraction& its,
                                                     const Vec3f& wo, bool mis,
                                                     EmitterNumbers numbers) {
  if (scene.emitters.empty()) return {};
  float pick_pmf = 0.0f;
  const EmitterRef emitter = PickEmitter(scene, &numbers, &pick_pmf);
  if (!(pick_pmf > 0)) return {};
  return PrepareEmitterSampleFrom(scene, its, wo, mis, emitter, pick_pmf, numbers.point);
}

/// The numbers of emitter sample `sub` of `sub_count` at vertex `depth`, in the one order every
/// path draws them: the emitter pick (independent sampler only), then the point on the emitter.
inline EmitterNumbers DrawEmitterNumbers(PathSampler& sampler, int depth, uint32_t sub,
                                         uint32_t sub_count) {
  EmitterNumbers n;
  n.folded = sampler.type() == SamplerType::kSobol;
  if (!n.folded) n.pick = sampler.Get1D(DecisionDimension(depth, Decision::kLightPick), sub, sub_count);
  n.point = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint), sub, sub_count);
  return n;
}

inline EmitterSampleRequest PrepareEmitterSample(const Scene& scene, const SurfaceInteraction& its,
                                                 const Vec3f& wo, bool mis, PathSampler& sampler,
                                                 int depth, uint32_t sub = 0,
                                                 uint32_t sub_count = 1) {
  if (scene.emitters.empty()) return {};  // draws nothing
  return PrepareEmitterSampleWith(scene, its, wo, mis,
                                  DrawEmitterNumbers(sampler, depth, sub, sub_count));
}

/// The BSDF numbers of vertex `depth`, in the one order every path draws them: the lobe, then
/// the direction.
inline void DrawBsdfNumbers(PathSampler& sampler, int depth, float* u_lobe, Vec2f* u_dir) {
  *u_lobe = sampler.Get1D(DecisionDimension(depth, Decision::kBsdfLobe));
  *u_dir = sampler.Get2D(DecisionDimension(depth, Decision::kBsdfDirection));
}

/// Samples the BSDF at its (wo local) with the lobe and direction dimensions of vertex depth.
inline bool SampleBsdf(const Scene& scene, const SurfaceInteraction& its, const Vec3f& wo,
                       PathSampler& sampler, int depth, BsdfSample* bs) {
  float u_lobe;
  Vec2f u_dir;
  DrawBsdfNumbers(sampler, depth, &u_lobe, &u_dir);
  return BsdfSampleDirection(scene.materials, its.material, wo, u_lobe, u_dir, bs,
                             TextureSiteOf(scene, its));
}

/// What a prepared emitter sample adds once its shadow ray's visibility is known (the scalar
/// SampleEmitterDirect's return value).
inline Color3f EmitterSampleResult(const EmitterSampleRequest& req, bool occluded) {
  if (!req.traced || occluded) return {};
  return req.contribution;
}

}  // namespace ptlab::integrator
