// Mitsuba <bsdf>s of the microfacet family: conductor, roughconductor, roughdielectric.
#pragma once

#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/mitsuba_properties.h"
#include "engine/scene/material_tables.h"

namespace ptlab::internal {

/// An IOR property of a Mitsuba BSDF (`int_ior`, `ext_ior`): a finite number > 0 or one of
/// Mitsuba's names ("bk7", "air", ...). Left unchanged when absent.
Status MitsubaIor(const MitsubaObject& obj, const char* name, float* ior);

/// Adds the material of `obj` (type conductor, roughconductor or roughdielectric) to
/// `materials` with Mitsuba 3's parameters and defaults: `material` names (default "none", the
/// perfect mirror) are read from ior/NAME.{eta,k}.spd in `search_paths` (LookupMitsubaConductor);
/// `distribution` beckmann (default) or ggx; `alpha` (default 0.1) or both `alpha_u` and
/// `alpha_v`; `sample_visible` (default true); int_ior / ext_ior as numbers or names (default
/// bk7 / air); specular_reflectance / specular_transmittance as constant colours. Errors name
/// the file, line and the accepted values.
/// mask: the texture rows (TextureTable ids, kNoTexture when constant) of a roughconductor's
/// `alpha` (both) or `alpha_u` / `alpha_v` given as textures; the caller resolves them. A
/// textured roughness of another type stops with `unsupported`.
struct MicrofacetRoughnessTextures {
  uint32_t alpha_u = kNoTexture, alpha_v = kNoTexture;
};

StatusOr<MaterialRef> AddMitsubaMicrofacetBsdf(const MitsubaObject& obj,
                                               const std::vector<std::string>& search_paths,
                                               MaterialTables* materials,
                                               const MicrofacetRoughnessTextures& textures = {});

}  // namespace ptlab::internal
