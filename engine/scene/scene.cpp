// Scene-wide systems that loaders run once all shapes are in.
#include "engine/scene/scene.h"

#include "engine/light/light_selection.h"

#include "engine/sampling/guide_table.h"

namespace ptlab {

const char* IntegratorTypeName(IntegratorDesc::Type type) {
  using T = IntegratorDesc::Type;
  switch (type) {
    case T::kNormals:
      return "normals";
    case T::kDirectEms:
      return "direct_ems";
    case T::kDirectMats:
      return "direct_mats";
    case T::kDirectMis:
      return "direct_mis";
    case T::kWhitted:
      return "whitted";
    case T::kPathMats:
      return "path_mats";
    case T::kPathEms:
      return "path_ems";
    case T::kPathMis:
      return "path_mis";
    case T::kBdpt:
      return "bdpt";
    case T::kPtracer:
      return "ptracer";
  }
  return "?";
}

bool IntegratorTypeFromName(std::string_view name, IntegratorDesc::Type* type) {
  for (int i = 0; i <= int(IntegratorDesc::Type::kPtracer); ++i) {
    if (name == IntegratorTypeName(IntegratorDesc::Type(i))) {
      *type = IntegratorDesc::Type(i);
      return true;
    }
  }
  return false;
}

void FinalizeAreaLights(Scene* scene) {
  AreaLightTable& lights = scene->area_lights;
  lights.area.assign(lights.size(), 0.0f);
  lights.cdf_offset.assign(lights.size(), 0);
  lights.triangle_cdf.clear();
  lights.guide_offset.assign(lights.size(), 0);
  lights.triangle_guide.clear();
  for (size_t i = 0; i < lights.size(); ++i) {
    const uint32_t mesh = lights.mesh[i];
    const uint32_t first = scene->meshes.first_triangle[mesh];
    const uint32_t count = scene->meshes.triangle_count[mesh];
    lights.cdf_offset[i] = uint32_t(lights.triangle_cdf.size());
    double total = 0;
    for (uint32_t t = first; t < first + count; ++t) {
      const TriangleTable& tri = scene->triangles;
      total += 0.5 * double(Length(Cross(tri.V1(t) - tri.V0(t), tri.V2(t) - tri.V0(t))));
      lights.triangle_cdf.push_back(float(total));
    }
    for (uint32_t t = 0; t < count; ++t) {
      float& c = lights.triangle_cdf[lights.cdf_offset[i] + t];
      c = total > 0 ? float(c / total) : float(t + 1) / float(count);
    }
    if (count > 0) lights.triangle_cdf[lights.cdf_offset[i] + count - 1] = 1.0f;
    lights.area[i] = float(total);
    lights.guide_offset[i] = uint32_t(lights.triangle_guide.size());
    lights.triangle_guide.resize(lights.triangle_guide.size() + count + 1);
    BuildGuideTable(&lights.triangle_cdf[lights.cdf_offset[i]], count,
                    &lights.triangle_guide[lights.guide_offset[i]]);
  }
  BuildEmitterSelection(scene);
}

}  // namespace ptlab
