// Load-time terms of Mitsuba's coated plastics, computed by numerical integration.
#include "engine/bsdf/plastic_precompute.h"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <algorithm>
#include <cmath>

#include "engine/bsdf/beckmann.h"  // ReflectAbout
#include "engine/bsdf/fresnel.h"
#include "engine/bsdf/microfacet.h"

namespace ptlab {
namespace {

/// ∫_a^b f by 61-point Gauss–Kronrod, adaptive (the integrands here are smooth on [a, b]).
template <class F>
double Integrate(F f, double a, double b) {
  if (!(b > a)) return 0.0;
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 15, 1e-12);
}

/// ∫∫_[0,1]² f(u) du by a 48 × 48 Gauss–Legendre product rule.
template <class F>
double IntegrateSquare(F f) {
  using Rule = boost::math::quadrature::gauss<double, 48>;
  return Rule::integrate(
      [&](double ux) {
        return Rule::integrate([&](double uy) { return f(Vec2f{float(ux), float(uy)}); }, 0.0,
                               1.0);
      },
      0.0, 1.0);
}

/// The energy a rough interface of relative IOR eta (light on the side of w, w.z > 0) sends
/// back into w's hemisphere, Smith-shadowed: E_{m ~ D_w}[F(w·m) G1(reflect(w, m), m)], D_w the
/// visible normals seen from w (whose pdf cancels G1(w) (w·m) D / w.z of the BRDF).
double RoughReflectance(const Microfacet& dist, float eta, float cos_theta) {
  const float c = std::max(cos_theta, 1e-6f);
  const Vec3f w{std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c};
  return IntegrateSquare([&](const Vec2f& u) {
    float pdf = 0.0f;
    const Vec3f m = SampleMicrofacet(dist, w, u, &pdf);
    if (!(pdf > 0)) return 0.0;
    const Vec3f r = ReflectAbout(w, m);
    if (!(r.z > 0)) return 0.0;
    float cos_t;
    return double(FresnelDielectric(Dot(w, m), eta, &cos_t)) * double(MicrofacetG1(dist, r, m));
  });
}

/// The energy it transmits: E_{m ~ D_w}[(1 − F(w·m)) G1(t, m)], t the refraction of w about m.
double RoughTransmittance(const Microfacet& dist, float eta, float cos_theta) {
  const float c = std::max(cos_theta, 1e-6f);
  const Vec3f w{std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c};
  return IntegrateSquare([&](const Vec2f& u) {
    float pdf = 0.0f;
    const Vec3f m = SampleMicrofacet(dist, w, u, &pdf);
    if (!(pdf > 0)) return 0.0;
    const float wm = Dot(w, m);
    float cos_t;
    const float f = FresnelDielectric(wm, eta, &cos_t);
    if (!(f < 1.0f)) return 0.0;
    // t = −w/η + (w·m/η − cos θt) m, below the surface.
    const float inv = 1.0f / eta;
    const Vec3f t = m * (wm * inv - cos_t) - w * inv;
    return double(1.0f - f) * double(MicrofacetG1(dist, t, m));
  });
}

}  // namespace

double InternalDiffuseFresnel(double eta) {
  eta = ClampRelativeIor(float(eta));
  // From inside, the relative index is 1/η; total internal reflection (F = 1) below
  // μc = sqrt(1 − 1/η²) when η > 1, whose part of the integral is exactly μc².
  const double mu_c = eta > 1 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
  const auto integrand = [eta](double mu) {
    float cos_t;
    return 2.0 * double(FresnelDielectric(-float(mu), float(eta), &cos_t)) * mu;
  };
  return mu_c * mu_c + Integrate(integrand, mu_c, 1.0);
}

StatusOr<PlasticRow> MakePlasticRow(const PlasticDesc& desc) {
  PlasticRow row;
  row.distribution = desc.distribution;
  row.alpha = desc.alpha;
  row.eta = desc.int_ior / desc.ext_ior;
  double f_int = 0.0;
  if (desc.distribution == CoatingDistribution::kSmooth) {
    f_int = InternalDiffuseFresnel(row.eta);
  } else {
    const Microfacet dist = MakeMicrofacet(desc.distribution == CoatingDistribution::kGgx
                                               ? MicrofacetType::kGgx
                                               : MicrofacetType::kBeckmann,
                                           desc.alpha, desc.alpha);
    for (int j = 0; j < kCoatingTransmittanceRes; ++j) {
      const float mu = std::max(1e-6f, float(j) / float(kCoatingTransmittanceRes - 1));
      row.transmittance[j] = float(std::clamp(RoughTransmittance(dist, row.eta, mu), 0.0, 1.0));
    }
    // R_int: Mitsuba defines it as 2 × the mean of R(μ; 1/η) μ over the same 64 cosines as the
    // table (μ = max(1e-6, j/63); the light inside meets the coating with relative IOR 1/η),
    // a Riemann sum ~1.5 % below the integral 2 ∫ R μ dμ. Its references are rendered with
    // that sum, so it is used here too; each R(μ) is integrated as above.
    for (int j = 0; j < kCoatingTransmittanceRes; ++j) {
      const float mu = std::max(1e-6f, float(j) / float(kCoatingTransmittanceRes - 1));
      f_int += RoughReflectance(dist, 1.0f / row.eta, mu) * mu;
    }
    f_int *= 2.0 / kCoatingTransmittanceRes;
    f_int = std::clamp(f_int, 0.0, 0.999999);
  }
  const double inv_eta2 = 1.0 / (double(row.eta) * double(row.eta));
  const auto base = [&](float rho) {
    const double denom = 1.0 - (desc.nonlinear ? double(rho) * f_int : f_int);
    // Nonsense IORs (η → 1e-4 makes the coating a perfect internal mirror) could overflow:
    // the base is held finite, so f and the weights stay finite too.
    const double b = denom > 0 ? double(rho) / denom * inv_eta2 : 1e30;
    return float(std::min(b, 1e30));
  };
  row.base = {base(desc.diffuse.r), base(desc.diffuse.g), base(desc.diffuse.b)};
  row.specular = desc.specular;
  const float d_mean = (desc.diffuse.r + desc.diffuse.g + desc.diffuse.b) / 3.0f;
  const float s_mean = (desc.specular.r + desc.specular.g + desc.specular.b) / 3.0f;
  row.specular_sampling_weight = d_mean + s_mean > 0 ? s_mean / (d_mean + s_mean) : 0.5f;
  return row;
}

}  // namespace ptlab
