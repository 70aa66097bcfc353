// The emitter subjects of the chi-square lab are registered, and the SIMD area-light ones are
// distinguishable from their broken variant.
#include "tools/chi2/emitter_subjects.h"

#include <gtest/gtest.h>

#include "tools/chi2/chi2.h"

namespace ptlab {
namespace {

// The subjects themselves run with every other subject in subjects_test.cpp
// (DefaultChi2Registry registers them); here: what is registered and how.
TEST(EmitterChi2Registry, HoldsTheScalarAndSimdAreaLightSubjects) {
  Chi2Registry r;
  RegisterEmitterSubjects(&r);
  for (const char* name : {"emitter/spherical_triangle_near", "emitter/power_selection_four_quads",
                           "simd/area_light_fan_area", "simd/area_light_fan_solid_angle",
                           "simd/area_light_four_quads_area",
                           "emitter/mitsuba_cylinder_and_disk_area",
                           "simd/area_light_mitsuba_cylinder_and_disk_area"}) {
    const Chi2Subject* s = r.Find(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->expect, Chi2Expect::kPass) << name;
  }
  for (const char* name : {"simd/area_light_fan_area", "simd/area_light_fan_solid_angle",
                           "simd/area_light_four_quads_area"}) {
    EXPECT_TRUE(bool(r.Find(name)->sample_batch)) << name << ": drawn by the SIMD batch";
  }
  const Chi2Subject* broken = r.Find("broken/simd_area_light_fan_claims_solid_angle_pdf");
  ASSERT_NE(broken, nullptr);
  EXPECT_EQ(broken->expect, Chi2Expect::kFail);
  for (const Chi2Subject& s : r.subjects())
    EXPECT_EQ(s.name.rfind("broken/", 0) == 0, s.expect == Chi2Expect::kFail) << s.name;
}

}  // namespace
}  // namespace ptlab
