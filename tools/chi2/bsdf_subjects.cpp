// Chi-square subjects of the BSDFs: each model's Sample against its Pdf, scalar and SIMD.
#include "tools/chi2/bsdf_subjects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor.h"
#include "engine/bsdf/diffuse.h"
#include "engine/bsdf/rough_plastic.h"
#include "engine/wavefront/bsdf.h"
#include "engine/core/check.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"
#include "tools/chi2/lobe_disk.h"
#include "tools/chi2/microfacet_subjects.h"  // matA
#include "tools/chi2/perturbed_subjects.h"
#include "tools/chi2/principled_subjects.h"  // principled
#include "tools/chi2/stats_math.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// A gold-like conductor: the IOR does not enter sampling or the pdf, only the weights.
const Color3f kConductorEta{0.2f, 0.92f, 1.1f}, kConductorK{3.9f, 2.45f, 2.14f};
constexpr float kPlasticIntIor = 1.5046f, kPlasticExtIor = 1.000277f;

// SampleCosineHemisphere returns z = 0 for about a third of the u on the unit square's edge
// (u.x or u.y ∈ {0, 1 − 2⁻²⁴}: ~8e-8 of the draws), and DiffuseSample / RoughPlasticSample then
// return no sample. A mass just below 1 makes their subjects "defective" for the lab, so such a
// rare sample counts in the absorbed cell (expected ~0 samples: pooled) instead of failing the
// test outright; a sampler that loses a real fraction of its mass still fails the χ² (the
// absorbed count joins the pooled cell of tiny expectations), and the pdf must still integrate
// to 1 within the lab's tolerance. (No such sample occurs with the fixed seed.)
constexpr double kCosineSamplerMass = 1.0 - 1e-12;

// The kernels take up to this many rows per call from plain stack arrays.
constexpr int kBatch = 256;

struct Incidence {
  float theta_deg, phi_deg;
};
constexpr Incidence kIncidences[] = {{0, 0}, {30, 35}, {60, 110}, {85, 250}};

// "0.05" -> "0p05": names stay valid GoogleTest parameter names.
std::string Tag(const char* prefix, float v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%s%g", prefix, double(v));
  std::string s = buf;
  for (char& c : s)
    if (c == '.') c = 'p';
  return s;
}

std::string Params(float alpha, const Incidence& in, bool has_alpha) {
  char buf[96];
  if (has_alpha) {
    std::snprintf(buf, sizeof(buf), "alpha=%g theta_o=%g phi_o=%g", double(alpha),
                  double(in.theta_deg), double(in.phi_deg));
  } else {
    std::snprintf(buf, sizeof(buf), "theta_o=%g phi_o=%g", double(in.theta_deg),
                  double(in.phi_deg));
  }
  return buf;
}

std::shared_ptr<const MaterialTables> OneRowTables(Chi2BsdfModel model, float alpha,
                                                   MaterialRef* ref) {
  auto m = std::make_shared<MaterialTables>();
  switch (model) {
    case Chi2BsdfModel::kDiffuse:
      *ref = m->AddDiffuse(kChi2PlasticKd);
      break;
    case Chi2BsdfModel::kConductor:
      *ref = m->AddConductor(alpha, kConductorEta, kConductorK);
      break;
    case Chi2BsdfModel::kRoughPlastic:
      *ref = m->AddRoughPlastic(alpha, kPlasticIntIor, kPlasticExtIor, kChi2PlasticKd);
      break;
    case Chi2BsdfModel::kBeckmannReflection:
      PTLAB_CHECK(false);  // not a material
  }
  return m;
}

}  // namespace

