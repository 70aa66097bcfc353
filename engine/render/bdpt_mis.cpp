// Densities, scattering and the MIS weights of bidirectional path tracing (bdpt_vertex.h).
// Written from Veach's thesis, ch. 10 (the MIS weights as ratios of the subpaths' densities,
// eq. 10.9) and ch. 5.3 (the adjoint BSDF with shading normals on light subpaths).
#include <algorithm>
#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/light/infinite_light.h"
#include "engine/light/light_selection.h"
#include "engine/render/bdpt_vertex.h"

namespace ptlab::bdpt {
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

namespace {

// The probability that light subpaths start at emitter e (the scene's light selection).
float PickPmf(const Scene& scene, EmitterRef e) { return EmitterSelectionPmf(scene, e); }

}  // namespace

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

namespace {

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
// `next`. For a surface, wo / wi (when given): the directions to prev / next in its shading
// frame, already computed (the same bits).
float PdfOf(const Scene& scene, const BidirectionalSetup& setup, const Vertex* prev,
            const Vertex& cur, const Vertex& next, const Vec3f* wo_local = nullptr,
            const Vec3f* wi_local = nullptr) {
  switch (cur.kind) {
    case VertexKind::kLight:
      return PdfLight(scene, setup, cur, next);
    case VertexKind::kCamera:
      return ConvertDensity(setup.camera.DirectionPdf(cur.p, DirectionTo(cur, next)), cur, next);
    case VertexKind::kSurface: {
      if (prev == nullptr) return 0.0f;
      const Vec3f wo = wo_local ? *wo_local : cur.its.frame.ToLocal(DirectionTo(cur, *prev));
      const Vec3f wi = wi_local ? *wi_local : cur.its.frame.ToLocal(DirectionTo(cur, next));
      return ConvertDensity(BsdfPdf(scene.materials, cur.its.material, wo, wi, TextureSiteOf(scene, cur.its)), cur, next);
    }
  }
  return 0.0f;
}

}  // namespace

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
  if (!light_subpath) return BsdfEval(scene.materials, v.its.material, wo, wl, TextureSiteOf(scene, v.its)) * AbsCosTheta(wl);
  const Color3f f = BsdfEval(scene.materials, v.its.material, wl, wo, TextureSiteOf(scene, v.its));
  return f * (AbsCosTheta(wl) * ShadingNormalCorrection(v.its, v.wo, w));
}

// The MIS weight of strategy (s, t) (Veach eq. 10.9 as ratios of densities along the path):
// light[0..s) and camera[0..t) with the connection's sampled vertex (s = 1 or t = 1) already
// in place; delta vertices and delta lights exclude the strategies that would need them.
float MisWeightOf(const Scene& scene, const BidirectionalSetup& setup, Subpath& light, int s,
                  Subpath& camera, int t) {
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
  // Each surface end's direction across the connection, once, and to its own predecessor
  // (Vertex::to_prev, from the walk): the four densities below need no other direction.
  const bool pt_surface = s > 0 && pt->kind == VertexKind::kSurface;
  const bool qs_surface = s > 0 && qs->kind == VertexKind::kSurface;
  Vec3f pt_to_qs, qs_to_pt;
  if (pt_surface) pt_to_qs = pt->its.frame.ToLocal(DirectionTo(*pt, *qs));
  if (qs_surface) qs_to_pt = qs->its.frame.ToLocal(DirectionTo(*qs, *pt));
  const Vec3f* pt_prev = pt_surface ? &pt->to_prev : nullptr;
  const Vec3f* pt_conn = pt_surface ? &pt_to_qs : nullptr;
  const Vec3f* qs_prev = qs_surface ? &qs->to_prev : nullptr;
  const Vec3f* qs_conn = qs_surface ? &qs_to_pt : nullptr;
  if (pt) {
    pt->pdf_rev = s > 0 ? PdfOf(scene, setup, qs_minus, *qs, *pt, qs_prev, qs_conn)
                        : PdfLightOrigin(scene, setup, pt_light);
    pt->delta = false;
  }
  if (pt_minus) {
    pt_minus->pdf_rev = s > 0 ? PdfOf(scene, setup, qs, *pt, *pt_minus, pt_conn, pt_prev)
                              : PdfLight(scene, setup, pt_light, *pt_minus);
  }
  if (qs) {
    qs->pdf_rev = PdfOf(scene, setup, pt_minus, *pt, *qs, pt_prev, pt_conn);
    qs->delta = false;
  }
  if (qs_minus) qs_minus->pdf_rev = PdfOf(scene, setup, pt, *qs, *qs_minus, qs_conn, qs_prev);

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

}  // namespace ptlab::bdpt
