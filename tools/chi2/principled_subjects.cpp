// Chi-square subjects of Mitsuba's principled and principledthin BSDFs: BsdfSampleDirection's
// directions against BsdfPdf, over the whole sphere (transmission lobes), for parameter sets
// that exercise every lobe (diffuse + sheen, anisotropic metal, clearcoat, rough glass from
// outside and inside, the thin model's four lobes), scalar and through simd::ShadeBatch.
#include "tools/chi2/principled_subjects.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tools/chi2/bsdf_subjects.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Case {
  const char* name;
  bool thin;
  PrincipledRow row;
  float theta_deg;  // > 90: wo below the surface
  bool simd;
};

PrincipledRow Row(Color3f base, float roughness, float anisotropic, float metallic,
                  float spec_trans, float clearcoat, float gloss, float sheen, float eta,
                  float diff_trans = 0, float spec_tint = 0, float flatness = 0) {
  PrincipledRow r;
  r.base_color = base;
  r.value[kPrincipledRoughness] = roughness;
  r.value[kPrincipledAnisotropic] = anisotropic;
  r.value[kPrincipledMetallic] = metallic;
  r.value[kPrincipledSpecTrans] = spec_trans;
  r.value[kPrincipledClearcoat] = clearcoat;
  r.value[kPrincipledClearcoatGloss] = gloss;
  r.value[kPrincipledSheen] = sheen;
  r.value[kPrincipledSheenTint] = 0.5f;
  r.value[kPrincipledEta] = eta;
  r.value[kPrincipledDiffTrans] = diff_trans;
  r.value[kPrincipledSpecTint] = spec_tint;
  r.value[kPrincipledFlatness] = flatness;
  return r;
}

Chi2Subject Subject(const Case& c) {
  const double t = c.theta_deg * kPiD / 180, p = 0.6;  // azimuth off the tangent axes
  const Vec3f wo{float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                 float(std::cos(t))};
  auto m = std::make_shared<MaterialTables>();
  const MaterialRef ref = m->AddPrincipled(c.row, c.thin);
  Chi2Subject s;
  char name[160];
  std::snprintf(name, sizeof(name), "%s%s_t%g", c.simd ? "simd/shade_" : "bsdf/", c.name,
                double(c.theta_deg));
  s.name = name;
  s.domain = Chi2Domain::Sphere();
  s.albedo = kChi2UnknownAlbedo;  // lobes are lost below the horizon
  s.uniform_dims = 3;
  s.pdf = [m, ref, wo](const Chi2Point& wi) { return double(BsdfPdf(*m, ref, wo, wi)); };
  if (c.simd) {
    s.sample_batch = ShadeBatchSampler(m, ref, wo);
  } else {
    s.sample = [m, ref, wo](float u1, const Vec2f& u2, Chi2Point* pt) {
      BsdfSample bs;
      if (!BsdfSampleDirection(*m, ref, wo, u1, u2, &bs)) return false;
      *pt = bs.wi;
      return true;
    };
  }
  char params[200];
  std::snprintf(params, sizeof(params), "roughness=%g anisotropic=%g theta_o=%g%s",
                double(c.row.value[kPrincipledRoughness]),
                double(c.row.value[kPrincipledAnisotropic]), double(c.theta_deg),
                c.simd ? " target=" : "");
  s.params = params;
  if (c.simd) s.params += simd::DispatchedTargetName();
  s.sample_scale = 2;  // several lobes of different widths
  return s;
}

}  // namespace

void RegisterPrincipledBsdfSubjects(Chi2Registry* r) {
  const Color3f green{0.2f, 0.8f, 0.1f}, blue{0.3f, 0.6f, 0.8f}, red{0.7f, 0.1f, 0.1f};
  const Case cases[] = {
      // principled: plastic-like with sheen and fake subsurface.
      {"principled_diffuse_sheen", false, Row(green, 0.5f, 0, 0, 0, 0, 0, 0.9f, 1.5f, 0, 0.5f, 1),
       40, false},
      // anisotropic metal with a clearcoat (the suite's principled1 at its extremes).
      {"principled_metal_aniso_clearcoat", false,
       Row(green, 0.3f, 0.8f, 0.7f, 0, 0.9f, 0.3f, 0.2f, 1.62f), 30, false},
      {"principled_metal_aniso_clearcoat", false,
       Row(green, 0.3f, 0.8f, 0.7f, 0, 0.9f, 0.3f, 0.2f, 1.62f), 75, false},
      // rough glass with clearcoat and sheen (principled2), from outside and inside.
      {"principled_glass", false, Row(blue, 0.4f, 0.2f, 0, 0.7f, 0.6f, 0, 0.9f, 1.38f), 20,
       false},
      {"principled_glass", false, Row(blue, 0.4f, 0.2f, 0, 0.7f, 0.6f, 0, 0.9f, 1.38f), 135,
       false},
      // η = 1.2 (near 1 the transmitted lobe shrinks to a spike of width ~(η − 1)·θm that the
      // lab's grid cannot resolve: η = 1.001 fails on integration, not on sampling).
      {"principled_glass_eta1p2", false, Row(blue, 0.6f, 0, 0, 1, 0, 0, 0, 1.2f), 50, false},
      // principledthin: all four lobes, from both sides.
      {"principledthin", true,
       Row(red, 0.5f, 0.8f, 0, 0.8f, 0, 0, 0.8f, 1.33f, 0.7f, 0.5f, 0.5f), 35, false},
      {"principledthin", true, Row(red, 0.5f, 0.05f, 0, 0.2f, 0, 0, 0.1f, 1.33f, 0.2f), 120,
       false},
      {"principledthin_glossy", true, Row(red, 0.3f, 0, 0, 1, 0, 0, 0, 2.0f), 60, false},
      // Through the SIMD shading stage.
      {"principled_metal_aniso_clearcoat", false,
       Row(green, 0.3f, 0.8f, 0.7f, 0, 0.9f, 0.3f, 0.2f, 1.62f), 50, true},
      {"principled_glass", false, Row(blue, 0.4f, 0.2f, 0, 0.7f, 0.6f, 0, 0.9f, 1.38f), 140,
       true},
      {"principledthin", true,
       Row(red, 0.5f, 0.8f, 0, 0.8f, 0, 0, 0.8f, 1.33f, 0.7f, 0.5f, 0.5f), 60, true},
  };
  for (const Case& c : cases) r->Add(Subject(c));
}

}  // namespace ptlab
