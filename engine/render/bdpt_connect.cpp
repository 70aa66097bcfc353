// The connection strategies of bidirectional path tracing (bdpt_connect.h).
#include "engine/render/bdpt_connect.h"

#include <cmath>

#include "engine/bvh/ray_offset.h"
#include "engine/light/infinite_light.h"
#include "engine/light/light_selection.h"
#include "engine/render/integrator_common.h"

namespace ptlab::bdpt {
namespace {

using namespace integrator;

// The segment between two vertices (neither at infinity unless `b` is), offset off their
// surfaces; false when it is degenerate (counts as occluded).
bool ShadowRay(const Vertex& a, const Vertex& b, Ray* ray) {
  const Vec3f w = DirectionTo(a, b);
  ray->o = a.kind == VertexKind::kSurface ? SpawnOrigin(a.its, w)
           : a.on_surface                 ? OffsetRayOrigin(a.p, Dot(a.ng, w) >= 0 ? a.ng : -a.ng)
                                          : a.p;
  ray->t_min = 0.0f;
  if (b.infinite) {
    ray->d = w;
    ray->t_max = kInfinity;
    return true;
  }
  const Vec3f target = b.on_surface ? OffsetRayOrigin(b.p, Dot(b.ng, w) <= 0 ? b.ng : -b.ng) : b.p;
  ray->d = target - ray->o;
  ray->t_max = 1.0f;
  return Dot(ray->d, ray->d) > 0;
}

// Light sample for strategy s = 1 seen from camera vertex pt: a light vertex (emitter picked
// by the scene's light selection, position from its emission sampling, or for an infinite
// emitter a direction from its distribution) and the light it sends to pt without the BSDF and
// the cosine at pt, divided by its density: *value.
bool SampleLightVertex(const Scene& scene, const BidirectionalSetup& setup, const Vertex& pt,
                       PathSampler& sampler, int depth, Vertex* out, Color3f* value) {
  const EmitterNumbers numbers = DrawEmitterNumbers(sampler, depth, 0, 1);
  if (scene.emitters.empty()) return false;
  EmitterNumbers n = numbers;
  float pmf = 0.0f;
  const EmitterRef e = PickEmitter(scene, &n, &pmf);
  if (!(pmf > 0)) return false;
  *out = Vertex{};
  out->kind = VertexKind::kLight;
  out->emitter = e;
  if (e.tag() == EmitterTag::kEnvironment || e.tag() == EmitterTag::kDistantDisk) {
    EnvironmentSample es;
    if (!SampleInfiniteLight(scene, e, n.point, &es) || !(es.pdf > 0)) return false;
    out->infinite = true;
    out->w = es.wi;
    out->pdf_fwd = pmf * es.pdf;
    *value = es.radiance * (1.0f / out->pdf_fwd);
    return true;
  }
  if (e.tag() == EmitterTag::kDirectional) {
    out->infinite = true;
    out->w = -scene.directional_lights.direction[e.index()];
    out->pdf_fwd = pmf;
    *value = scene.directional_lights.radiance[e.index()] * (1.0f / pmf);
    return true;
  }
  EmissionSample es;
  if (!SampleEmission(scene, setup.sphere, e, n.point, Vec2f{0.5f, 0.5f}, &es)) return false;
  out->p = es.p, out->n = es.n, out->ng = es.ng;
  out->on_surface = e.tag() == EmitterTag::kArea;
  out->pdf_fwd = pmf * es.pdf_pos;
  const Vec3f d = pt.p - es.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return false;
  const Vec3f w = d / std::sqrt(dist2);
  Color3f emitted;
  if (e.tag() == EmitterTag::kArea) {
    // The shading normal decides the emitting side; the area measure's cosine is geometric,
    // as for the camera subpath that hits the light (ConvertDensity).
    emitted = AreaLightRadiance(es.radiance, es.n, w) * std::abs(Dot(es.ng, w));
  } else {
    emitted = DeltaLightIntensity(scene, e, w);
  }
  *value = emitted * (1.0f / (dist2 * out->pdf_fwd));
  return !IsBlack(*value) && IsFinite(*value);
}

}  // namespace

bool PrepareConnection(const Scene& scene, const BidirectionalSetup& setup, Subpath& light, int s,
                       Subpath& camera, int t, PathSampler& sampler, bool ptracer, Connection* out,
                       Ray* shadow, Vertex* endpoint) {
  out->s = s, out->t = t;
  out->shadow = true;
  if (s == 0) {
    out->shadow = false;
    Vertex& pt = camera[size_t(t - 1)];
    if (pt.infinite) {
      // Every infinite emitter seen along the escaped direction, each with its own weight.
      const EmitterRef saved = pt.emitter;
      Color3f L;
      for (const EmitterRef e : scene.emitters) {
        if (!IsInfiniteLight(e)) continue;
        const Color3f Le = InfiniteLightRadiance(scene, e, pt.w);
        if (IsBlack(Le)) continue;
        pt.emitter = e;
        const float w = ptracer ? 1.0f : MisWeightOf(scene, setup, light, 0, camera, t);
        L += pt.beta * Le * w;
      }
      pt.emitter = saved;
      out->value = L;
      return true;
    }
    if (!pt.emitter.valid() || pt.emitter.tag() != EmitterTag::kArea) return false;
    const Color3f Le = Emitted(scene, pt.its, pt.wo);
    if (IsBlack(Le)) return false;
    const float w = ptracer ? 1.0f : MisWeightOf(scene, setup, light, 0, camera, t);
    out->value = pt.beta * Le * w;
    return true;
  }
  if (t == 1) {
    const Vertex& qs = light[size_t(s - 1)];
    if (!qs.Connectible() || qs.infinite) return false;
    const int depth = kLightSubpathDepth + s;
    const Vec2f u_lens = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint));
    CameraConnection cc;
    if (!setup.camera.SampleConnection(qs.p, u_lens, &cc)) return false;
    const Vec3f w = -cc.w;  // from qs to the lens
    // A light vertex itself (s = 1) is never connected to the lens: the camera subpath sees
    // emitters (s = 0, t = 2), and a point light has no image.
    if (qs.kind != VertexKind::kSurface) return false;
    Color3f value = qs.beta * ScatterTo(scene, qs, w, true);
    value = value * (cc.importance / (cc.distance * cc.distance));
    if (IsBlack(value) || !IsFinite(value)) return false;
    *endpoint = Vertex{};
    endpoint->kind = VertexKind::kCamera;
    endpoint->p = cc.p;
    out->value = value;
    out->sx = cc.sx, out->sy = cc.sy;
    return ShadowRay(qs, *endpoint, shadow);
  }
  const Vertex& pt = camera[size_t(t - 1)];
  if (!pt.Connectible() || pt.infinite) return false;
  if (s == 1) {
    Color3f value;
    if (!SampleLightVertex(scene, setup, pt, sampler, t - 2, endpoint, &value)) return false;
    const Vec3f w = DirectionTo(pt, *endpoint);
    const Color3f f = ScatterTo(scene, pt, w, false);
    if (IsBlack(f)) return false;
    out->value = pt.beta * f * value;
    return ShadowRay(pt, *endpoint, shadow);
  }
  const Vertex& qs = light[size_t(s - 1)];
  if (!qs.Connectible() || qs.kind != VertexKind::kSurface) return false;
  const Vec3f d = qs.p - pt.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return false;
  const Vec3f w = d / std::sqrt(dist2);  // pt -> qs
  const Color3f f_cam = ScatterTo(scene, pt, w, false);
  if (IsBlack(f_cam)) return false;
  const Color3f f_light = ScatterTo(scene, qs, -w, true);
  if (IsBlack(f_light)) return false;
  const Color3f L = pt.beta * f_cam * f_light * qs.beta * (1.0f / dist2);
  if (IsBlack(L) || !IsFinite(L)) return false;
  out->value = L;
  return ShadowRay(pt, qs, shadow);
}

Color3f FinishConnection(const Scene& scene, const BidirectionalSetup& setup, Subpath& light,
                         Subpath& camera, const Connection& c, const Vertex& endpoint, bool ptracer,
                         std::vector<LightSplat>* splats) {
  if (c.s == 0) return c.value;
  if (c.t == 1) {
    const Vertex saved = camera[0];
    camera[0] = endpoint;
    const float weight = ptracer ? 1.0f : MisWeightOf(scene, setup, light, c.s, camera, 1);
    camera[0] = saved;
    const Color3f value = c.value * weight;
    if (IsFinite(value) && !IsBlack(value)) splats->push_back({c.sx, c.sy, value});
    return {};
  }
  if (c.s == 1) {
    Vertex& l0 = At(&light, 0);
    const Vertex saved = l0;
    l0 = endpoint;
    const float weight = MisWeightOf(scene, setup, light, 1, camera, c.t);
    light[0] = saved;
    const Color3f L = c.value * weight;
    return IsFinite(L) ? L : Color3f{};
  }
  const Color3f L = c.value * MisWeightOf(scene, setup, light, c.s, camera, c.t);
  return IsFinite(L) ? L : Color3f{};
}

}  // namespace ptlab::bdpt
