// Chi-square subjects of matB's models: the smooth plastic's, the blend's and the mask's non-delta
// samples.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/plastic.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/scene/material_tables.h"
#include "engine/wavefront/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tools/chi2/bsdf_subjects.h"

namespace ptlab {
namespace {

// As in bsdf_subjects.cpp: the cosine warp drops ~8e-8 of the draws on the square's edge.
constexpr double kCosineSamplerMass = 1.0 - 1e-12;

// The non-delta samples of `ref` at wo, scalar (BsdfSampleDirection) or SIMD (simd::ShadeBatch
// with the delta column): a delta sample has no density and counts as absorbed, so the
// subject's mass is the probability of the non-delta lobes, `albedo`.
Chi2Subject NonDeltaSubject(std::string name, std::string params,
                            std::shared_ptr<const MaterialTables> m, MaterialRef ref,
                            const Vec3f& wo, bool simd, double albedo) {
  Chi2Subject s;
  s.name = std::move(name);
  s.params = std::move(params);
  s.domain = Chi2Domain::Hemisphere();
  s.albedo = albedo;
  s.uniform_dims = 3;
  // The delta lobe takes a share of the draws: more of them keep the power to catch a 2 %
  // error of the pdf ≥ 95 % (the lab's target) where the non-delta mass is small.
  s.sample_scale = int(std::min(8.0, std::ceil(1.5 / albedo)));
  s.pdf = [m, ref, wo](const Chi2Point& wi) { return double(BsdfPdf(*m, ref, wo, wi)); };
  if (!simd) {
    s.sample = [m, ref, wo](float u1, const Vec2f& u, Chi2Point* p) {
      BsdfSample bs;
      if (!BsdfSampleDirection(*m, ref, wo, u1, u, &bs) || bs.delta) return false;
      *p = bs.wi;
      return true;
    };
    return s;
  }
  s.params += std::string(" target=") + simd::DispatchedTargetName();
  s.sample_batch = ShadeBatchSampler(m, ref, wo, /*reject_delta=*/true);
  return s;
}

std::string Fmt(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[128];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

}  // namespace

void RegisterCoatedBsdfSubjects(Chi2Registry* r) {
  struct Case {
    float eta, theta_deg, phi_deg;
    bool nonlinear;
  };
  const Case cases[] = {{1.5f, 0, 0, false},   {1.5f, 30, 35, true}, {1.5f, 60, 110, false},
                        {1.5f, 85, 250, true}, {1.1f, 60, 20, false}, {3.0f, 30, 200, false}};
  for (const Case& c : cases) {
    for (bool simd : {false, true}) {
      if (simd && c.eta != 1.5f) continue;
      auto m = std::make_shared<MaterialTables>();
      PlasticDesc d;
      d.int_ior = c.eta, d.ext_ior = 1.0f, d.nonlinear = c.nonlinear;
      d.diffuse = {0.35f, 0.3f, 0.2f};
      const MaterialRef ref = m->AddPlastic(*MakePlasticRow(d));
      const Vec3f wo = Chi2Direction(c.theta_deg, c.phi_deg);
      const PlasticParams p = PlasticRowParams(m->plastic, ref.index());
      const double ps = CoatingSpecularProbability(1.0f - CoatingFresnel(wo.z, p.eta),
                                                   p.specular_sampling_weight);
      const std::string name = std::string(simd ? "simd/shade_plastic" : "bsdf/plastic") +
                               Fmt("_eta%g_t%g", c.eta, c.theta_deg);
      std::string n2 = name;
      for (char& ch : n2)
        if (ch == '.') ch = 'p';
      r->Add(NonDeltaSubject(n2, Fmt("eta=%g theta_o=%g phi_o=%g", c.eta, c.theta_deg,
                                     c.phi_deg),
                             m, ref, wo, simd, (1.0 - ps) * kCosineSamplerMass));
    }
  }
  // Blends of a diffuse and a smooth plastic (delta lobe absorbed), at several weights.
  for (float w : {0.25f, 0.7f}) {
    for (bool simd : {false, true}) {
      auto m = std::make_shared<MaterialTables>();
      PlasticDesc d;
      d.int_ior = 1.5f, d.ext_ior = 1.0f, d.diffuse = {0.5f, 0.5f, 0.5f};
      const MaterialRef plastic = m->AddPlastic(*MakePlasticRow(d));
      const MaterialRef ref = m->AddBlend(w, m->AddDiffuse({0.8f, 0.8f, 0.8f}), plastic);
      const Vec3f wo = Chi2Direction(45, 70);
      const PlasticParams p = PlasticRowParams(m->plastic, plastic.index());
      const double ps = CoatingSpecularProbability(1.0f - CoatingFresnel(wo.z, p.eta),
                                                   p.specular_sampling_weight);
      std::string name = std::string(simd ? "simd/shade_blend" : "bsdf/blend") + Fmt("_w%g", w);
      for (char& ch : name)
        if (ch == '.') ch = 'p';
      r->Add(NonDeltaSubject(name, Fmt("weight=%g theta_o=45 phi_o=70", w), m, ref, wo, simd,
                             ((1.0 - w) + w * (1.0 - ps)) * kCosineSamplerMass));
    }
  }
  // Masks: the pass-through (Mitsuba's null lobe) is a delta sample, so the non-delta mass is
  // the opacity times the nested model's own: a diffuse one (known) and an anisotropic GGX
  // conductor with visible normals (unknown: some normals reflect below the horizon).
  struct MaskCase {
    float opacity, theta_deg;
    bool conductor;
  };
  for (const MaskCase& c : {MaskCase{0.3f, 40, false}, MaskCase{0.8f, 75, false},
                            MaskCase{0.6f, 50, true}}) {
    for (bool simd : {false, true}) {
      auto m = std::make_shared<MaterialTables>();
      const MaterialRef nested =
          c.conductor ? m->AddRoughConductor(0.15f, 0.45f, kMicrofacetGgx | kMicrofacetSampleVisible,
                                             {0.2f, 0.9f, 1.1f}, {3.9f, 2.4f, 2.1f}, {1, 1, 1})
                      : m->AddDiffuse({0.6f, 0.5f, 0.4f});
      const MaterialRef ref = m->AddMask(c.opacity, nested);
      const Vec3f wo = Chi2Direction(c.theta_deg, 30);
      std::string name = std::string(simd ? "simd/shade_mask" : "bsdf/mask") +
                         (c.conductor ? "_ggx_conductor" : "_diffuse") +
                         Fmt("_o%g_t%g", c.opacity, c.theta_deg);
      for (char& ch : name)
        if (ch == '.') ch = 'p';
      Chi2Subject subject =
          NonDeltaSubject(name, Fmt("opacity=%g theta_o=%g phi_o=30", c.opacity, c.theta_deg), m,
                          ref, wo, simd, c.opacity * kCosineSamplerMass);
      if (c.conductor) subject.albedo = kChi2UnknownAlbedo;
      r->Add(std::move(subject));
    }
  }
}

}  // namespace ptlab
