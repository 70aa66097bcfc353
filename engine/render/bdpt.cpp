// Bidirectional path tracing and the particle tracer (see bdpt.h). Written from Veach's thesis,
// ch. 10 (strategies (s, t), the MIS weights as ratios of the subpaths' densities, eq. 10.9)
// and ch. 5.3 (the adjoint BSDF with shading normals on light subpaths).
#include "engine/render/bdpt.h"

#include <algorithm>
#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/intersect1.h"
#include "engine/bvh/ray_offset.h"
#include "engine/light/delta_light.h"
#include "engine/light/infinite_light.h"
#include "engine/light/light_selection.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"

namespace ptlab {
namespace {

using namespace integrator;

enum class VertexKind : uint8_t { kCamera, kLight, kSurface };

// One subpath vertex. pdf_fwd: density with which its own subpath produced it; pdf_rev: with
// which the other subpath would have (both per unit area, or per solid angle for a vertex at
// infinity, whose `w` is then the unit direction towards the emitter).
struct Vertex {
  VertexKind kind = VertexKind::kSurface;
  Vec3f p, ng, n;   // position, geometric and shading normals (zero for points and the camera)
  Vec3f wo;         // surface: unit direction towards the previous vertex of its subpath
  Vec3f w;          // vertex at infinity: unit direction towards the emitter
  SurfaceInteraction its;
  EmitterRef emitter;  // light vertex: its emitter; surface: the area light it lies on, if any
  Color3f beta;
  float pdf_fwd = 0, pdf_rev = 0;
  bool delta = false;     // surface with a delta BSDF
  bool infinite = false;  // light vertex at infinity
  bool on_surface = false;

