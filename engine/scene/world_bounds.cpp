// The world box of a scene's geometry (world_bounds.h).
#include "engine/scene/world_bounds.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace ptlab {

bool WorldBounds(const Scene& scene, Vec3f* lo_out, Vec3f* hi_out) {
  const TriangleTable& t = scene.triangles;
  const SphereTable& spheres = scene.spheres;
  const InstanceTable& instances = scene.instances;
  constexpr float kMax = std::numeric_limits<float>::max();
  const auto expand = [](Vec3f* lo, Vec3f* hi, const Vec3f& v) {
    *lo = {std::min(lo->x, v.x), std::min(lo->y, v.y), std::min(lo->z, v.z)};
    *hi = {std::max(hi->x, v.x), std::max(hi->y, v.y), std::max(hi->z, v.z)};
  };
  // Group rows are in their group's space: they reach the world only through instances.
  std::vector<uint8_t> in_group;
  if (instances.groups() > 0) {
    in_group.assign(t.size(), 0);
    for (size_t g = 0; g < instances.groups(); ++g)
      std::fill_n(in_group.begin() + instances.group_first_row[g], instances.group_row_count[g],
                  uint8_t{1});
  }
  Vec3f lo{kMax, kMax, kMax}, hi{-kMax, -kMax, -kMax};
  bool any = false;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!in_group.empty() && in_group[i]) continue;
    for (const Vec3f& v : {t.V0(i), t.V1(i), t.V2(i)}) expand(&lo, &hi, v);
    any = true;
  }
  for (size_t i = 0; i < spheres.size(); ++i) {
    const float r = spheres.radius[i];
    expand(&lo, &hi, spheres.Center(i) - Vec3f{r, r, r});
    expand(&lo, &hi, spheres.Center(i) + Vec3f{r, r, r});
    any = true;
  }
  // An sdfgrid by its whole box [0, 1]^3 placed by its to_world.
  for (size_t i = 0; i < scene.sdf_grids.size(); ++i) {
    for (int c = 0; c < 8; ++c)
      expand(&lo, &hi,
             scene.sdf_grids.to_world[i].ApplyPoint(
                 {float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1)}));
    any = true;
  }
  for (size_t k = 0; k < instances.size(); ++k) {
    const uint32_t g = instances.group[k];
    const uint32_t first = instances.group_first_row[g], end = first + instances.group_row_count[g];
    if (first == end) continue;
    Vec3f glo{kMax, kMax, kMax}, ghi{-kMax, -kMax, -kMax};
    for (uint32_t i = first; i < end; ++i)
      for (const Vec3f& v : {t.V0(i), t.V1(i), t.V2(i)}) expand(&glo, &ghi, v);
    for (int c = 0; c < 8; ++c)
      expand(&lo, &hi,
             instances.to_world[k].ApplyPoint({c & 1 ? ghi.x : glo.x, c & 2 ? ghi.y : glo.y,
                                               c & 4 ? ghi.z : glo.z}));
    any = true;
  }
  if (!any) return false;
  *lo_out = lo, *hi_out = hi;
  return true;
}

}  // namespace ptlab
