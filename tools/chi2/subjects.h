// The chi-square lab's registry of test subjects, and the subjects it ships with (warps, broken).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/vec.h"
#include "tools/chi2/chi2.h"

namespace ptlab {

/// An ordered set of subjects with unique names; what `chi2 --list` shows and `--all` runs.
class Chi2Registry {
 public:
  /// Appends a subject. Its name must be new and its pdf and a sampler set (checked).
  void Add(Chi2Subject subject);
  const std::vector<Chi2Subject>& subjects() const { return subjects_; }
  /// The subject called `name`, or null.
  const Chi2Subject* Find(std::string_view name) const;

 private:
  std::vector<Chi2Subject> subjects_;
};

/// A subject from a planar warp: `sample(Vec2f u) -> Vec2f` on the domain, `pdf(Vec2f) -> float`
/// per unit area. Any callables (function names, lambdas with captures).
template <typename Sample, typename Pdf>
Chi2Subject PlanarWarpSubject(std::string name, Chi2Domain domain, Sample sample, Pdf pdf,
                              Chi2Expect expect = Chi2Expect::kPass) {
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = domain;
  s.sample = [sample](float, const Vec2f& u, Chi2Point* p) {
    const Vec2f q = sample(u);
    *p = {q.x, q.y, 0.0f};
    return true;
  };
  s.pdf = [pdf](const Chi2Point& p) { return double(pdf(Vec2f{p.x, p.y})); };
  s.expect = expect;
  return s;
}

/// A subject from a direction warp: `sample(Vec2f u) -> Vec3f` (unit), `pdf(Vec3f) -> float`
/// per steradian, on Chi2Domain::Sphere() or Hemisphere().
template <typename Sample, typename Pdf>
Chi2Subject DirectionWarpSubject(std::string name, Chi2Domain domain, Sample sample, Pdf pdf,
                                 Chi2Expect expect = Chi2Expect::kPass) {
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = domain;
  s.sample = [sample](float, const Vec2f& u, Chi2Point* p) {
    *p = sample(u);
    return true;
  };
  s.pdf = [pdf](const Chi2Point& p) { return double(pdf(p)); };
  s.expect = expect;
  return s;
}

/// The fixed triangle of "warp/uniform_triangle" (counter-clockwise, inside the unit square;
/// coordinates off every grid line of small resolutions).
inline constexpr Vec2f kChi2TriangleA{0.1234f, 0.1618f}, kChi2TriangleB{0.9142f, 0.3183f},
    kChi2TriangleC{0.3679f, 0.8660f};

/// Every warp of engine/sampling/warp.h, plus SampleUniformTriangle mapped onto the triangle
/// above (pdf 1/area inside): names "warp/...", expected to pass.
void RegisterWarpSubjects(Chi2Registry* registry);

/// Deliberately wrong (sampler, pdf) pairs, names "broken/...", expected to be rejected: they
/// prove the lab can fail.
void RegisterBrokenSubjects(Chi2Registry* registry);

/// Every subject of the lab: the warps, then the broken variants. A new group of subjects
/// (BSDFs, environment map, thin lens, SIMD twins) adds its Register...Subjects call here.
Chi2Registry DefaultChi2Registry();

}  // namespace ptlab
