// WorldBounds: the world geometry only — group rows through their instances, not where they
// are stored.
#include "engine/scene/world_bounds.h"

#include <gtest/gtest.h>

#include "engine/core/transform.h"

namespace ptlab {
namespace {

TEST(WorldBounds, EmptySceneHasNone) {
  Scene scene;
  Vec3f lo{7, 7, 7}, hi{7, 7, 7};
  EXPECT_FALSE(WorldBounds(scene, &lo, &hi));
  EXPECT_EQ(lo.x, 7.0f);
}

TEST(WorldBounds, GroupRowsCountOnlyThroughTheirInstances) {
  Scene scene;
  scene.triangles.Append({0, 0, 0}, {1, 0, 0}, {0, 1, 0});          // world row
  scene.triangles.Append({-50, -50, -50}, {-49, -50, -50}, {-50, -49, -50});  // group row
  const uint32_t g = scene.instances.AddGroup(1, 1);
  Vec3f lo, hi;
  ASSERT_TRUE(WorldBounds(scene, &lo, &hi));  // a group without instances is not in the world
  EXPECT_EQ(lo.x, 0.0f);
  EXPECT_EQ(hi.x, 1.0f);
  EXPECT_EQ(lo.z, 0.0f);
  scene.instances.AddInstance(g, Transform::Translate({150, 0, 0}));  // group box at x 100..101
  scene.spheres.Append({0, 0, 5}, 2.0f, MaterialRef::None());
  ASSERT_TRUE(WorldBounds(scene, &lo, &hi));
  EXPECT_EQ(lo.x, -2.0f);    // the sphere
  EXPECT_EQ(hi.x, 101.0f);   // the instance's far corner
  EXPECT_EQ(lo.y, -50.0f);   // the instance's box keeps y and z of the group
  EXPECT_EQ(hi.z, 7.0f);     // the sphere's top
  EXPECT_EQ(lo.z, -50.0f);
}

}  // namespace
}  // namespace ptlab
