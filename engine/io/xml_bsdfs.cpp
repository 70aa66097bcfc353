// Nori XML <bsdf>: diffuse, mirror, dielectric, microfacet (rough plastic), roughconductor.

#include "engine/bsdf/conductor_presets.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/image/image_io.h"
#include "engine/light/distant_disk.h"
#include "engine/light/environment_map.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/obj_loader.h"
#include "engine/scene/scene_limits.h"
#include "engine/io/shapes.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_loader_internal.h"
#include "engine/io/xml_scene_parser.h"

namespace ptlab::internal {

StatusOr<MaterialRef> SceneParser::ParseBsdf(const pugi::xml_node& node) {
  PropertyList props(&at_, node);
  PTLAB_RETURN_IF_ERROR(CollectLeafObject(node, &props));
  const std::string type = node.attribute("type").value();
  MaterialTables& materials = scene_.materials;
  float int_ior = 1.5046f, ext_ior = 1.000277f, alpha = 0.1f;
  if (type == "diffuse") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"albedo"}));
    Color3f albedo{0.5f, 0.5f, 0.5f};
    PTLAB_RETURN_IF_ERROR(props.Color("albedo", &albedo));
    PTLAB_RETURN_IF_ERROR(CheckColor(props, "albedo", albedo, Range::kUnit));
    return materials.AddDiffuse(albedo);
  }
  if (type == "mirror") {
    PTLAB_RETURN_IF_ERROR(props.Expect({}));
    return materials.AddMirror();
  }
  if (type == "dielectric") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"intIOR", "extIOR", "schlick", "scaleRadiance"}));
    PTLAB_RETURN_IF_ERROR(props.Float("intIOR", &int_ior));
    PTLAB_RETURN_IF_ERROR(props.Float("extIOR", &ext_ior));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "intIOR", int_ior));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "extIOR", ext_ior));
    // ptlab extensions: Schlick's approximation (as CS184's glass) and the (η_o/η_i)²
    // radiance scaling on refraction; both off by default, as in Nori.
    bool schlick = false, scale_radiance = false;
    PTLAB_RETURN_IF_ERROR(props.Boolean("schlick", &schlick));
    PTLAB_RETURN_IF_ERROR(props.Boolean("scaleRadiance", &scale_radiance));
    const uint8_t flags = uint8_t((schlick ? kDielectricSchlick : 0) |
                                  (scale_radiance ? kDielectricScaleRadiance : 0));
    return materials.AddDielectric(int_ior, ext_ior, flags);
  }
  if (type == "microfacet") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"alpha", "intIOR", "extIOR", "kd"}));
    Color3f kd{0.5f, 0.5f, 0.5f};
    PTLAB_RETURN_IF_ERROR(props.Float("alpha", &alpha));
    PTLAB_RETURN_IF_ERROR(props.Float("intIOR", &int_ior));
    PTLAB_RETURN_IF_ERROR(props.Float("extIOR", &ext_ior));
    PTLAB_RETURN_IF_ERROR(props.Color("kd", &kd));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "alpha", alpha));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "intIOR", int_ior));
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "extIOR", ext_ior));
    PTLAB_RETURN_IF_ERROR(CheckColor(props, "kd", kd, Range::kUnit));
    return materials.AddRoughPlastic(alpha, int_ior, ext_ior, kd);
  }
  if (type == "roughconductor") {
    PTLAB_RETURN_IF_ERROR(props.Expect({"alpha", "eta", "k", "material"}));
    // Mitsuba's roughconductor: a named `material` (default Cu) or explicit eta and k.
    Color3f eta, k;
    PTLAB_RETURN_IF_ERROR(props.Float("alpha", &alpha));
    if (props.Has("eta") || props.Has("k")) {
      if (props.Has("material"))
        return props.Error("material", "give either string 'material' or colors 'eta' and "
                                       "'k', not both");
      PTLAB_RETURN_IF_ERROR(props.Require("eta", "color"));
      PTLAB_RETURN_IF_ERROR(props.Require("k", "color"));
      PTLAB_RETURN_IF_ERROR(props.Color("eta", &eta));
      PTLAB_RETURN_IF_ERROR(props.Color("k", &k));
    } else {
      std::string name = "Cu";
      PTLAB_RETURN_IF_ERROR(props.String("material", &name));
      if (!LookupConductorPreset(name, &eta, &k)) {
        return props.Error("material", "unknown conductor '" + name + "'; expected one of " +
                                            std::string(ConductorPresetNames()));
      }
    }
    PTLAB_RETURN_IF_ERROR(CheckPositive(props, "alpha", alpha));
    PTLAB_RETURN_IF_ERROR(CheckColor(props, "eta", eta, Range::kNonNegative));
    PTLAB_RETURN_IF_ERROR(CheckColor(props, "k", k, Range::kNonNegative));
    return materials.AddConductor(alpha, eta, k);
  }
  return at_.Error(node, "unknown bsdf type '" + type +
                             "'; expected diffuse, mirror, dielectric, microfacet or "
                             "roughconductor");
}

}  // namespace ptlab::internal
