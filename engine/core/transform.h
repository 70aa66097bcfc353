// Affine 4x4 transforms (row-major), as composed by scene files: points, vectors, normals.
#pragma once

#include "engine/core/vec.h"

namespace ptlab {

/// Row-major 4x4 matrix; m[row][col]. Column vectors: p' = M p.
struct Matrix4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  static Matrix4 Identity() { return Matrix4(); }
  friend Matrix4 operator*(const Matrix4& a, const Matrix4& b);
};

Matrix4 operator*(const Matrix4& a, const Matrix4& b);
/// General 4x4 inverse (Gauss-Jordan with partial pivoting, in double).
/// Returns false when the matrix is singular.
bool Inverse(const Matrix4& a, Matrix4* inverse);
Matrix4 Transpose(const Matrix4& a);

/// A transform and its inverse, kept together so normals transform without a new inversion.
class Transform {
 public:
  Transform() = default;
  /// m must be invertible (callers that read matrices from files check with Inverse first).
  explicit Transform(const Matrix4& m);
  Transform(const Matrix4& m, const Matrix4& inv) : m_(m), inv_(inv) {}

  static Transform Translate(const Vec3f& t);
  static Transform Scale(const Vec3f& s);
  /// Rotation by angle_deg degrees about axis (need not be unit length) — right-hand rule.
  static Transform Rotate(const Vec3f& axis, float angle_deg);

  const Matrix4& matrix() const { return m_; }
  const Matrix4& inverse_matrix() const { return inv_; }
  Transform Inverted() const { return Transform(inv_, m_); }

  Vec3f ApplyPoint(const Vec3f& p) const;
  Vec3f ApplyVector(const Vec3f& v) const;
  /// Normals transform with the inverse transpose; the result is not normalised.
  Vec3f ApplyNormal(const Vec3f& n) const;
  /// Sign of the determinant of the upper 3x3: negative for mirroring transforms.
  bool FlipsHandedness() const;

  friend Transform operator*(const Transform& a, const Transform& b) {
    return Transform(a.m_ * b.m_, b.inv_ * a.inv_);
  }

 private:
  Matrix4 m_, inv_;
};

}  // namespace ptlab