  bool DeltaLight() const {
    return kind == VertexKind::kLight && (IsDeltaLight(emitter));
  }
  // Whether a connection may end here.
  bool Connectible() const {
    if (kind == VertexKind::kSurface) return !delta;
    if (kind == VertexKind::kLight) return emitter.tag() != EmitterTag::kDirectional;
    return true;
  }
};

bool Trace(const RenderContext& ctx, const Ray& ray, Hit* hit, RayCounters* c) {
  ++c->rays;
  return Intersect1(ctx.bvh, ray, hit);
}

// Area density at `to` of a direction sampled at `from` with solid-angle density pdf; a vertex
// at infinity keeps the solid-angle density.
float ConvertDensity(float pdf, const Vertex& from, const Vertex& to) {
  if (to.infinite) return pdf;
  const Vec3f d = to.p - from.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return 0.0f;
  const float inv_dist2 = 1.0f / dist2;
  if (to.on_surface) pdf *= std::abs(Dot(to.ng, d * std::sqrt(inv_dist2)));
  return pdf * inv_dist2;
}

Vec3f DirectionTo(const Vertex& from, const Vertex& to) {
  if (to.infinite) return to.w;
  if (from.infinite) return -from.w;
  return Normalize(to.p - from.p);
}

// The probability that light subpaths start at emitter e (the scene's light selection).
float PickPmf(const Scene& scene, EmitterRef e) { return EmitterSelectionPmf(scene, e); }

// Density (area at `next`) with which light vertex v emits towards `next`.
float PdfLight(const Scene& scene, const BidirectionalSetup& setup, const Vertex& v,
               const Vertex& next) {
  if (v.infinite) {
    // A ray of fixed direction through a uniform point of the scene disk: the area density
    // at `next` is the disk's times the cosine there.
    const float pdf_pos = 1.0f / (kPi * setup.sphere.radius * setup.sphere.radius);
    return next.on_surface ? pdf_pos * std::abs(Dot(next.ng, v.w)) : pdf_pos;
  }
  const Vec3f w = DirectionTo(v, next);
  float pdf_pos, pdf_dir;
  EmissionPdf(scene, setup.sphere, v.emitter, v.n, w, &pdf_pos, &pdf_dir);
  return ConvertDensity(pdf_dir, v, next);
}

// Density with which light subpaths start at light vertex v: the pick times the density of
// its position (area), or of its direction (solid angle) for a vertex at infinity.
float PdfLightOrigin(const Scene& scene, const BidirectionalSetup& setup, const Vertex& v) {
  const float pmf = PickPmf(scene, v.emitter);
  if (v.infinite) {
    if (v.emitter.tag() == EmitterTag::kDirectional) return pmf;
    return pmf * InfiniteLightPdf(scene, v.emitter, v.w);
  }
  float pdf_pos, pdf_dir;
  EmissionPdf(scene, setup.sphere, v.emitter, v.n, v.n, &pdf_pos, &pdf_dir);
  return pmf * pdf_pos;
}

// Density (area at `next`) with which vertex `cur`, reached from `prev` (null: none), samples
// `next`.
float PdfOf(const Scene& scene, const BidirectionalSetup& setup, const Vertex* prev,
            const Vertex& cur, const Vertex& next) {
  switch (cur.kind) {
    case VertexKind::kLight:
      return PdfLight(scene, setup, cur, next);
    case VertexKind::kCamera:
      return ConvertDensity(setup.camera.DirectionPdf(cur.p, DirectionTo(cur, next)), cur, next);
    case VertexKind::kSurface: {
      if (prev == nullptr) return 0.0f;
      const Vec3f wo = cur.its.frame.ToLocal(DirectionTo(cur, *prev));
      const Vec3f wi = cur.its.frame.ToLocal(DirectionTo(cur, next));
      return ConvertDensity(BsdfPdf(scene.materials, cur.its.material, wo, wi), cur, next);
    }
  }
  return 0.0f;
}

// Veach's adjoint-BSDF factor for a light subpath turning at a surface with shading normals
// (thesis eq. 5.18): |w_in·ns| |w_out·ng| / (|w_in·ng| |w_out·ns|), w_in towards the light,
// w_out the way the importance-carrying subpath goes on. 0 where a geometric cosine vanishes.
float ShadingNormalCorrection(const SurfaceInteraction& its, const Vec3f& w_in,
                              const Vec3f& w_out) {
  const float num = std::abs(Dot(w_in, its.frame.n)) * std::abs(Dot(w_out, its.ng));
  const float den = std::abs(Dot(w_in, its.ng)) * std::abs(Dot(w_out, its.frame.n));
  if (!(den > 0)) return 0.0f;
  const float c = num / den;
  return std::isfinite(c) ? c : 0.0f;
}

// What a surface vertex v sends towards unit direction w (to the vertex it connects with):
// camera subpath: f(wo, w) |w·ns|; light subpath: the adjoint f(w, wo) |wo·ns| |w·ng| / |wo·ng|.
// Either way the cosine at v of the connecting edge is included.
Color3f ScatterTo(const Scene& scene, const Vertex& v, const Vec3f& w, bool light_subpath) {
  const Frame& frame = v.its.frame;
  const Vec3f wo = frame.ToLocal(v.wo), wl = frame.ToLocal(w);
  if (!light_subpath) return BsdfEval(scene.materials, v.its.material, wo, wl) * AbsCosTheta(wl);
  const Color3f f = BsdfEval(scene.materials, v.its.material, wl, wo);
  return f * (AbsCosTheta(wl) * ShadingNormalCorrection(v.its, v.wo, w));
}

// Whether the segment between two vertices (neither at infinity unless `b` is) is free.
bool Unoccluded(const RenderContext& ctx, const Vertex& a, const Vertex& b, RayCounters* c) {
  Ray ray;
  const Vec3f w = DirectionTo(a, b);
  ray.o = a.kind == VertexKind::kSurface ? SpawnOrigin(a.its, w)
          : a.on_surface                 ? OffsetRayOrigin(a.p, Dot(a.ng, w) >= 0 ? a.ng : -a.ng)
                                         : a.p;
  ray.t_min = 0.0f;
  if (b.infinite) {
    ray.d = w;
    ray.t_max = kInfinity;
  } else {
    const Vec3f target =
        b.on_surface ? OffsetRayOrigin(b.p, Dot(b.ng, w) <= 0 ? b.ng : -b.ng) : b.p;
    ray.d = target - ray.o;
    ray.t_max = 1.0f;
    if (!(Dot(ray.d, ray.d) > 0)) return false;
  }
  ++c->rays;
  return !Occluded1(ctx.bvh, ray);
}

// Extends a subpath whose vertex path[n - 1] sent `ray` with solid-angle density pdf_dir and
// throughput beta, up to max_vertices vertices; returns the new count. light_subpath: the
// vertices carry light (adjoint BSDFs), and the sampler dimensions are the light subpath's.
int RandomWalk(const RenderContext& ctx, Ray ray, Color3f beta, float pdf_dir, bool light_subpath,
               int max_vertices, PathSampler& sampler, std::vector<Vertex>* path, int n,
               RayCounters* c) {
  const Scene& scene = ctx.scene;
  const bool infinite_lights = scene.environment_maps.size() + scene.distant_disks.size() > 0;
  Color3f ratio{1, 1, 1};  // the product of the BSDF weights, for Russian roulette
  float eta = 1.0f;
  for (int bounce = 0; n < max_vertices; ++bounce) {
    std::vector<Vertex>& v = *path;
    Vertex& prev = v[size_t(n - 1)];
    Hit hit;
    if (!Trace(ctx, ray, &hit, c)) {
      // A camera subpath that escapes ends at infinity, where s = 0 finds the environment.
      if (!light_subpath && infinite_lights) {
        Vertex& e = v[size_t(n)];
        e = Vertex{};
        e.kind = VertexKind::kLight;
        e.infinite = true;
        e.w = ray.d / Length(ray.d);
        e.beta = beta;
        e.pdf_fwd = pdf_dir;
        ++n;
      }
      break;
    }
    Vertex& x = v[size_t(n)];
    x = Vertex{};
    x.kind = VertexKind::kSurface;
    x.its = MakeInteraction(scene, ray, hit);
    x.p = x.its.p, x.ng = x.its.ng, x.n = x.its.frame.n;
    x.on_surface = true;
    x.emitter = x.its.emitter;
    x.wo = -ray.d / Length(ray.d);
    x.beta = beta;
    x.pdf_fwd = ConvertDensity(pdf_dir, prev, x);
    x.delta = IsDeltaMaterial(x.its.material.tag());
    ++n;
    if (n >= max_vertices) break;
    const int depth = light_subpath ? kLightSubpathDepth + 1 + bounce : bounce;
    if (bounce >= 3) {
      const float q = std::min(MaxComponent(ratio) * eta * eta, 0.99f);
      if (!(sampler.Get1D(DecisionDimension(depth, Decision::kRoulette)) < q)) break;
      beta = beta * (1.0f / q);
      ratio = ratio * (1.0f / q);
    }
    const Vec3f wo = x.its.frame.ToLocal(x.wo);
    BsdfSample bs;
    if (!SampleBsdf(scene, x.its, wo, sampler, depth, &bs)) break;
    const Vec3f wi = x.its.frame.ToWorld(bs.wi);
    Color3f weight = bs.weight;
    if (light_subpath) {
      weight = weight * ShadingNormalCorrection(x.its, x.wo, wi);
      // A dielectric that scales radiance by (η_o/η_i)² on refraction: importance is not
      // scaled (Veach 5.2), so the light subpath takes the scale back out.
      if (bs.delta && bs.eta != 1.0f && x.its.material.tag() == MaterialTag::kDielectric &&
          (scene.materials.dielectric.Flags(x.its.material.index()) & kDielectricScaleRadiance))
        weight = weight * (bs.eta * bs.eta);
    }
    beta = beta * weight;
    ratio = ratio * weight;
    eta *= light_subpath ? 1.0f : bs.eta;
    if (IsBlack(beta) || !IsFinite(beta)) break;
    float pdf_rev = 0.0f;
    if (bs.delta) {
      pdf_dir = 0.0f;
    } else {
      pdf_dir = bs.pdf;
      pdf_rev = BsdfPdf(scene.materials, x.its.material, bs.wi, wo);
    }
    prev.pdf_rev = ConvertDensity(pdf_rev, x, prev);
    ray = Ray{SpawnOrigin(x.its, wi), wi, 0.0f, kInfinity};
  }
  return n;
}

// The MIS weight of strategy (s, t) (Veach eq. 10.9 as ratios of densities along the path):
// light[0..s) and camera[0..t) with the connection's sampled vertex (s = 1 or t = 1) already
// in place; delta vertices and delta lights exclude the strategies that would need them.
float MisWeightOf(const Scene& scene, const BidirectionalSetup& setup, std::vector<Vertex>& light,
                  int s, std::vector<Vertex>& camera, int t) {
  if (s + t == 2) return 1.0f;
  const bool power = scene.integrator.power_heuristic;
  Vertex* qs = s > 0 ? &light[size_t(s - 1)] : nullptr;
  Vertex* pt = t > 0 ? &camera[size_t(t - 1)] : nullptr;
  Vertex* qs_minus = s > 1 ? &light[size_t(s - 2)] : nullptr;
  Vertex* pt_minus = t > 1 ? &camera[size_t(t - 2)] : nullptr;
  // The reverse densities of the four vertices around the connection, saved and restored.
  struct Saved {
    Vertex* v;
    float pdf_rev;
    bool delta;
  } saved[4] = {{qs, 0, false}, {pt, 0, false}, {qs_minus, 0, false}, {pt_minus, 0, false}};
  for (Saved& sv : saved)
    if (sv.v) sv.pdf_rev = sv.v->pdf_rev, sv.delta = sv.v->delta;
  // pt as an emitter (s = 0): it started a light subpath; it is a light vertex for the ratios.
  Vertex pt_light;
  if (s == 0) {
    pt_light = *pt;
    pt_light.kind = VertexKind::kLight;
  }
  if (pt) {
    pt->pdf_rev = s > 0 ? PdfOf(scene, setup, qs_minus, *qs, *pt)
                        : PdfLightOrigin(scene, setup, pt_light);
    pt->delta = false;
  }
  if (pt_minus) {
    pt_minus->pdf_rev = s > 0 ? PdfOf(scene, setup, qs, *pt, *pt_minus)
                              : PdfLight(scene, setup, pt_light, *pt_minus);
  }
  if (qs) {
    qs->pdf_rev = PdfOf(scene, setup, pt_minus, *pt, *qs);
    qs->delta = false;
  }
  if (qs_minus) qs_minus->pdf_rev = PdfOf(scene, setup, pt, *qs, *qs_minus);

  const auto remap = [](float f) { return f != 0.0f ? f : 1.0f; };
  const auto h = [power](float r) { return power ? r * r : r; };
  double sum = 0.0, ri = 1.0;
  for (int i = t - 1; i > 0; --i) {
    ri *= h(remap(camera[size_t(i)].pdf_rev) / remap(camera[size_t(i)].pdf_fwd));
    if (!camera[size_t(i)].delta && !camera[size_t(i - 1)].delta) sum += ri;
  }
  ri = 1.0;
  for (int i = s - 1; i >= 0; --i) {
    ri *= h(remap(light[size_t(i)].pdf_rev) / remap(light[size_t(i)].pdf_fwd));
    const bool delta_before = i > 0 ? light[size_t(i - 1)].delta : light[0].DeltaLight();
    if (!light[size_t(i)].delta && !delta_before) sum += ri;
  }
  for (Saved& sv : saved)
    if (sv.v) sv.v->pdf_rev = sv.pdf_rev, sv.v->delta = sv.delta;
  const double w = 1.0 / (1.0 + sum);
  return std::isfinite(w) ? float(w) : 0.0f;
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

// Starts the light subpath: emitter, emitted ray, first vertices. Returns the vertex count.
int TraceLightSubpath(const RenderContext& ctx, const BidirectionalSetup& setup, int max_vertices,
                      PathSampler& sampler, std::vector<Vertex>* light, RayCounters* c) {
  const Scene& scene = ctx.scene;
  if (max_vertices <= 0 || scene.emitters.empty()) return 0;
  const int depth = kLightSubpathDepth;
  EmitterNumbers numbers = DrawEmitterNumbers(sampler, depth, 0, 1);
  const Vec2f u_dir = sampler.Get2D(DecisionDimension(depth, Decision::kBsdfDirection));
  float pmf = 0.0f;
  const EmitterRef e = PickEmitter(scene, &numbers, &pmf);
  EmissionSample es;
  if (!(pmf > 0) || !SampleEmission(scene, setup.sphere, e, numbers.point, u_dir, &es)) return 0;
  if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0)) return 0;
  Vertex& x0 = (*light)[0];
  x0 = Vertex{};
  x0.kind = VertexKind::kLight;
  x0.emitter = e;
  x0.infinite = es.infinite;
  Color3f beta;
  if (es.infinite) {
    x0.w = -es.w;
    x0.pdf_fwd = e.tag() == EmitterTag::kDirectional ? pmf : pmf * es.pdf_dir;
    // The cosine at the first hit cancels against the disk's projection (PdfLight).
    beta = es.radiance * (1.0f / (pmf * es.pdf_pos * es.pdf_dir));
  } else {
    x0.p = es.p, x0.n = es.n, x0.ng = es.ng;
    x0.on_surface = e.tag() == EmitterTag::kArea;
    x0.pdf_fwd = pmf * es.pdf_pos;
    x0.beta = Color3f{1, 1, 1} * (1.0f / x0.pdf_fwd);
    const float cos = x0.on_surface ? std::abs(Dot(es.ng, es.w)) : 1.0f;
    beta = es.radiance * (cos / (x0.pdf_fwd * es.pdf_dir));
  }
  if (!IsFinite(beta) || IsBlack(beta)) return 1;
  Ray ray;
  ray.o = x0.on_surface ? OffsetRayOrigin(es.p, Dot(es.ng, es.w) >= 0 ? es.ng : -es.ng) : es.p;
  ray.d = es.w;
  ray.t_min = 0.0f;
  ray.t_max = kInfinity;
  if (!es.infinite) return RandomWalk(ctx, ray, beta, es.pdf_dir, true, max_vertices, sampler, light,
                                      1, c);
  // From infinity the first vertex's density is the disk's (area) times the cosine there:
  // RandomWalk converts solid-angle densities, so convert by hand after the walk.
  const int n = RandomWalk(ctx, ray, beta, 0.0f, true, max_vertices, sampler, light, 1, c);
  if (n > 1) {
    Vertex& x1 = (*light)[1];
    x1.pdf_fwd = PdfLight(scene, setup, x0, x1);
  }
  return n;
}

// The contribution of one connection strategy (s, t) >= (0, 2) or t = 1, MIS weight included.
// For t = 1 it is appended to splats instead.
Color3f Connect(const RenderContext& ctx, const BidirectionalSetup& setup,
                std::vector<Vertex>& light, int s, std::vector<Vertex>& camera, int t,
                PathSampler& sampler, bool ptracer, RayCounters* c,
                std::vector<LightSplat>* splats) {
  const Scene& scene = ctx.scene;
  Color3f L;
  if (s == 0) {
    const Vertex& pt = camera[size_t(t - 1)];
    if (pt.infinite) {
      // Every infinite emitter seen along the escaped direction, each with its own weight.
      Vertex saved = pt;
      for (const EmitterRef e : scene.emitters) {
        if (!IsInfiniteLight(e)) continue;
        const Color3f Le = InfiniteLightRadiance(scene, e, pt.w);
        if (IsBlack(Le)) continue;
        camera[size_t(t - 1)].emitter = e;
        const float w = ptracer ? 1.0f : MisWeightOf(scene, setup, light, 0, camera, t);
        L += pt.beta * Le * w;
      }
      camera[size_t(t - 1)] = saved;
      return L;
    }
    if (!pt.emitter.valid() || pt.emitter.tag() != EmitterTag::kArea) return {};
    const Color3f Le = Emitted(scene, pt.its, pt.wo);
    if (IsBlack(Le)) return {};
    const float w = ptracer ? 1.0f : MisWeightOf(scene, setup, light, 0, camera, t);
    return pt.beta * Le * w;
  }
  if (t == 1) {
    const Vertex& qs = light[size_t(s - 1)];
    if (!qs.Connectible() || qs.infinite) return {};
    const int depth = kLightSubpathDepth + s;
    const Vec2f u_lens = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint));
    CameraConnection cc;
    if (!setup.camera.SampleConnection(qs.p, u_lens, &cc)) return {};
    const Vec3f w = -cc.w;  // from qs to the lens
    // A light vertex itself (s = 1) is never connected to the lens: the camera subpath sees
    // emitters (s = 0, t = 2), and a point light has no image.
    if (qs.kind != VertexKind::kSurface) return {};
    Color3f value = qs.beta * ScatterTo(scene, qs, w, true);
    value = value * (cc.importance / (cc.distance * cc.distance));
    if (IsBlack(value) || !IsFinite(value)) return {};
    Vertex cam;
    cam.kind = VertexKind::kCamera;
    cam.p = cc.p;
    if (!Unoccluded(ctx, qs, cam, c)) return {};
    const Vertex saved = camera[0];
    camera[0] = cam;
    const float weight = ptracer ? 1.0f : MisWeightOf(scene, setup, light, s, camera, 1);
    camera[0] = saved;
    value = value * weight;
    if (IsFinite(value) && !IsBlack(value)) splats->push_back({cc.sx, cc.sy, value});
    return {};
  }
  const Vertex& pt = camera[size_t(t - 1)];
  if (!pt.Connectible() || pt.infinite) return {};
  if (s == 1) {
    Vertex lv;
    Color3f value;
    if (!SampleLightVertex(scene, setup, pt, sampler, t - 2, &lv, &value)) return {};
    const Vec3f w = DirectionTo(pt, lv);
    const Color3f f = ScatterTo(scene, pt, w, false);
    if (IsBlack(f)) return {};
    if (!Unoccluded(ctx, pt, lv, c)) return {};
    const Vertex saved = light[0];
    light[0] = lv;
    const float weight = MisWeightOf(scene, setup, light, 1, camera, t);
    light[0] = saved;
    L = pt.beta * f * value * weight;
    return IsFinite(L) ? L : Color3f{};
  }
  const Vertex& qs = light[size_t(s - 1)];
  if (!qs.Connectible() || qs.kind != VertexKind::kSurface) return {};
  const Vec3f d = qs.p - pt.p;
  const float dist2 = Dot(d, d);
  if (!(dist2 > 0)) return {};
  const Vec3f w = d / std::sqrt(dist2);  // pt -> qs
  const Color3f f_cam = ScatterTo(scene, pt, w, false);
  if (IsBlack(f_cam)) return {};
  const Color3f f_light = ScatterTo(scene, qs, -w, true);
  if (IsBlack(f_light)) return {};
  L = pt.beta * f_cam * f_light * qs.beta * (1.0f / dist2);
  if (IsBlack(L) || !IsFinite(L)) return {};
  if (!Unoccluded(ctx, pt, qs, c)) return {};
  L = L * MisWeightOf(scene, setup, light, s, camera, t);
  return IsFinite(L) ? L : Color3f{};
}

}  // namespace

