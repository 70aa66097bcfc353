// Chi-square subjects of the Mitsuba microfacet models: rough conductor and rough dielectric.
#include "tools/chi2/microfacet_subjects.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tools/chi2/bsdf_subjects.h"
#include "tools/chi2/lobe_disk.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Case {
  bool dielectric;
  bool ggx, visible;
  float au, av;
  float eta;       // dielectric only
  float theta_deg;  // > 90: wo below the surface
  bool simd;
};

std::string Name(const Case& c) {
  char buf[160];
  const char* prefix = c.simd ? (c.dielectric ? "simd/shade_rough_dielectric_"
                                              : "simd/shade_rough_conductor_")
                              : (c.dielectric ? "bsdf/rough_dielectric_"
                                              : "bsdf/rough_conductor_");
  std::snprintf(buf, sizeof(buf), "%s%s%s_a%g", prefix, c.ggx ? "ggx" : "beckmann",
                c.visible ? "" : "_dcos", double(c.au));
  std::string s = buf;
  if (c.av != c.au) {
    std::snprintf(buf, sizeof(buf), "x%g", double(c.av));
    s += buf;
  }
  if (c.dielectric) {
    std::snprintf(buf, sizeof(buf), "_eta%g", double(c.eta));
    s += buf;
  }
  std::snprintf(buf, sizeof(buf), "_t%g", double(c.theta_deg));
  s += buf;
  for (char& ch : s)
    if (ch == '.') ch = 'p';
  return s;
}

Chi2Subject Subject(const Case& c) {
  const double t = c.theta_deg * kPiD / 180, p = 0.6;  // azimuth off the tangent axes
  const Vec3f wo{float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                 float(std::cos(t))};
  auto m = std::make_shared<MaterialTables>();
  const uint8_t flags = uint8_t((c.ggx ? kMicrofacetGgx : 0) |
                                (c.visible ? kMicrofacetSampleVisible : 0));
  // A gold-like conductor and clear glass: the colours do not enter sampling or the pdf.
  const MaterialRef ref =
      c.dielectric ? m->AddRoughDielectric(c.au, c.av, flags, c.eta, 1.0f)
                   : m->AddRoughConductor(c.au, c.av, flags, {0.2f, 0.92f, 1.1f},
                                          {3.9f, 2.45f, 2.14f}, {1, 1, 1});
  Chi2Subject s;
  s.name = Name(c);
  s.domain = c.dielectric ? Chi2Domain::Sphere() : Chi2Domain::Hemisphere();
  s.albedo = kChi2UnknownAlbedo;
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
  char params[160];
  std::snprintf(params, sizeof(params), "alpha_u=%g alpha_v=%g theta_o=%g%s", double(c.au),
                double(c.av), double(c.theta_deg), c.simd ? " target=" : "");
  s.params = params;
  if (c.simd) s.params += simd::DispatchedTargetName();
  // Wide lobes lose many samples (absorbed) and spread thin: more samples keep the lab's power
  // (≥ 95 % against a 2 % smooth error). D cos θ sampling of glass at normal incidence puts
  // most samples in the narrow reflected and transmitted peaks: 0.76 at 10⁶ samples, so 4×.
  if (std::fmax(c.au, c.av) >= 0.5f) s.sample_scale = 2;
  if (c.dielectric && !c.visible && c.theta_deg == 0) s.sample_scale = 4;
  // Narrow reflection lobes on a disk around the mirror direction (k = 2α, as bsdf_subjects).
  const float a = std::fmax(c.au, c.av);
  if (!c.dielectric && a < 0.3f) return OnLobeDisk(std::move(s), LobeDisk({-wo.x, -wo.y, wo.z}, 2.0 * a));
  return s;
}

}  // namespace

void RegisterMicrofacetBsdfSubjects(Chi2Registry* r) {
  const Case cases[] = {
      // Rough conductor, scalar.
      {false, true, true, 0.1f, 0.1f, 1, 30, false},
      {false, true, true, 0.5f, 0.5f, 1, 60, false},
      {false, true, true, 0.3f, 0.8f, 1, 45, false},
      {false, false, true, 0.05f, 0.05f, 1, 0, false},
      {false, false, true, 0.3f, 0.3f, 1, 85, false},
      {false, false, true, 0.6f, 0.3f, 1, 30, false},
      {false, false, false, 0.5f, 0.5f, 1, 30, false},
      {false, true, false, 0.3f, 0.3f, 1, 60, false},
      // Rough dielectric, scalar (θ > 90°: from inside; 150° is beyond the critical angle).
      {true, true, true, 0.3f, 0.3f, 1.5f, 30, false},
      {true, false, true, 0.5f, 0.5f, 1.5f, 70, false},
      {true, true, false, 0.3f, 0.3f, 1.5f, 0, false},
      {true, false, true, 0.3f, 0.3f, 1.5f, 150, false},
      {true, true, true, 0.2f, 0.6f, 1.0f / 1.33f, 45, false},
      // The SIMD kernels.
      {false, true, true, 0.3f, 0.3f, 1, 30, true},
      {false, false, true, 0.5f, 0.3f, 1, 60, true},
      {true, true, true, 0.3f, 0.3f, 1.5f, 60, true},
      {true, false, false, 0.5f, 0.5f, 1.5f, 140, true},
  };
  for (const Case& c : cases) r->Add(Subject(c));
}

}  // namespace ptlab
