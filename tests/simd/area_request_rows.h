// Area-light emitter requests over a loaded scene, for the area_request kernels' test
// (tests/simd/wavefront/area_request8_test.cpp) and benchmark (benchmarks/emitter_bench.cpp): shading
// points on the scene's triangles, their wo, material rows of one tag and light samples drawn
// by SampleAreaLight from them; and the hard cases.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/bsdf/plastic_precompute.h"
#include "engine/core/frame.h"
#include "engine/core/rng.h"
#include "engine/light/area_light.h"
#include "engine/wavefront/area_request.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"

namespace ptlab::test {

/// The inputs of an area_request batch as owned vectors: shading points and wo by queue entry
/// (its, wo; the rows' ref and wo columns are copies), the rest by row.
struct AreaRequestRows {
  std::vector<SurfaceInteraction> its;
  std::vector<Vec3f> wo;
  std::vector<uint32_t> entry, light;
  std::vector<float> ref_x, ref_y, ref_z, wo_x, wo_y, wo_z;
  std::vector<float> pick_pmf, p_x, p_y, p_z, n_x, n_y, n_z, ng_x, ng_y, ng_z, pdf;

  size_t size() const { return entry.size(); }
  AreaRequestInputs In() const {
    return {its.data(),  entry.data(), ref_x.data(), ref_y.data(), ref_z.data(),
            wo_x.data(), wo_y.data(),  wo_z.data(),  light.data(), pick_pmf.data(),
            p_x.data(),  p_y.data(),   p_z.data(),   n_x.data(),   n_y.data(),
            n_z.data(),  ng_x.data(),  ng_y.data(),  ng_z.data(),  pdf.data()};
  }
  void Push(uint32_t e, uint32_t l, float pmf, const AreaLightSample& s) {
    entry.push_back(e), light.push_back(l), pick_pmf.push_back(pmf);
    ref_x.push_back(its[e].p.x), ref_y.push_back(its[e].p.y), ref_z.push_back(its[e].p.z);
    wo_x.push_back(wo[e].x), wo_y.push_back(wo[e].y), wo_z.push_back(wo[e].z);
    p_x.push_back(s.p.x), p_y.push_back(s.p.y), p_z.push_back(s.p.z);
    n_x.push_back(s.n.x), n_y.push_back(s.n.y), n_z.push_back(s.n.z);
    ng_x.push_back(s.ng.x), ng_y.push_back(s.ng.y), ng_z.push_back(s.ng.z);
    pdf.push_back(s.pdf);
  }
};

/// The outputs of an area_request batch as owned vectors, poisoned (every row must be written).
struct AreaRequestColumns {
  explicit AreaRequestColumns(size_t n) : traced(n, 7), col(9, std::vector<float>(n, -7.0f)) {}
  std::vector<uint8_t> traced;
  std::vector<std::vector<float>> col;  // o x, y, z, d x, y, z, contribution r, g, b
  AreaRequestOutputs Out() {
    return {traced.data(), col[0].data(), col[1].data(), col[2].data(), col[3].data(),
            col[4].data(), col[5].data(), col[6].data(), col[7].data(), col[8].data()};
  }
};

/// Adds material rows of every model to the scene, among them black ones (a black diffuse, a
/// rough plastic of kd = 0) and rough and smooth ones, so that each tag has rows to pick.
inline void AddRequestMaterials(Scene* scene) {
  MaterialTables& m = scene->materials;
  m.AddDiffuse({0.5f, 0.3f, 0.2f}), m.AddDiffuse({0, 0, 0});
  m.AddMirror(), m.AddDielectric(1.5f, 1.0f);
  m.AddConductor(0.05f, {0.2f, 0.9f, 1.1f}, {3.9f, 2.4f, 2.2f});
  m.AddConductor(0.6f, {0.2f, 0.9f, 1.1f}, {3.9f, 2.4f, 2.2f});
  m.AddConductor(1e-3f, {1, 1, 1}, {0, 0, 0});
  m.AddRoughPlastic(0.1f, 1.5f, 1.0f, {0.5f, 0.5f, 0.5f});
  m.AddRoughPlastic(0.01f, 1.5f, 1.0f, {0, 0, 0});
  // matB: a smooth plastic (two-sided too), a thin dielectric, blends with a delta child.
  PlasticDesc d;
  d.diffuse = {0.6f, 0.4f, 0.2f};
  const MaterialRef plastic = m.AddPlastic(*MakePlasticRow(d));
  m.two_sided.Set(m.AddPlastic(*MakePlasticRow(d)));
  m.AddThinDielectric(1.5f);
  m.AddBlend(0.3f, MaterialRef::Make(MaterialTag::kDiffuse, 0), plastic);
  m.AddBlend(0.6f, MaterialRef::Make(MaterialTag::kMirror, 0),
             MaterialRef::Make(MaterialTag::kConductor, 0));
  // matA: rough glass, Beckmann isotropic and GGX anisotropic.
  m.AddRoughDielectric(0.1f, 0.1f, kMicrofacetSampleVisible, 1.5f, 1.0f);
  m.AddRoughDielectric(0.05f, 0.5f, uint8_t(kMicrofacetSampleVisible | kMicrofacetGgx), 1.33f, 1.0f);
}

inline uint32_t MaterialRows(const MaterialTables& m, MaterialTag tag) {
  switch (tag) {
    case MaterialTag::kDiffuse:
      return uint32_t(m.diffuse.size());
    case MaterialTag::kMirror:
      return uint32_t(m.mirror.size());
    case MaterialTag::kDielectric:
      return uint32_t(m.dielectric.size());
    case MaterialTag::kConductor:
      return uint32_t(m.conductor.size());
    case MaterialTag::kRoughPlastic:
      return uint32_t(m.rough_plastic.size());
    // matB
    case MaterialTag::kPlastic:
      return uint32_t(m.plastic.size());
    case MaterialTag::kThinDielectric:
      return uint32_t(m.thin_dielectric.size());
    case MaterialTag::kBlend:
      return uint32_t(m.blend.size());
    case MaterialTag::kMask:  // mask: its own test (mask8_test.cpp)
      return uint32_t(m.mask.size());
    case MaterialTag::kRoughDielectric:  // matA
      return uint32_t(m.rough_dielectric.size());
    case MaterialTag::kPrincipled:  // principled
      return uint32_t(m.principled.size());
    case MaterialTag::kPrincipledThin:
      return uint32_t(m.principled_thin.size());
  }
  return 0;
}

/// `random` rows: shading points uniform over the scene's triangles (either side; a shading
/// normal tilted from the geometric one), 1 in 8 wo below the surface, each point the reference
/// of 1 to 3 rows (as with several emitter samples per vertex), lights and numbers at random;
/// material rows of `tag` at random (the scene must have some, AddRequestMaterials). With
/// `hard`, then the hard cases, several of each: no sample (pdf 0), the light point on the
/// shading point (distance 0), on the tangent plane (grazing, cos θi = 0 or a few ulp off), behind
/// the surface, a light facing away or edge-on, a pdf_light that underflows to 0 (the oracle's
/// contribution is infinite) or overflows, and points within 1/32 of the origin (the fixed
/// offset step), negative coordinates included.
inline AreaRequestRows MakeAreaRequestRows(const Scene& scene, MaterialTag tag, size_t random,
                                           bool hard, Pcg32& rng) {
  AreaRequestRows r;
  const TriangleTable& t = scene.triangles;
  const uint32_t triangles = uint32_t(t.v0_x.size()), lights = uint32_t(scene.area_lights.size());
  const uint32_t materials = MaterialRows(scene.materials, tag);
  const auto unit = [&rng] {
    for (;;) {
      const Vec3f v{2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1, 2 * rng.NextFloat() - 1};
      const float l2 = Dot(v, v);
      if (l2 > 1e-4f && l2 <= 1) return v / std::sqrt(l2);
    }
  };
  const auto add_point = [&](const Vec3f& p, const Vec3f& ng, const Vec3f& n) {
    SurfaceInteraction its;
    its.p = p, its.ng = ng, its.frame = Frame(n);
    its.material = MaterialRef::Make(tag, rng.NextUint() % materials);
    r.its.push_back(its);
    Vec3f wo = unit();
    wo.z = r.its.size() % 8 == 0 ? -std::fabs(wo.z) : std::fabs(wo.z);
    r.wo.push_back(wo);
    return uint32_t(r.its.size() - 1);
  };
  while (r.size() < random) {
    const uint32_t tri = rng.NextUint() % triangles;
    const float su = std::sqrt(rng.NextFloat()), b1 = 1 - su, b2 = rng.NextFloat() * su;
    const Vec3f p = t.V0(tri) * (1 - b1 - b2) + t.V1(tri) * b1 + t.V2(tri) * b2;
    Vec3f ng = Cross(t.V1(tri) - t.V0(tri), t.V2(tri) - t.V0(tri));
    if (!(Dot(ng, ng) > 0)) continue;
    ng = ng / std::sqrt(Dot(ng, ng));
    if (rng.NextFloat() < 0.5f) ng = -ng;
    Vec3f n = ng + unit() * 0.3f;
    n = n / std::sqrt(Dot(n, n));
    const uint32_t e = add_point(p, ng, n);
    for (uint32_t k = 0, m = 1 + rng.NextUint() % 3; k < m; ++k) {
      const uint32_t l = rng.NextUint() % lights;
      const Vec2f u{rng.NextFloat(), rng.NextFloat()};
      r.Push(e, l, 1.0f / float(lights), SampleAreaLight(scene, l, p, TriangleSampling::kArea, u));
    }
  }
  if (!hard) return r;
  const size_t points = r.its.size();
  for (size_t k = 0; k < 64; ++k) {
    const uint32_t e = uint32_t(rng.NextUint() % points), l = rng.NextUint() % lights;
    const SurfaceInteraction its = r.its[e];
    const Vec3f p = its.p, n = its.frame.n;
    AreaLightSample s =
        SampleAreaLight(scene, l, p, TriangleSampling::kArea, {rng.NextFloat(), rng.NextFloat()});
    const float dist = 0.5f + rng.NextFloat();
    const auto toward = [&](const Vec3f& target) {  // the light point moved to target
      AreaLightSample m = s;
      m.p = target;
      const Vec3f w = target - p;
      m.n = m.ng = Dot(w, w) > 0 ? -(w / std::sqrt(Dot(w, w))) : Vec3f{0, 0, 1};
      if (!(m.pdf > 0)) m.pdf = 1.0f;
      return m;
    };
    AreaLightSample none = s;
    none.pdf = 0;
    r.Push(e, l, 0.5f, none);
    r.Push(e, l, 0.5f, toward(p));  // distance 0
    // Grazing: on the shading frame's tangent plane, exactly and a few ulp either side.
    const Vec3f tangent = its.frame.s;
    r.Push(e, l, 0.5f, toward(p + tangent * dist));
    r.Push(e, l, 0.5f, toward(p + tangent * dist + n * (dist * 1e-7f)));
    r.Push(e, l, 0.5f, toward(p + tangent * dist - n * (dist * 1e-7f)));
    r.Push(e, l, 0.5f, toward(p + Cross(its.ng, tangent) * dist));
    r.Push(e, l, 0.5f, toward(p - n * dist));  // behind
    AreaLightSample away = toward(p + n * dist);
    away.n = -away.n;  // facing away
    r.Push(e, l, 0.5f, away);
    away.n = tangent;  // edge-on
    r.Push(e, l, 0.5f, away);
    AreaLightSample faint = toward(p + (n + tangent * 0.3f) * dist);
    faint.pdf = 1e-30f;
    r.Push(e, l, 1e-20f, faint);  // pdf_light underflows: the oracle's contribution is Inf
    faint.pdf = 3e38f;
    r.Push(e, l, 1.0f, faint);
    // Near the origin, where the offset is a fixed step, and negative coordinates.
    const Vec3f near_origin{(rng.NextFloat() - 0.5f) / 20, (rng.NextFloat() - 0.5f) / 20,
                            -(rng.NextFloat()) / 40};
    const uint32_t e0 = add_point(near_origin, its.ng, n);
    r.Push(e0, l, 0.5f, toward(near_origin + (n + unit() * 0.5f) * 0.01f));
    r.Push(e0, l, 0.5f, toward(-p + n * dist));
  }
  return r;
}

}  // namespace ptlab::test
