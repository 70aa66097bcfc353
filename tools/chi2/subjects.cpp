// Subjects of the chi-square lab: the warps of engine/sampling/warp.h and broken variants.
#include "tools/chi2/subjects.h"

#include "tools/chi2/bsdf_subjects.h"
#include "tools/chi2/emission_subjects.h"
#include "tools/chi2/emitter_subjects.h"
#include "tools/chi2/geometry_subjects.h"
#include "tools/chi2/light_subjects.h"

#include <algorithm>
#include <cmath>

#include "engine/core/check.h"
#include "engine/sampling/warp.h"

namespace ptlab {
namespace {

double Cross(const Vec2f& a, const Vec2f& b, const Vec2f& p) {
  return (double(b.x) - a.x) * (double(p.y) - a.y) - (double(b.y) - a.y) * (double(p.x) - a.x);
}

const double kTriangleArea = 0.5 * Cross(kChi2TriangleA, kChi2TriangleB, kChi2TriangleC);

Vec2f SampleFixedTriangle(const Vec2f& u) {
  const Vec2f b = SampleUniformTriangle(u);
  const float b2 = 1.0f - b.x - b.y;
  const Vec2f &A = kChi2TriangleA, &B = kChi2TriangleB, &C = kChi2TriangleC;
  return {b.x * A.x + b.y * B.x + b2 * C.x, b.x * A.y + b.y * B.y + b2 * C.y};
}

float FixedTrianglePdf(const Vec2f& p) {
  const Vec2f &A = kChi2TriangleA, &B = kChi2TriangleB, &C = kChi2TriangleC;
  const bool inside = Cross(A, B, p) >= 0 && Cross(B, C, p) >= 0 && Cross(C, A, p) >= 0;
  return inside ? float(1.0 / kTriangleArea) : 0.0f;
}

// A smooth error of relative size delta in a uniform variable: u + delta u (1 - u) maps [0, 1]
// onto itself with slope 1 + delta (1 - 2u), so the density of what follows is off by the ramp
// -delta (1 - 2u) (to first order): a polar or planar "smooth" error of delta.
float QuantileTilt(float u, float delta) { return u + delta * u * (1.0f - u); }

// A direction with its azimuth moved by phi -> phi + delta sin(phi): the azimuthal density is
// divided by 1 + delta cos(phi), an azimuthal smooth error of delta.
Vec3f AzimuthTilt(const Vec3f& w, float delta) {
  const float r = std::sqrt(w.x * w.x + w.y * w.y);
  if (r == 0) return w;
  const float phi = std::atan2(w.y, w.x);
  const float moved = phi + delta * std::sin(phi);
  return {r * std::cos(moved), r * std::sin(moved), w.z};
}

// The cosine hemisphere's z² is uniform: tilting it is a polar error of delta.
Vec3f CosineHemispherePolarTilt(const Vec2f& u, float delta) {
  const Vec3f w = SampleCosineHemisphere(u);
  const float r = std::sqrt(w.x * w.x + w.y * w.y);
  const float z2 = QuantileTilt(w.z * w.z, delta), r2 = std::sqrt(std::max(0.0f, 1.0f - z2));
  if (r == 0) return {0, 0, std::sqrt(z2)};
  return {w.x * r2 / r, w.y * r2 / r, std::sqrt(z2)};
}

}  // namespace

void Chi2Registry::Add(Chi2Subject subject) {
  PTLAB_CHECK(!subject.name.empty() && Find(subject.name) == nullptr);
  PTLAB_CHECK(subject.pdf && (subject.sample || subject.sample_batch));
  subjects_.push_back(std::move(subject));
}

const Chi2Subject* Chi2Registry::Find(std::string_view name) const {
  for (const Chi2Subject& s : subjects_)
    if (s.name == name) return &s;
  return nullptr;
}

void RegisterWarpSubjects(Chi2Registry* r) {
  const Chi2Domain square = Chi2Domain::UnitSquare(), box = Chi2Domain::Box(-1, -1, 1, 1);
  const Chi2Domain disk = Chi2Domain::Disk();
  const Chi2Domain sphere = Chi2Domain::Sphere(), hemi = Chi2Domain::Hemisphere();
  r->Add(PlanarWarpSubject("warp/uniform_square", square, SampleUniformSquare, UniformSquarePdf));
  r->Add(PlanarWarpSubject("warp/tent", box, SampleTent, TentPdf));
  r->Add(PlanarWarpSubject("warp/uniform_disk", disk, SampleUniformDisk, UniformDiskPdf));
  r->Add(PlanarWarpSubject("warp/concentric_disk", disk, SampleConcentricDisk, ConcentricDiskPdf));
  r->Add(PlanarWarpSubject("warp/uniform_triangle", square, SampleFixedTriangle, FixedTrianglePdf));
  r->Add(
      DirectionWarpSubject("warp/uniform_sphere", sphere, SampleUniformSphere, UniformSpherePdf));
  r->Add(DirectionWarpSubject("warp/uniform_hemisphere", hemi, SampleUniformHemisphere,
                              UniformHemispherePdf));
  r->Add(DirectionWarpSubject("warp/cosine_hemisphere", hemi, SampleCosineHemisphere,
                              CosineHemispherePdf));
}

void RegisterBrokenSubjects(Chi2Registry* r) {
  constexpr Chi2Expect kFail = Chi2Expect::kFail;
  // The cosine pdf normalised like the uniform one: integrates to 1/2.
  r->Add(DirectionWarpSubject(
      "broken/cosine_hemisphere_pdf_over_2pi", Chi2Domain::Hemisphere(), SampleCosineHemisphere,
      [](const Vec3f& w) { return w.z > 0 ? w.z * kInv2Pi : 0.0f; }, kFail));
  // A correctly normalised pdf that is not the sampler's: only the χ² statistic can see it.
  r->Add(DirectionWarpSubject("broken/cosine_sampler_uniform_pdf", Chi2Domain::Hemisphere(),
                              SampleCosineHemisphere, UniformHemispherePdf, kFail));
  // r = u instead of sqrt(u): samples crowd the centre of the disk.
  r->Add(PlanarWarpSubject(
      "broken/uniform_disk_linear_r", Chi2Domain::Disk(),
      [](const Vec2f& u) {
        const float phi = 2.0f * kPi * u.y;
        return Vec2f{u.x * std::cos(phi), u.x * std::sin(phi)};
      },
      UniformDiskPdf, kFail));
  // z = u covers the upper hemisphere only, but claims the whole sphere's pdf.
  r->Add(DirectionWarpSubject(
      "broken/uniform_sphere_upper_z", Chi2Domain::Sphere(),
      [](const Vec2f& u) {
        const float z = u.x, s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 2.0f * kPi * u.y;
        return Vec3f{s * std::cos(phi), s * std::sin(phi), z};
      },
      UniformSpherePdf, kFail));
  // The tent pdf scaled by 1.1: integrates to 1.1.
  r->Add(PlanarWarpSubject(
      "broken/tent_pdf_scaled", Chi2Domain::Box(-1, -1, 1, 1), SampleTent,
      [](const Vec2f& p) { return 1.1f * TentPdf(p); }, kFail));

  // Small errors, each of a size the lab claims to catch (docs/chi2-power.md). Smooth: the
  // density off by a low-order ramp or harmonic of relative size 1-3 %.
  const Chi2Domain hemi = Chi2Domain::Hemisphere();
  r->Add(DirectionWarpSubject(
      "broken/cosine_hemisphere_azimuth_2pct", hemi,
      [](const Vec2f& u) { return AzimuthTilt(SampleCosineHemisphere(u), 0.02f); },
      CosineHemispherePdf, kFail));
  r->Add(DirectionWarpSubject(
      "broken/cosine_hemisphere_polar_2pct", hemi,
      [](const Vec2f& u) { return CosineHemispherePolarTilt(u, 0.02f); }, CosineHemispherePdf,
      kFail));
  r->Add(PlanarWarpSubject(
      "broken/tent_x_3pct", Chi2Domain::Box(-1, -1, 1, 1),
      [](const Vec2f& u) { return SampleTent(Vec2f{QuantileTilt(u.x, 0.03f), u.y}); }, TentPdf,
      kFail));
  {
    // 1 % is below what 10^6 samples catch: this subject draws 4x as many (see sample_scale).
    Chi2Subject s = DirectionWarpSubject(
        "broken/uniform_sphere_polar_1pct", Chi2Domain::Sphere(),
        [](const Vec2f& u) { return SampleUniformSphere(Vec2f{QuantileTilt(u.x, 0.01f), u.y}); },
        UniformSpherePdf, kFail);
    s.sample_scale = 4;
    r->Add(std::move(s));
  }
  // Local: 1-3 % of the samples misplaced within a small region. The first 3 % of the azimuth
  // range squeezed into its first half (a wedge of twice the density next to an empty one).
  r->Add(DirectionWarpSubject(
      "broken/cosine_hemisphere_wedge_3pct", hemi,
      [](const Vec2f& u) {
        const Vec3f w = SampleCosineHemisphere(u);
        const float phi = std::atan2(w.y, w.x), r = std::sqrt(w.x * w.x + w.y * w.y);
        const float wedge = 0.03f * 2.0f * kPi;
        if (!(phi >= 0 && phi < wedge)) return w;
        return Vec3f{r * std::cos(0.5f * phi), r * std::sin(0.5f * phi), w.z};
      },
      CosineHemispherePdf, kFail));
  // The samples in a patch of 1 % of the disk's area (radius 0.1 around (0.3, 0.2)) reflected
  // through the centre: 1 % of the samples misplaced, an empty patch next to a doubled one.
  r->Add(PlanarWarpSubject(
      "broken/uniform_disk_patch_1pct", Chi2Domain::Disk(),
      [](const Vec2f& u) {
        const Vec2f p = SampleUniformDisk(u);
        const float dx = p.x - 0.3f, dy = p.y - 0.2f;
        return dx * dx + dy * dy < 0.01f ? Vec2f{-p.x, -p.y} : p;
      },
      UniformDiskPdf, kFail));
}

Chi2Registry DefaultChi2Registry() {
  Chi2Registry registry;
  RegisterWarpSubjects(&registry);
  RegisterBrokenSubjects(&registry);
  RegisterLightSubjects(&registry);
  RegisterGeometrySubjects(&registry);
  RegisterEmitterSubjects(&registry);
  RegisterEmissionSubjects(&registry);
  RegisterBsdfSubjects(&registry);
  return registry;
}

}  // namespace ptlab
