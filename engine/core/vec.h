// Small fixed-size vector math: Vec2f, Vec3f and Color3f (linear RGB).
#pragma once

#include <algorithm>
#include <cmath>

namespace ptlab {

struct Vec2f {
  float x = 0, y = 0;
};

/// A 3-vector used for points, directions and normals alike (the meaning is in the name).
struct Vec3f {
  float x = 0, y = 0, z = 0;

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f& operator+=(const Vec3f& o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3f& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
};

constexpr Vec3f operator+(const Vec3f& a, const Vec3f& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3f operator-(const Vec3f& a, const Vec3f& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3f operator*(const Vec3f& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3f operator*(float s, const Vec3f& a) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3f operator/(const Vec3f& a, float s) { return a * (1.0f / s); }
constexpr bool operator==(const Vec3f& a, const Vec3f& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

constexpr float Dot(const Vec3f& a, const Vec3f& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f Cross(const Vec3f& a, const Vec3f& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float Length(const Vec3f& a) { return std::sqrt(Dot(a, a)); }
/// Unit vector along a; a must be non-zero.
inline Vec3f Normalize(const Vec3f& a) { return a / Length(a); }
constexpr Vec3f Min(const Vec3f& a, const Vec3f& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
constexpr Vec3f Max(const Vec3f& a, const Vec3f& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline Vec3f Abs(const Vec3f& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline float MaxComponent(const Vec3f& a) { return std::max(a.x, std::max(a.y, a.z)); }
inline int MaxDimension(const Vec3f& a) {
  return (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
}

/// Linear RGB radiance, reflectance or throughput.
struct Color3f {
  float r = 0, g = 0, b = 0;

  constexpr Color3f& operator+=(const Color3f& o) { r += o.r; g += o.g; b += o.b; return *this; }
  constexpr Color3f& operator*=(const Color3f& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
  constexpr Color3f& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
};

constexpr Color3f operator+(const Color3f& a, const Color3f& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr Color3f operator-(const Color3f& a, const Color3f& b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr Color3f operator*(const Color3f& a, const Color3f& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr Color3f operator*(const Color3f& a, float s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Color3f operator*(float s, const Color3f& a) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Color3f operator/(const Color3f& a, float s) { return a * (1.0f / s); }
constexpr bool IsBlack(const Color3f& c) { return c.r == 0 && c.g == 0 && c.b == 0; }
inline float MaxComponent(const Color3f& c) { return std::max(c.r, std::max(c.g, c.b)); }
inline bool IsFinite(const Color3f& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}
/// Rec. 709 luminance.
constexpr float Luminance(const Color3f& c) { return 0.212671f * c.r + 0.715160f * c.g + 0.072169f * c.b; }

inline constexpr float kPi = 3.14159265358979323846f;
/// 1 − 2⁻²⁴, the largest float below 1; sample coordinates are clamped into [0, this].
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;

constexpr float Radians(float deg) { return deg * (kPi / 180.0f); }

}  // namespace ptlab