// simd::ShadeBatch over n rows of one material: wo broadcast, no light evaluation.
Chi2BatchSampleFn ShadeBatchSampler(std::shared_ptr<const MaterialTables> m, MaterialRef ref,
                                    const Vec3f& wo, bool reject_delta) {
  return [m, ref, wo, reject_delta](const float* u1, const Vec2f* u2, int n, Chi2Point* p,
                                    uint8_t* ok) {
    float wo_x[kBatch], wo_y[kBatch], wo_z[kBatch], u_lobe[kBatch], u_x[kBatch], u_y[kBatch];
    float wi_x[kBatch], wi_y[kBatch], wi_z[kBatch], w_r[kBatch], w_g[kBatch], w_b[kBatch];
    float pdf[kBatch], eta[kBatch], delta[kBatch];
    uint32_t index[kBatch];
    for (int begin = 0; begin < n; begin += kBatch) {
      const int count = std::min(kBatch, n - begin);
      for (int i = 0; i < count; ++i) {
        wo_x[i] = wo.x, wo_y[i] = wo.y, wo_z[i] = wo.z;
        u_lobe[i] = u1[begin + i], u_x[i] = u2[begin + i].x, u_y[i] = u2[begin + i].y;
        index[i] = ref.index();
      }
      ShadeInputs in;
      in.wo = {wo_x, wo_y, wo_z};
      in.u_lobe = u_lobe, in.u_x = u_x, in.u_y = u_y;
      ShadeOutputs out;
      out.wi = {wi_x, wi_y, wi_z};
      out.weight = {w_r, w_g, w_b};
      out.pdf = pdf;
      out.eta = eta;
      if (reject_delta) out.delta = delta;
      simd::ShadeBatch(*m, ref.tag(), index, size_t(count), in, out);
      for (int i = 0; i < count; ++i) {
        ok[begin + i] = pdf[i] > 0 && !(reject_delta && delta[i] != 0) ? 1 : 0;
        p[begin + i] = {wi_x[i], wi_y[i], wi_z[i]};
      }
    }
  };
}

namespace {

// (simd::)SampleBeckmannReflectionBatch: reflect wo about h ~ BeckmannPdfH.
Chi2BatchSampleFn BeckmannReflectionSampler(Chi2BsdfPath path, float alpha, const Vec3f& wo) {
  return [path, alpha, wo](const float* /*u1*/, const Vec2f* u2, int n, Chi2Point* p, uint8_t* ok) {
    float a[kBatch], wo_x[kBatch], wo_y[kBatch], wo_z[kBatch], u_x[kBatch], u_y[kBatch];
    float wi_x[kBatch], wi_y[kBatch], wi_z[kBatch], pdf[kBatch];
    for (int begin = 0; begin < n; begin += kBatch) {
      const int count = std::min(kBatch, n - begin);
      for (int i = 0; i < count; ++i) {
        a[i] = alpha, wo_x[i] = wo.x, wo_y[i] = wo.y, wo_z[i] = wo.z;
        u_x[i] = u2[begin + i].x, u_y[i] = u2[begin + i].y;
      }
      const DirectionArrays o{wo_x, wo_y, wo_z};
      const DirectionOutArrays wi{wi_x, wi_y, wi_z};
      if (path == Chi2BsdfPath::kSimd) {
        simd::SampleBeckmannReflectionBatch(a, o, u_x, u_y, size_t(count), wi, pdf);
      } else {
        SampleBeckmannReflectionBatch(a, o, u_x, u_y, size_t(count), wi, pdf);
      }
      for (int i = 0; i < count; ++i) {
        ok[begin + i] = pdf[i] > 0 ? 1 : 0;
        p[begin + i] = {wi_x[i], wi_y[i], wi_z[i]};
      }
    }
  };
}

Vec3f MirrorDirection(const Vec3f& wo) { return {-wo.x, -wo.y, wo.z}; }

// A subject on the hemisphere, moved to a LobeDisk around the mirror direction when its
// specular lobe is too narrow for the hemisphere grid.
// The models see α clamped (ClampBeckmannAlpha), so the zoom does too.
Chi2Subject Placed(Chi2Subject s, Chi2BsdfModel model, float alpha, const Vec3f& wo) {
  alpha = ClampBeckmannAlpha(alpha);
  if (model == Chi2BsdfModel::kDiffuse || !(alpha < kChi2BsdfZoomAlpha)) return s;
  return OnLobeDisk(std::move(s), LobeDisk(MirrorDirection(wo), 2.0 * alpha));
}

}  // namespace

