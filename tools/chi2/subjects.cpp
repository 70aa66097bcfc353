// Subjects of the chi-square lab: the warps of engine/sampling/warp.h and broken variants.
#include "tools/chi2/subjects.h"

#include "tools/chi2/bsdf_subjects.h"
#include "tools/chi2/emitter_subjects.h"
#include "tools/chi2/geometry_subjects.h"
#include "tools/chi2/light_subjects.h"

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
}

Chi2Registry DefaultChi2Registry() {
  Chi2Registry registry;
  RegisterWarpSubjects(&registry);
  RegisterBrokenSubjects(&registry);
  RegisterLightSubjects(&registry);
  RegisterGeometrySubjects(&registry);
  RegisterEmitterSubjects(&registry);
  RegisterBsdfSubjects(&registry);
  return registry;
}

}  // namespace ptlab
