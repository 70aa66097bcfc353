// Fresnel reflectance: exact unpolarised dielectric (with TIR), Schlick, conductors.
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/core/vec.h"

namespace ptlab {

// Where a sum cancels (η² − sin²θ near the critical angle, η² − κ² − sin²θ), the formulas are
// arranged so that no precision is lost beyond the input's own conditioning: η² − 1 is formed
// as (η − 1)(η + 1), and cos²θ is kept as c·c rather than recovered from 1 − sin²θ (which
// would lose it entirely below cos θ ≈ 2.4e-4). The SIMD twins in simd/wavefront/bsdf8-inl.h round
// the products of these sums exactly as this code does (no FMA contraction there).

/// Relative IORs are clamped into [kMinRelativeIor, kMaxRelativeIor] (NaN → the minimum), so
/// denormal or huge parameters cannot overflow η².
inline constexpr float kMinRelativeIor = 1e-4f;
inline constexpr float kMaxRelativeIor = 1e4f;

inline float ClampRelativeIor(float eta) {
  return !(eta > kMinRelativeIor) ? kMinRelativeIor
                                  : (eta < kMaxRelativeIor ? eta : kMaxRelativeIor);
}
/// |c| clamped to [0, 1]; NaN → 1.
inline float ClampCosine(float c) {
  const float a = std::fabs(c);
  return a < 1.0f ? a : 1.0f;
}

/// Unpolarised Fresnel reflectance of a smooth dielectric interface for light arriving with
/// cosine cos_i w.r.t. the normal on the exterior side (negative = from inside), relative IOR
/// eta = η_int / η_ext (clamped, see above). Returns 1 under total internal reflection (including
/// exactly at the critical angle, and at exactly grazing incidence) and sets *cos_t to the
/// (non-negative) cosine of the refracted direction (0 under TIR). For η = 1 it returns 0 and
/// cos_t = |cos_i| at every angle but exactly grazing.
inline float FresnelDielectric(float cos_i, float eta, float* cos_t) {
  eta = ClampRelativeIor(eta);
  if (cos_i < 0) eta = 1.0f / eta;
  const float c = ClampCosine(cos_i);
  const float p = (eta - 1.0f) * (eta + 1.0f) + c * c;  // (η cos θt)² = η² − sin² θi
  if (!(p > 0)) {
    *cos_t = 0.0f;
    return 1.0f;
  }
  const float eta_ct = std::sqrt(p);               // η cos θt
  const float ct_over_eta = eta_ct / (eta * eta);  // cos θt / η
  const float rs = (c - eta_ct) / (c + eta_ct);    // (cos i − η cos t) / (cos i + η cos t)
  const float rp = (c - ct_over_eta) / (c + ct_over_eta);  // (η cos i − cos t) / (η cos i + cos t)
  *cos_t = eta_ct / eta;
  return 0.5f * (rs * rs + rp * rp);
}

/// Schlick's approximation R0 + (1 − R0)(1 − |cos_i|)^5 with R0 = ((η − 1)/(η + 1))², evaluated
/// with the cosine on the incident side as UC Berkeley CS184's GlassBSDF does. It does not
/// detect total internal reflection; callers test that separately (FresnelDielectric's cos_t).
inline float FresnelSchlick(float cos_i, float eta) {
  eta = ClampRelativeIor(eta);
  const float r = (eta - 1.0f) / (eta + 1.0f);
  const float r0 = r * r;
  const float m = 1.0f - ClampCosine(cos_i);
  const float m2 = m * m;
  return r0 + (1.0f - r0) * (m2 * m2 * m);
}

/// Conductor IOR components are clamped into [0, kMaxConductorIor] (NaN → 0).
inline constexpr float kMaxConductorIor = 1e4f;
inline float ClampConductorIor(float v) {
  return !(v > 0) ? 0.0f : (v < kMaxConductorIor ? v : kMaxConductorIor);
}

/// Unpolarised reflectance of a conductor with complex relative IOR η + iκ for light arriving
/// at cosine |cos_i| (clamped to [0, 1]). With (a + ib)² = η² − κ² − sin²θ + 2iηκ (Born & Wolf,
/// Principles of Optics §14.2), Rs = ((a − c)² + b²)/((a + c)² + b²) and
/// Rp = Rs ((ac − s²)² + (bc)²)/((ac + s²)² + (bc)²); the sums of squares replace the usual
/// a² + b² + c² − 2ac forms, which cancel. Result in [0, 1]; exactly 1 at grazing incidence.
inline float FresnelConductor(float cos_i, float eta, float k) {
  eta = ClampConductorIor(eta);
  k = ClampConductorIor(k);
  const float c = ClampCosine(cos_i);
  const float s2 = (1.0f - c) * (1.0f + c);
  const float t = (eta - k) * (eta + k) - s2;  // Re z = η² − κ² − sin²θ
  const float ek = eta * k;                    // Im z / 2 = ab
  const float abs_z = std::sqrt(t * t + 4.0f * (ek * ek));
  // a² = (|z| + t)/2, b² = (|z| − t)/2: take the non-cancelling root (a for t > 0, else b)
  // and divide for the other. A root below 1e-20 (only for |z| < 2e-40, so ek < 1e-40) divides
  // as 1e-20: where it is 0 (t is float's least denormal or 0 and |z| underflowed) the other is
  // then 0 instead of ek/0.
  const float root = std::sqrt(0.5f * (abs_z + std::abs(t)));
  const float other = ek / std::max(root, 1e-20f);
  const float a = t > 0 ? root : other, b = t > 0 ? other : root;
  const float b2 = b * b;
  const float am = a - c, ap = a + c;
  const float num_s = am * am + b2, den_s = ap * ap + b2;
  const float ac = a * c, bc = b * c;
  const float pm = ac - s2, pp = ac + s2;
  const float num_p = pm * pm + bc * bc, den_p = pp * pp + bc * bc;
  // (Rs + Rp)/2 with Rs = num_s/den_s and Rp = Rs·num_p/den_p, as one quotient, each term
  // + 1e-30. That changes no term above 1e-23; below, where the squares are denormal (a, b and
  // cos θ or sin θ under about 1e-15) and the plain quotient was off by up to 3 % (above 1), it
  // takes each ratio to its limit 1 (num ≤ den, so it never passes 1). One of den_s ≥ cos²θ and
  // den_p ≥ sin⁴θ is at least 1/4, so ds·dp ≥ 2.5e-31 never underflows; with η, κ ≤ 1e4 nothing
  // overflows.
  const float tiny = 1e-30f;
  const float ns = num_s + tiny, ds = den_s + tiny, np = num_p + tiny, dp = den_p + tiny;
  return (0.5f * ns) * (dp + np) / (ds * dp);
}

/// FresnelConductor per RGB channel.
inline Color3f FresnelConductor(float cos_i, const Color3f& eta, const Color3f& k) {
  return {FresnelConductor(cos_i, eta.r, k.r), FresnelConductor(cos_i, eta.g, k.g),
          FresnelConductor(cos_i, eta.b, k.b)};
}

}  // namespace ptlab