Color3f LiBidirectional(const RenderContext& ctx, const BidirectionalSetup& setup, const Ray& ray,
                        PathSampler& sampler, RayCounters* counters,
                        std::vector<LightSplat>* splats) {
  const Scene& scene = ctx.scene;
  const bool ptracer = scene.integrator.type == IntegratorDesc::Type::kPtracer;
  const int max_depth = scene.integrator.max_depth;
  // s + t - 2 <= maxDepth bounces; the particle tracer's camera subpath only finds emitters.
  const int max_camera =
      ptracer ? 2 : (max_depth >= 0 ? max_depth + 2 : kBidirectionalMaxVertices);
  const int max_light = max_depth >= 0 ? max_depth + 1 : kBidirectionalMaxVertices;

  // The subpaths' vertices, kept per thread: constructing 2 × 257 vertices per sample cost
  // more than tracing the sample. Every vertex is assigned before it is read.
  thread_local std::vector<Vertex> camera, light;
  if (camera.size() < size_t(max_camera) + 1) camera.resize(size_t(max_camera) + 1);
  if (light.size() < size_t(max_light) + 1) light.resize(size_t(max_light) + 1);
  Vertex& c0 = camera[0];
  c0 = Vertex{};
  c0.kind = VertexKind::kCamera;
  c0.p = ray.o;
  c0.beta = {1, 1, 1};
  const Vec3f d = ray.d / Length(ray.d);
  const int nc = RandomWalk(ctx, ray, {1, 1, 1}, setup.camera.DirectionPdf(ray.o, d), false,
                            max_camera, sampler, &camera, 1, counters);
  const int nl = TraceLightSubpath(ctx, setup, max_light, sampler, &light, counters);

  // s = 1 draws its own light sample, so it runs even when the light subpath is empty.
  const int s_max = std::max(nl, ptracer ? 0 : std::min(1, max_light));
  Color3f L;
  for (int t = 1; t <= nc; ++t) {
    for (int s = 0; s <= s_max; ++s) {
      const int depth = s + t - 2;
      if ((s == 1 && t == 1) || depth < 0 || (max_depth >= 0 && depth > max_depth)) continue;
      if (ptracer && !(t == 1 && s >= 2) && !(s == 0 && t == 2)) continue;
      L += Connect(ctx, setup, light, s, camera, t, sampler, ptracer, counters, splats);
    }
  }
  return L;
}

}  // namespace ptlab
