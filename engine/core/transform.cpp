// Affine 4x4 transforms: products, inverse, and the constructors used by scene files.
#include "engine/core/transform.h"

#include <cmath>
#include <utility>

#include "engine/core/check.h"

namespace ptlab {

Matrix4 operator*(const Matrix4& a, const Matrix4& b) {
  Matrix4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * double(b.m[k][j]);
      r.m[i][j] = static_cast<float>(s);
    }
  return r;
}

Matrix4 Transpose(const Matrix4& a) {
  Matrix4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
  return r;
}

bool Inverse(const Matrix4& a, Matrix4* inverse) {
  double m[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      m[i][j] = a.m[i][j];
      m[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (!(std::fabs(m[pivot][c]) > 1e-300)) return false;
    if (pivot != c)
      for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[pivot][j]);
    const double inv = 1.0 / m[c][c];
    for (int j = 0; j < 8; ++j) m[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = m[r][c];
      for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) inverse->m[i][j] = static_cast<float>(m[i][j + 4]);
  return true;
}

Transform::Transform(const Matrix4& m) : m_(m) { PTLAB_CHECK(Inverse(m, &inv_)); }

Transform Transform::Translate(const Vec3f& t) {
  Matrix4 m, inv;
  m.m[0][3] = t.x, m.m[1][3] = t.y, m.m[2][3] = t.z;
  inv.m[0][3] = -t.x, inv.m[1][3] = -t.y, inv.m[2][3] = -t.z;
  return Transform(m, inv);
}

Transform Transform::Scale(const Vec3f& s) {
  Matrix4 m;
  m.m[0][0] = s.x, m.m[1][1] = s.y, m.m[2][2] = s.z;
  return Transform(m);
}

Transform Transform::Rotate(const Vec3f& axis, float angle_deg) {
  const Vec3f a = Normalize(axis);
  const double theta = double(angle_deg) * 3.14159265358979323846 / 180.0;
  const double s = std::sin(theta), c = std::cos(theta), t = 1.0 - c;
  Matrix4 m;
  m.m[0][0] = float(a.x * a.x * t + c);
  m.m[0][1] = float(a.x * a.y * t - a.z * s);
  m.m[0][2] = float(a.x * a.z * t + a.y * s);
  m.m[1][0] = float(a.x * a.y * t + a.z * s);
  m.m[1][1] = float(a.y * a.y * t + c);
  m.m[1][2] = float(a.y * a.z * t - a.x * s);
  m.m[2][0] = float(a.x * a.z * t - a.y * s);
  m.m[2][1] = float(a.y * a.z * t + a.x * s);
  m.m[2][2] = float(a.z * a.z * t + c);
  return Transform(m, Transpose(m));
}

Vec3f Transform::ApplyPoint(const Vec3f& p) const {
  const auto& a = m_.m;
  const float x = a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3];
  const float y = a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3];
  const float z = a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3];
  const float w = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
  return (w == 1.0f) ? Vec3f{x, y, z} : Vec3f{x / w, y / w, z / w};
}

Vec3f Transform::ApplyVector(const Vec3f& v) const {
  const auto& a = m_.m;
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z,
          a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

Vec3f Transform::ApplyNormal(const Vec3f& n) const {
  const auto& a = inv_.m;  // inverse transpose: rows of inv become columns
  return {a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z,
          a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z,
          a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z};
}

bool Transform::FlipsHandedness() const {
  const auto& a = m_.m;
  const float det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                    a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                    a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  return det < 0;
}

}  // namespace ptlab
