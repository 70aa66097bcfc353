// The geometric subjects of the chi-square lab: registry, area-light triangle choice, thin lens.
#include "tools/chi2/geometry_subjects.h"

#include <gtest/gtest.h>

#include "tools/chi2/chi2.h"

namespace ptlab {
namespace {

const Chi2Registry& Registry() {
  static const Chi2Registry registry = [] {
    Chi2Registry r;
    RegisterGeometrySubjects(&r);
    return r;
  }();
  return registry;
}

double Cross(const Vec2f& a, const Vec2f& b, const Chi2Point& p) {
  return (double(b.x) - a.x) * (double(p.y) - a.y) - (double(b.y) - a.y) * (double(p.x) - a.x);
}

// Which triangle of the quad a point is in: 0 = (A, B, C), 1 = (A, C, D).
int QuadTriangle(const Chi2Point& p) { return Cross(kChi2QuadA, kChi2QuadC, p) >= 0 ? 1 : 0; }

TEST(GeometrySubjects, RegistersWarpsLightLensAndBrokenVariants) {
  for (const char* name :
       {"warp/beckmann_normal_a0p3", "warp/beckmann_normal_a2", "warp/beckmann_normal_zoom_a0p0001",
        "warp/beckmann_normal_zoom_a0p05", "area_light/quad", "camera/thin_lens_aperture"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kPass) << name;
  }
  for (const char* name :
       {"broken/beckmann_normal_pdf_no_sin_jacobian", "broken/beckmann_normal_theta_from_tan",
        "broken/area_light_uniform_triangle_choice"}) {
    const Chi2Subject* s = Registry().Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kFail) << name;
  }
}

// u.x picks the triangle by area: ABC holds 0.2938 / 0.40775 = 72.05% of it.
TEST(GeometrySubjects, AreaLightPicksTrianglesByArea) {
  const Chi2Subject* light = Registry().Find("area_light/quad");
  const Chi2Subject* broken = Registry().Find("broken/area_light_uniform_triangle_choice");
  ASSERT_NE(light, nullptr);
  ASSERT_NE(broken, nullptr);
  ASSERT_EQ(light->uniform_dims, 2);
  Chi2Point p;
  for (float ux : {0.0f, 0.3f, 0.6f, 0.715f}) {
    ASSERT_TRUE(light->sample(0.0f, {ux, 0.6f}, &p));
    EXPECT_EQ(QuadTriangle(p), 0) << ux;
    EXPECT_GT(light->pdf(p), 0.0);
  }
  for (float ux : {0.725f, 0.9f, 0.999f}) {
    ASSERT_TRUE(light->sample(0.0f, {ux, 0.6f}, &p));
    EXPECT_EQ(QuadTriangle(p), 1) << ux;
  }
  ASSERT_TRUE(broken->sample(0.0f, {0.6f, 0.6f}, &p));
  EXPECT_EQ(QuadTriangle(p), 1);
}

TEST(GeometrySubjects, ThinLensOriginsCoverTheUnitDisk) {
  const Chi2Subject* lens = Registry().Find("camera/thin_lens_aperture");
  ASSERT_NE(lens, nullptr);
  Chi2Point p;
  ASSERT_TRUE(lens->sample(0.0f, {0.5f, 0.5f}, &p));
  EXPECT_NEAR(p.x, 0.0f, 1e-6f);
  EXPECT_NEAR(p.y, 0.0f, 1e-6f);
  // The concentric map sends the middle of the square's right edge to (1, 0).
  ASSERT_TRUE(lens->sample(0.0f, {0x1.fffffep-1f, 0.5f}, &p));
  EXPECT_NEAR(p.x, 1.0f, 1e-5f);
  EXPECT_NEAR(p.y, 0.0f, 1e-5f);
  EXPECT_TRUE(Chi2Contains(Chi2Domain::Disk(), p));
}

}  // namespace
}  // namespace ptlab
