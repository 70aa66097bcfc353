// The mirror BSDF: the reflected direction, and a sample weight equal to the reflectance.
#include "engine/bsdf/mirror.h"

#include <gtest/gtest.h>

#include "engine/bsdf/bsdf.h"

namespace ptlab {
namespace {

TEST(Mirror, ReflectsAndWeightsByTheReflectance) {
  MaterialTables m;
  const MaterialRef white = m.AddMirror();
  const MaterialRef tinted = m.AddMirror({0.9f, 0.5f, 0.25f});
  const Vec3f wo = Normalize(Vec3f{0.3f, -0.4f, 0.8f});
  BsdfSample s;
  ASSERT_TRUE(BsdfSampleDirection(m, tinted, wo, 0.5f, {0.5f, 0.5f}, &s));
  EXPECT_EQ(s.wi.x, -wo.x);
  EXPECT_EQ(s.wi.y, -wo.y);
  EXPECT_EQ(s.wi.z, wo.z);
  EXPECT_TRUE(s.delta);
  EXPECT_EQ(s.weight.r, 0.9f);
  EXPECT_EQ(s.weight.g, 0.5f);
  EXPECT_EQ(s.weight.b, 0.25f);
  ASSERT_TRUE(BsdfSampleDirection(m, white, wo, 0.5f, {0.5f, 0.5f}, &s));
  EXPECT_EQ(s.weight.g, 1.0f);
  // Nothing from below the surface; no value for Eval and Pdf (a delta lobe).
  EXPECT_FALSE(BsdfSampleDirection(m, tinted, {wo.x, wo.y, -wo.z}, 0.5f, {0.5f, 0.5f}, &s));
  EXPECT_TRUE(IsBlack(BsdfEval(m, tinted, wo, s.wi)));
  EXPECT_EQ(BsdfPdf(m, tinted, wo, s.wi), 0.0f);
}

}  // namespace
}  // namespace ptlab
