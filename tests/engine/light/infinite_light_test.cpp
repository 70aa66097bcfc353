// Tests of the infinite-light dispatch: per-emitter calls and the escaped-ray sum.
#include "engine/light/infinite_light.h"

#include <gtest/gtest.h>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

Scene SceneWithInfiniteLights() {
  Scene scene;
  Image image(4, 2);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) image.Set(i, j, {float(i + 1), float(j + 1), 0.5f});
  EXPECT_TRUE(AddEnvironmentMap(image, {}, "env", &scene.environment_maps).ok());
  EXPECT_TRUE(AddDistantDisk({5, 5, 5}, 20, Frame(), "disk", &scene.distant_disks).ok());
  scene.emitters = {EmitterRef::Make(EmitterTag::kArea, 0),
                    EmitterRef::Make(EmitterTag::kEnvironment, 0),
                    EmitterRef::Make(EmitterTag::kDistantDisk, 0)};
  return scene;
}

TEST(InfiniteLight, DispatchesOnTheTag) {
  const Scene scene = SceneWithInfiniteLights();
  const EmitterRef area = scene.emitters[0], env = scene.emitters[1], disk = scene.emitters[2];
  EXPECT_FALSE(IsInfiniteLight(area));
  EXPECT_TRUE(IsInfiniteLight(env));
  EXPECT_TRUE(IsInfiniteLight(disk));
  EXPECT_FALSE(IsInfiniteLight(EmitterRef::None()));
  Pcg32 rng(1, 1);
  for (int k = 0; k < 100; ++k) {
    const Vec2f u{rng.NextFloat(), rng.NextFloat()};
    EnvironmentSample a, b;
    ASSERT_TRUE(SampleInfiniteLight(scene, env, u, &a));
    ASSERT_TRUE(SampleEnvironment(scene.environment_maps, 0, u, &b));
    EXPECT_EQ(a.wi, b.wi);
    EXPECT_EQ(a.pdf, b.pdf);
    EXPECT_EQ(InfiniteLightPdf(scene, env, a.wi), EnvironmentPdf(scene.environment_maps, 0, a.wi));
    EXPECT_EQ(InfiniteLightRadiance(scene, env, a.wi).r,
              EnvironmentRadiance(scene.environment_maps, 0, a.wi).r);
    ASSERT_TRUE(SampleInfiniteLight(scene, disk, u, &a));
    EXPECT_EQ(InfiniteLightPdf(scene, disk, a.wi), a.pdf);
    EXPECT_EQ(InfiniteLightRadiance(scene, disk, a.wi).g, 5.0f);
    EXPECT_FALSE(SampleInfiniteLight(scene, area, u, &a));
    EXPECT_EQ(InfiniteLightPdf(scene, area, a.wi), 0.0f);
    EXPECT_TRUE(IsBlack(InfiniteLightRadiance(scene, area, a.wi)));
  }
}

TEST(InfiniteLight, EscapedRadianceSumsEveryInfiniteEmitter) {
  const Scene scene = SceneWithInfiniteLights();
  for (const Vec3f& w : {Vec3f{0, 0, 1}, Vec3f{1, 0, 0}, Normalize(Vec3f{0.1f, 0.2f, 0.9f})}) {
    const Color3f expected = EnvironmentRadiance(scene.environment_maps, 0, w) +
                             DistantDiskRadiance(scene.distant_disks, 0, w);
    const Color3f got = EscapedRadiance(scene, w);
    EXPECT_EQ(got.r, expected.r);
    EXPECT_EQ(got.b, expected.b);
  }
  EXPECT_TRUE(IsBlack(EscapedRadiance(Scene(), {0, 0, 1})));
}

}  // namespace
}  // namespace ptlab
