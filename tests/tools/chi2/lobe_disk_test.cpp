// The zoomed equal-area disk of the chi-square lab: round trips, its Jacobian, the tail flush.
#include "tools/chi2/lobe_disk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/frame.h"
#include "engine/core/rng.h"
#include "engine/sampling/warp.h"
#include "tools/chi2/stats_math.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double AngleBetween(const Vec3f& a, const Vec3f& b) {
  const double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
}

const Vec3f kAxes[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.3f, -0.5f, 0.8124038f}};

// Near the axis (the lobe) directions survive the round trip to float disk coordinates at full
// relative precision. Far from it the zoom compresses the sphere towards the rim, where a float
// step of r is dρ = 2⁻²⁴ (ρ + k)² / (c k) (6e-4 rad for k = 1e-4): there the round trip is
// exact in disk coordinates instead, which is where the lab bins and integrates.
TEST(LobeDisk, RoundTripsDirectionsNearTheAxisAndDiskPointsEverywhere) {
  Pcg32 rng(7, 1);
  for (const Vec3f& axis : kAxes) {
    for (double k : {1e-4, 1e-2, 0.5, 3.0}) {
      const LobeDisk zoom(axis, k);
      const Frame frame(Normalize(axis));
      for (int i = 0; i < 1000; ++i) {
        const Vec2f u{rng.NextFloat(), rng.NextFloat()};
        const float g = float(std::min(3.0 * k, 3.0)) * u.x, phi = 2.0f * kPi * u.y;
        const Vec3f w =
            frame.ToWorld({std::sin(g) * std::cos(phi), std::sin(g) * std::sin(phi), std::cos(g)});
        const Chi2Point p = zoom.ToDisk(w);
        ASSERT_LE(p.x * p.x + p.y * p.y, 1.0f + 1e-6f);
        double jac;
        const Vec3f back = zoom.FromDisk(p, &jac);
        EXPECT_NEAR(Length(back), 1.0f, 1e-6f);
        EXPECT_LE(AngleBetween(w, back), 2e-7 + 1e-5 * g) << "k=" << k << " i=" << i;
        EXPECT_TRUE(std::isfinite(jac) && jac > 0);

        // Away from the antipode, which the whole rim maps to (its disk angle is arbitrary).
        const Vec3f far = SampleUniformSphere({rng.NextFloat(), rng.NextFloat()});
        if (AngleBetween(far, axis) > 3.0) continue;
        const Chi2Point q = zoom.ToDisk(far);
        ASSERT_LE(q.x * q.x + q.y * q.y, 1.0f + 1e-6f);
        const Chi2Point q2 = zoom.ToDisk(zoom.FromDisk(q, &jac));
        EXPECT_NEAR(q2.x, q.x, 2e-6f) << "k=" << k << " i=" << i;
        EXPECT_NEAR(q2.y, q.y, 2e-6f) << "k=" << k << " i=" << i;
      }
    }
  }
}

// The disk of radius r maps to the cap 1 − cosγ = ρ²/2 (ρ = k r / (c − r)), whose solid angle
// is π ρ²; ∫ dω/dA over the disk must give it, and 4π over the whole disk. (Not for k = 1e-4
// up to the rim: float r cannot resolve the last k/2, where the whole far side of the sphere
// is; the subjects with such k have pdf 0 there.)
TEST(LobeDisk, JacobianIntegratesToTheCapsSolidAngle) {
  for (const Vec3f& axis : kAxes) {
    for (double k : {1e-4, 0.05, 1.0}) {
      const LobeDisk zoom(axis, k);
      const double c = 0.5 * (2.0 + k);
      for (double r0 : {0.1, 0.5, 0.9, 1.0}) {
        if (k < 0.01 && r0 > 0.9) continue;
        SimpsonOptions options;
        options.rel_tol = 1e-10;
        const double area = AdaptiveSimpson(
            [&](double r) {
              double jac;
              zoom.FromDisk({float(r), 0.0f, 0.0f}, &jac);
              return 2.0 * kPiD * r * jac;
            },
            0.0, r0, options);
        const double rho = k * r0 / (c - r0);
        EXPECT_NEAR(area, kPiD * rho * rho, 1e-6 * kPiD * rho * rho) << "k=" << k << " r=" << r0;
        double jac;
        const Vec3f w = zoom.FromDisk({0.0f, float(r0), 0.0f}, &jac);
        EXPECT_NEAR(1.0 - Dot(w, Normalize(axis)), 0.5 * rho * rho, 1e-6 + 1e-5 * rho * rho);
      }
    }
  }
}

TEST(LobeDisk, FlushLobeTailZeroesOnlyTinyNonNegativeValues) {
  const Chi2PdfFn pdf = [](const Chi2Point& p) { return double(p.x); };
  const Chi2PdfFn flushed = FlushLobeTail(pdf, 1e6);  // floor 1e-6
  EXPECT_EQ(flushed({5e-7f, 0, 0}), 0.0);
  EXPECT_EQ(flushed({0, 0, 0}), 0.0);
  EXPECT_EQ(flushed({2e-6f, 0, 0}), double(2e-6f));
  EXPECT_EQ(flushed({-1e-9f, 0, 0}), double(-1e-9f));  // the lab must still see it
  EXPECT_TRUE(std::isnan(flushed({std::numeric_limits<float>::quiet_NaN(), 0, 0})));
}

TEST(LobeDisk, OnLobeDiskReportsSamplesOutsideTheInnerDomain) {
  Chi2Subject s = DirectionWarpSubject(
      "test/below", Chi2Domain::Hemisphere(),
      [](const Vec2f&) {
        return Vec3f{0, 0.6f, -0.8f};
      },
      UniformHemispherePdf);
  const Chi2Subject on_disk = OnLobeDisk(s, LobeDisk({0, 0, 1}, 0.1));
  Chi2Point p;
  ASSERT_TRUE(on_disk.sample(0.0f, {0.5f, 0.5f}, &p));
  EXPECT_FALSE(Chi2Contains(Chi2Domain::Disk(), p));
  EXPECT_EQ(on_disk.domain.kind, Chi2DomainKind::kDisk);
}

// The whole lab through the zoom: a uniform sphere around a tilted axis passes with mass 1; a
// cosine sampler claiming the uniform hemisphere pdf is rejected.
TEST(StatLobeDisk, UniformSphereThroughTheZoomPassesAndAWrongPdfFails) {
  Chi2Options options;
  options.samples = 200000;
  options.test_count = 2;
  const LobeDisk zoom(kAxes[3], 0.3);
  const Chi2Subject good = OnLobeDisk(DirectionWarpSubject("test/sphere", Chi2Domain::Sphere(),
                                                           SampleUniformSphere, UniformSpherePdf),
                                      zoom);
  const Chi2Result r = RunChi2Test(good, options);
  EXPECT_TRUE(r.pass) << FormatChi2Result(good, r);
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-5);
  const Chi2Subject bad =
      OnLobeDisk(DirectionWarpSubject("test/cosine_as_uniform", Chi2Domain::Hemisphere(),
                                      SampleCosineHemisphere, UniformHemispherePdf),
                 LobeDisk({0, 0, 1}, 0.5));
  const Chi2Result rb = RunChi2Test(bad, options);
  EXPECT_FALSE(rb.pass) << FormatChi2Result(bad, rb);
}

}  // namespace
}  // namespace ptlab