double BeckmannReflectionAlbedo(float alpha, float cos_theta_o) {
  PTLAB_CHECK(cos_theta_o > 0);
  const double a = ClampBeckmannAlpha(alpha);
  const double ct = std::min(double(cos_theta_o), 1.0), st = std::sqrt(1.0 - ct * ct);
  const auto escape = [a, ct, st](double phi) {
    const double theta_max = 0.5 * std::atan2(st * std::cos(phi), ct) + 0.25 * kPiD;
    const double t = std::tan(theta_max);
    return -std::expm1(-(t * t) / (a * a));
  };
  SimpsonOptions options;
  options.rel_tol = 1e-12;
  options.min_depth = 6;
  options.max_depth = 24;
  return AdaptiveSimpson(escape, 0.0, 2.0 * kPiD, options) / (2.0 * kPiD);
}

Vec3f Chi2Direction(float theta_deg, float phi_deg) {
  const double t = theta_deg * kPiD / 180.0, p = phi_deg * kPiD / 180.0;
  return {float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t))};
}

namespace {

// The subject before placement: on the hemisphere.
Chi2Subject HemisphereSubject(std::string name, Chi2BsdfModel model, Chi2BsdfPath path, float alpha,
                              const Vec3f& wo) {
  PTLAB_CHECK(wo.z > 0);
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = Chi2Domain::Hemisphere();
  if (model == Chi2BsdfModel::kDiffuse) {
    s.albedo = kCosineSamplerMass;
  } else {
    s.albedo = BeckmannReflectionAlbedo(alpha, wo.z);
  }
  if (model == Chi2BsdfModel::kBeckmannReflection) {
    s.sample_batch = BeckmannReflectionSampler(path, alpha, wo);
    s.pdf = [alpha, wo](const Chi2Point& wi) {
      return double(BeckmannReflectionPdf(alpha, wo, wi));
    };
    const double peak = s.pdf(MirrorDirection(wo));
    s.pdf = FlushLobeTail(std::move(s.pdf), peak);
    return s;
  }
  MaterialRef ref;
  const std::shared_ptr<const MaterialTables> m = OneRowTables(model, alpha, &ref);
  // The pdf is BsdfPdf of the same table row for both paths: the scalar oracle.
  s.pdf = [m, ref, wo](const Chi2Point& wi) { return double(BsdfPdf(*m, ref, wo, wi)); };
  // The pure lobe's far tail is zeroed (see FlushLobeTail). Not the rough plastic's: its
  // diffuse part, ∝ cosθi, would be cut near the horizon by a floor set by a sharp lobe's peak.
  if (model == Chi2BsdfModel::kConductor) {
    const double peak = s.pdf(MirrorDirection(wo));  // about the lobe's maximum
    s.pdf = FlushLobeTail(std::move(s.pdf), peak);
  }
  if (path == Chi2BsdfPath::kSimd) s.sample_batch = ShadeBatchSampler(m, ref, wo);
  // The scalar path calls the per-model entry points (what BsdfSampleDirection dispatches to).
  if (model == Chi2BsdfModel::kDiffuse && path == Chi2BsdfPath::kScalar) {
    s.sample = [wo](float, const Vec2f& u, Chi2Point* p) {
      BsdfSample bs;
      if (!DiffuseSample(kChi2PlasticKd, wo, u, &bs)) return false;
      *p = bs.wi;
      return true;
    };
  }
  if (model == Chi2BsdfModel::kConductor && path == Chi2BsdfPath::kScalar) {
    ConductorParams params;
    params.alpha = alpha, params.eta = kConductorEta, params.k = kConductorK;
    s.sample = [params, wo](float, const Vec2f& u, Chi2Point* p) {
      BsdfSample bs;
      if (!ConductorSample(params, wo, u, &bs)) return false;
      *p = bs.wi;
      return true;
    };
  }
  if (model == Chi2BsdfModel::kRoughPlastic) {
    const RoughPlasticParams params =
        MakeRoughPlasticParams(alpha, kPlasticIntIor, kPlasticExtIor, kChi2PlasticKd);
    // Only the specular pick absorbs (below the horizon); cosine samples always stay.
    s.albedo = std::min(params.ks * s.albedo + (1.0 - params.ks), kCosineSamplerMass);
    s.uniform_dims = 3;
    if (path == Chi2BsdfPath::kScalar) {
      s.sample = [params, wo](float u1, const Vec2f& u, Chi2Point* p) {
        BsdfSample bs;
        if (!RoughPlasticSample(params, wo, u1, u, &bs)) return false;
        *p = bs.wi;
        return true;
      };
    }
  }
  return s;
}

}  // namespace

