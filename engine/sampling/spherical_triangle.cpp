// Arvo's spherical triangle sampling, computed in double.
#include "engine/sampling/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace ptlab {
namespace {

struct D3 {
  double x, y, z;
};
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(double s, const D3& a) { return {s * a.x, s * a.y, s * a.z}; }
double Dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 Cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double Length(const D3& a) { return std::sqrt(Dot(a, a)); }
D3 ToD3(const Vec3f& v) { return {double(v.x), double(v.y), double(v.z)}; }

// Normalises a; false for a zero or non-finite vector.
bool Normalize(D3* a) {
  const double len = Length(*a);
  if (!(len > 0) || !std::isfinite(len)) return false;
  *a = (1.0 / len) * *a;
  return true;
}

double SafeSqrt(double x) { return std::sqrt(std::max(x, 0.0)); }

// The component of b orthogonal to unit a, normalised (false when b is parallel to a).
bool Orthonormal(const D3& a, const D3& b, D3* out) {
  *out = b - Dot(b, a) * a;
  return Normalize(out);
}

// Solid angle of the spherical triangle with unit corners a, b, c.
double SolidAngle(const D3& a, const D3& b, const D3& c) {
  const double det = std::abs(Dot(a, Cross(b, c)));
  const double denom = 1.0 + Dot(a, b) + Dot(b, c) + Dot(c, a);
  return 2.0 * std::atan2(det, denom);
}

}  // namespace

float SphericalTriangleArea(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, const Vec3f& p) {
  const D3 o = ToD3(p);
  D3 a = ToD3(v0) - o, b = ToD3(v1) - o, c = ToD3(v2) - o;
  if (!Normalize(&a) || !Normalize(&b) || !Normalize(&c)) return 0.0f;
  const double omega = SolidAngle(a, b, c);
  return std::isfinite(omega) ? float(omega) : 0.0f;
}

bool SampleSphericalTriangle(const Vec3f& v0, const Vec3f& v1, const Vec3f& v2, const Vec3f& p,
                             const Vec2f& u, SphericalTriangleSample* out) {
  const D3 o = ToD3(p);
  D3 a = ToD3(v0) - o, b = ToD3(v1) - o, c = ToD3(v2) - o;
  if (!Normalize(&a) || !Normalize(&b) || !Normalize(&c)) return false;
  const double omega = SolidAngle(a, b, c);
  const float omega_f = float(omega);
  if (!std::isfinite(omega) || !UsesSphericalTriangleSampling(omega_f)) return false;
  // The corner angle α at a, between the great circles a-b and a-c, as its cosine and sine
  // (no trigonometric calls); the area is the solid angle.
  D3 n_ab = Cross(a, b), n_ac = Cross(a, c);
  if (!Normalize(&n_ab) || !Normalize(&n_ac)) return false;
  const double cos_alpha = std::clamp(Dot(n_ab, n_ac), -1.0, 1.0);
  const double sin_alpha = Length(Cross(n_ab, n_ac));
  // Arvo: the sub-triangle (a, b, c_hat) of area u0 * area fixes c_hat on the arc a-c ...
  const double sub_area = double(u.x) * omega;
  const double sin_sub = std::sin(sub_area), cos_sub = std::cos(sub_area);
  const double s = sin_sub * cos_alpha - cos_sub * sin_alpha;  // sin(sub_area - α)
  const double t = cos_sub * cos_alpha + sin_sub * sin_alpha;  // cos(sub_area - α)
  const double cos_c = Dot(a, b);  // the side opposite c
  const double uu = t - cos_alpha, vv = s + sin_alpha * cos_c;
  const double denom = (vv * s + uu * t) * sin_alpha;
  double q = denom != 0 ? ((vv * t - uu * s) * cos_alpha - vv) / denom : 1.0;
  q = std::clamp(q, -1.0, 1.0);
  D3 c_perp;
  if (!Orthonormal(a, c, &c_perp)) return false;
  const D3 c_hat = q * a + SafeSqrt(1.0 - q * q) * c_perp;
  // ... and the direction is uniform in cos along the arc from b to c_hat.
  const double z = 1.0 - double(u.y) * (1.0 - Dot(c_hat, b));
  D3 chat_perp;
  if (!Orthonormal(b, c_hat, &chat_perp)) return false;
  const D3 w = z * b + SafeSqrt(1.0 - z * z) * chat_perp;
  // The point of the triangle's plane along w (Möller-Trumbore in double).
  const D3 e1 = ToD3(v1) - ToD3(v0), e2 = ToD3(v2) - ToD3(v0);
  const D3 pv = Cross(w, e2);
  const double det = Dot(e1, pv);
  if (!(std::abs(det) > 0)) return false;
  const D3 tv = o - ToD3(v0);
  double b1 = Dot(tv, pv) / det;
  const D3 qv = Cross(tv, e1);
  double b2 = Dot(w, qv) / det;
  if (!std::isfinite(b1) || !std::isfinite(b2)) return false;
  // Rounding can put the point a hair outside: clamp it back onto the triangle.
  b1 = std::clamp(b1, 0.0, 1.0);
  b2 = std::clamp(b2, 0.0, 1.0);
  if (b1 + b2 > 1.0) {
    const double sum = b1 + b2;
    b1 /= sum, b2 /= sum;
  }
  const D3 point = ToD3(v0) + b1 * e1 + b2 * e2;
  out->p = {float(point.x), float(point.y), float(point.z)};
  out->b1 = float(b1), out->b2 = float(b2);
  out->pdf = 1.0f / omega_f;
  return true;
}

}  // namespace ptlab
