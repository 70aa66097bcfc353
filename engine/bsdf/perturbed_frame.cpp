// normal: Mitsuba 3's `normalmap` and `bumpmap` wrappers (the scalar oracle).
#include "engine/bsdf/perturbed_frame.h"

#include <algorithm>
#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/texture/texture_gradient.h"

namespace ptlab {
namespace {

bool Finite(const Vec3f& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// v / |v|, or `fallback` where |v|² is 0, subnormal or not finite.
Vec3f NormalizedOr(const Vec3f& v, const Vec3f& fallback) {
  const float len2 = Dot(v, v);
  if (!(len2 >= 1e-30f) || !std::isfinite(len2)) return fallback;
  return v / std::sqrt(len2);
}

// The frame (s, t, n) with s = `s_hint` made orthogonal to the unit n; Frame(n) when the hint
// is (nearly) parallel to n.
Frame FrameAlong(const Vec3f& n, const Vec3f& s_hint) {
  const Vec3f s = NormalizedOr(s_hint - n * Dot(n, s_hint), Vec3f{0, 0, 0});
  if (s.x == 0 && s.y == 0 && s.z == 0) return Frame(n);
  Frame f;
  f.n = n, f.s = s, f.t = Cross(n, s);
  return f;
}

float TanTheta2(const Vec3f& w) {
  const float z2 = w.z * w.z;
  return std::max(0.0f, 1.0f - z2) / z2;
}

TextureSite Inside(const TextureSite& site) {
  TextureSite inner = site;
  inner.frame_perturbed = true;
  return inner;
}

}  // namespace

LocalTangents LocalTangentsAt(const ShadingPerturbations& p, const TextureSite& site) {
  PTLAB_CHECK(site.frame != nullptr && site.ng != nullptr);
  const Frame& frame = *site.frame;
  const Vec3f ng = *site.ng;
  const uint32_t prim = site.at.prim;
  Vec3f du, dv;
  if (!IsSphereHit(prim) && prim < p.dp_du_x.size()) {
    du = {p.dp_du_x[prim], p.dp_du_y[prim], p.dp_du_z[prim]};
    dv = {p.dp_dv_x[prim], p.dp_dv_y[prim], p.dp_dv_z[prim]};
  } else {  // a sphere or an instanced triangle: Mitsuba's basis of a degenerate uv map
    const Frame g(ng);
    du = g.s, dv = g.t;
  }
  return {frame.ToLocal(du), frame.ToLocal(dv), frame.ToLocal(ng)};
}

Frame PerturbedFrame(const MaterialTables& m, int64_t id, const Vec3f& wo, const TextureSite& site) {
  const ShadingPerturbations& p = m.perturbation;
  PTLAB_CHECK(site.textures != nullptr);
  const LocalTangents tan = LocalTangentsAt(p, site);
  const uint32_t texture = p.texture[size_t(id)];
  Vec3f n, s_hint;
  if (PerturbationKind(p.kind[size_t(id)]) == PerturbationKind::kNormalMap) {
    // Mitsuba's frame of the unperturbed surface: s along ∂p/∂u in the tangent plane.
    const Vec3f s0 = NormalizedOr({tan.dp_du.x, tan.dp_du.y, 0.0f}, Vec3f{1, 0, 0});
    const Vec3f t0{-s0.y, s0.x, 0.0f};
    const Color3f c = EvalTexture(*site.textures, texture, site.at);
    const Vec3f nm{2.0f * c.r - 1.0f, 2.0f * c.g - 1.0f, 2.0f * c.b - 1.0f};
    n = s0 * nm.x + t0 * nm.y + Vec3f{0, 0, nm.z};
    s_hint = s0;
  } else {
    const Vec2f g = EvalTextureGradient(*site.textures, texture, site.at);
    const float scale = p.scale[size_t(id)];
    const Vec3f du{tan.dp_du.x, tan.dp_du.y, scale * g.x};
    const Vec3f dv{tan.dp_dv.x, tan.dp_dv.y, scale * g.y};
    n = Cross(du, dv);
    if (Dot(tan.ng, n) < 0) n = -n;
    s_hint = tan.dp_du;
  }
  n = NormalizedOr(Finite(n) ? n : Vec3f{0, 0, 0}, Vec3f{0, 0, 1});
  if (wo.z * Dot(wo, n) <= 0) n = {-n.x, -n.y, n.z};
  return FrameAlong(n, Finite(s_hint) ? s_hint : Vec3f{1, 0, 0});
}

float ShadowTerminator(const Vec3f& n, const Vec3f& w) {
  const float alpha2 = std::min(0.125f * TanTheta2(n), 1.0f);
  if (!(alpha2 > 0)) return 1.0f;  // n = z (or not finite): no shadowing
  const float g = 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * TanTheta2(w)));
  return std::isfinite(g) ? g : 0.0f;
}

namespace {

// f_row(P wo, P wi) · |P(wi).z| / |wi.z| · shadowing, with the row's pdf in *pdf (when non-null).
Color3f EvalInFrame(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site) {
  if (pdf != nullptr) *pdf = 0.0f;
  const int64_t id = m.perturbation.Of(ref);
  const Frame P = PerturbedFrame(m, id, wo, site);
  const Vec3f wo_p = P.ToLocal(wo), wi_p = P.ToLocal(wi);
  if (!(wi.z * wi_p.z > 0)) return {};
  const TextureSite inner = Inside(site);
  Color3f f;
  if (pdf != nullptr) f = BsdfEvalPdf(m, ref, wo_p, wi_p, pdf, inner);
  else f = BsdfEval(m, ref, wo_p, wi_p, inner);
  const float scale = std::abs(wi_p.z) / std::abs(wi.z) * ShadowTerminator(P.n, wi);
  if (!std::isfinite(scale)) return {};
  return f * scale;
}

}  // namespace

Color3f PerturbedBsdfEval(const MaterialTables& m, MaterialRef ref, const Vec3f& wo,
                          const Vec3f& wi, const TextureSite& site) {
  return EvalInFrame(m, ref, wo, wi, nullptr, site);
}

float PerturbedBsdfPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                       const TextureSite& site) {
  const Frame P = PerturbedFrame(m, m.perturbation.Of(ref), wo, site);
  const Vec3f wo_p = P.ToLocal(wo), wi_p = P.ToLocal(wi);
  if (!(wi.z * wi_p.z > 0)) return 0.0f;
  return BsdfPdf(m, ref, wo_p, wi_p, Inside(site));
}

Color3f PerturbedBsdfEvalPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo,
                             const Vec3f& wi, float* pdf, const TextureSite& site) {
  return EvalInFrame(m, ref, wo, wi, pdf, site);
}

bool PerturbedBsdfSample(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, float u1,
                         const Vec2f& u2, BsdfSample* sample, const TextureSite& site) {
  const Frame P = PerturbedFrame(m, m.perturbation.Of(ref), wo, site);
  if (!BsdfSampleDirection(m, ref, P.ToLocal(wo), u1, u2, sample, Inside(site))) return false;
  const Vec3f wi_p = sample->wi;
  const Vec3f wi = P.ToWorld(wi_p);
  if (!(wi_p.z * wi.z > 0)) return false;
  sample->wi = wi;
  sample->weight = sample->weight * ShadowTerminator(P.n, wi);
  return true;
}

}  // namespace ptlab
