// COLLADA <effect>: the CGL BSDF extras (CS184) and the common profile's diffuse fallback.
#pragma once

#include <pugixml.hpp>

#include "engine/core/status.h"
#include "engine/io/collada_document.h"
#include "engine/scene/material_tables.h"

namespace ptlab::collada {

/// A material as CS184 defines it, before it becomes a row of ptlab's tables.
struct Effect {
  enum class Model { kDiffuse, kMirror, kGlass, kRefraction, kMicrofacet, kEmission };
  Model model = Model::kDiffuse;
  Color3f reflectance{0.5f, 0.5f, 0.5f};  // diffuse albedo, mirror/glass reflectance
  Color3f transmittance{1, 1, 1};         // glass, refraction
  Color3f radiance;                       // emission
  float ior = 1.5f, alpha = 0.1f;         // glass/refraction IOR; microfacet roughness
  Color3f eta, k;                         // microfacet conductor (RGB)
  pugi::xml_node node;                    // the <effect> or its CGL BSDF element, for messages
};

/// Reads an <effect>: the first element of its <technique profile="CGL"> when there is one
/// (diffuse, mirror, glass, refraction, microfacet, emission), else the diffuse color of its
/// profile_COMMON technique (phong, blinn, lambert or constant; 0.5 grey when it has none).
StatusOr<Effect> ReadEffect(const Document& doc, const pugi::xml_node& effect);

/// Adds the ptlab row for `effect` (docs/cs184.md gives the mapping): diffuse →
/// Lambertian; mirror → mirror; glass → dielectric with Schlick's Fresnel and radiance scaling
/// (CS184 GlassBSDF), exterior IOR 1; refraction → the same, refraction only; microfacet →
/// Beckmann conductor with the RGB η, k; emission → black Lambertian (its radiance becomes an
/// area light on the mesh). Reflectance or transmittance other than 1 on mirror/glass/
/// refraction is an error "not supported yet" (ptlab's delta BSDFs have no tint).
StatusOr<MaterialRef> AddEffectMaterial(const Document& doc, const Effect& effect,
                                        MaterialTables* materials);

}  // namespace ptlab::collada