Chi2Subject BsdfChi2Subject(std::string name, Chi2BsdfModel model, Chi2BsdfPath path, float alpha,
                            const Vec3f& wo, bool zoom) {
  Chi2Subject s = HemisphereSubject(std::move(name), model, path, alpha, wo);
  return zoom ? Placed(std::move(s), model, alpha, wo) : s;
}

void RegisterBsdfSubjects(Chi2Registry* r) {
  constexpr Chi2BsdfPath kScalar = Chi2BsdfPath::kScalar, kSimd = Chi2BsdfPath::kSimd;
  const auto add = [r](const char* model_name, Chi2BsdfModel model, Chi2BsdfPath path, float alpha,
                       const Incidence& in) {
    const bool has_alpha = model != Chi2BsdfModel::kDiffuse;
    std::string name =
        std::string(model_name) + (has_alpha ? Tag("_a", alpha) : "") + Tag("_t", in.theta_deg);
    Chi2Subject s = BsdfChi2Subject(std::move(name), model, path, alpha,
                                    Chi2Direction(in.theta_deg, in.phi_deg));
    s.params = Params(alpha, in, has_alpha) + (s.params.empty() ? "" : " " + s.params);
    if (path == Chi2BsdfPath::kSimd) s.params += std::string(" target=") + simd::DispatchedTargetName();
    // Rough Beckmann reflection loses samples below the horizon (absorbed: no direction), so
    // fewer land in the cells and a 2 % error of the pdf is caught with less than 95 %
    // probability at 10^6 samples (chi2 --power: 0.91 at α = 1, 0.14 at α = 2, θ = 0°); these
    // subjects draw more (docs/chi2-power.md lists every subject's power).
    const bool beckmann_reflection =
        model == Chi2BsdfModel::kConductor || model == Chi2BsdfModel::kBeckmannReflection;
    if (beckmann_reflection && alpha >= 0.5f) s.sample_scale = alpha >= 2.0f ? 4 : 2;
    r->Add(std::move(s));
  };
  for (const Incidence& in : kIncidences)
    add("bsdf/diffuse", Chi2BsdfModel::kDiffuse, kScalar, 0, in);
  for (float alpha : {0.005f, 0.05f, 0.2f, 0.5f, 1.0f})
    for (const Incidence& in : kIncidences)
      add("bsdf/conductor", Chi2BsdfModel::kConductor, kScalar, alpha, in);
  // The roughness limits: α = 1e-4 (kBeckmannMinAlpha) and 2.
  add("bsdf/conductor", Chi2BsdfModel::kConductor, kScalar, 1e-4f, kIncidences[0]);
  add("bsdf/conductor", Chi2BsdfModel::kConductor, kScalar, 1e-4f, kIncidences[2]);
  for (int i : {0, 2, 3})
    add("bsdf/conductor", Chi2BsdfModel::kConductor, kScalar, 2.0f, kIncidences[i]);
  for (float alpha : {0.005f, 0.05f, 0.2f, 0.5f, 1.0f})
    for (const Incidence& in : kIncidences)
      add("bsdf/rough_plastic", Chi2BsdfModel::kRoughPlastic, kScalar, alpha, in);

  add("simd/beckmann_reflection", Chi2BsdfModel::kBeckmannReflection, kSimd, 0.005f,
      kIncidences[1]);
  add("simd/beckmann_reflection", Chi2BsdfModel::kBeckmannReflection, kSimd, 0.05f, kIncidences[2]);
  add("simd/beckmann_reflection", Chi2BsdfModel::kBeckmannReflection, kSimd, 0.5f, kIncidences[3]);
  add("simd/shade_diffuse", Chi2BsdfModel::kDiffuse, kSimd, 0, kIncidences[2]);
  add("simd/shade_conductor", Chi2BsdfModel::kConductor, kSimd, 0.05f, kIncidences[1]);
  add("simd/shade_conductor", Chi2BsdfModel::kConductor, kSimd, 0.5f, kIncidences[3]);
  add("simd/shade_rough_plastic", Chi2BsdfModel::kRoughPlastic, kSimd, 0.05f, kIncidences[2]);
  add("simd/shade_rough_plastic", Chi2BsdfModel::kRoughPlastic, kSimd, 0.5f, kIncidences[1]);
  RegisterCoatedBsdfSubjects(r);  // matB
  RegisterMicrofacetBsdfSubjects(r);  // matA: the Mitsuba microfacet models
  RegisterPrincipledBsdfSubjects(r);  // principled: principled and principledthin
  RegisterPerturbedBsdfSubjects(r);   // normal: normalmap and bumpmap

  // Deliberately wrong pdfs for the right samplers. Both keep the true albedo, so the lab
  // compares their integral (and the absorbed count) with the sampler's actual mass.
  constexpr Chi2Expect kFail = Chi2Expect::kFail;
  {
    const float alpha = 0.2f;
    const Incidence in = kIncidences[1];
    const Vec3f wo = Chi2Direction(in.theta_deg, in.phi_deg);
    Chi2Subject s = HemisphereSubject("broken/conductor_pdf_no_reflection_jacobian",
                                      Chi2BsdfModel::kConductor, kScalar, alpha, wo);
    s.pdf = [alpha, wo](const Chi2Point& wi) {
      if (!(wi.z > 0)) return 0.0;
      return double(BeckmannPdfH(alpha, Normalize(wo + wi)));  // missing 1 / (4 wo·h)
    };
    s.params = Params(alpha, in, true);
    s.expect = kFail;
    r->Add(Placed(std::move(s), Chi2BsdfModel::kConductor, alpha, wo));
  }
  {
    const float alpha = 0.5f;
    const Incidence in = kIncidences[1];
    const Vec3f wo = Chi2Direction(in.theta_deg, in.phi_deg);
    Chi2Subject s = HemisphereSubject("broken/rough_plastic_pdf_swapped_weights",
                                      Chi2BsdfModel::kRoughPlastic, kScalar, alpha, wo);
    const RoughPlasticParams p =
        MakeRoughPlasticParams(alpha, kPlasticIntIor, kPlasticExtIor, kChi2PlasticKd);
    s.pdf = [p, wo](const Chi2Point& wi) {
      if (!(wi.z > 0)) return 0.0;
      return double((1.0f - p.ks) * BeckmannReflectionPdf(p.alpha, wo, wi) +
                    p.ks * (wi.z * kInvPi));
    };
    s.params = Params(alpha, in, true);
    s.expect = kFail;
    r->Add(Placed(std::move(s), Chi2BsdfModel::kRoughPlastic, alpha, wo));
  }
}

}  // namespace ptlab
