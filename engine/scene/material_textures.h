// The textures a material row reads (its own textured parameters and its nested materials').
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/scene/material_tables.h"

namespace ptlab {

/// Appends to *ids (once each) the texture rows that `ref` reads: the diffuse albedo, a
/// blend's weight and its children's, a mask's opacity and its nested material's, a rough
/// conductor's αu and αv, a principled row's parameters. Tags without textured parameters add nothing.
inline void MaterialTextures(const MaterialTables& m, MaterialRef ref, std::vector<uint32_t>* ids) {
  const auto add = [ids](const AlignedVector<uint32_t>& column, uint32_t row) {
    if (row >= column.size() || column[row] == kNoTexture) return;
    if (std::find(ids->begin(), ids->end(), column[row]) == ids->end()) ids->push_back(column[row]);
  };
  if (!ref.valid()) return;
  const uint32_t i = ref.index();
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return add(m.diffuse.albedo_texture, i);
    case MaterialTag::kConductor:
      add(m.conductor.alpha_texture, i);
      return add(m.conductor.alpha_v_texture, i);
    case MaterialTag::kRoughDielectric:
      add(m.rough_dielectric.alpha_texture, i);
      return add(m.rough_dielectric.alpha_v_texture, i);
    case MaterialTag::kBlend:
      add(m.blend.weight_texture, i);
      MaterialTextures(m, m.blend.First(i), ids);
      return MaterialTextures(m, m.blend.Second(i), ids);
    case MaterialTag::kMask:
      add(m.mask.opacity_texture, i);
      return MaterialTextures(m, m.mask.Nested(i), ids);
    case MaterialTag::kPrincipled:
    case MaterialTag::kPrincipledThin: {
      const PrincipledTable& t =
          ref.tag() == MaterialTag::kPrincipled ? m.principled : m.principled_thin;
      add(t.base_color_texture, i);
      for (const AlignedVector<uint32_t>& column : t.texture) add(column, i);
      return;
    }
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
    case MaterialTag::kRoughPlastic:
    case MaterialTag::kPlastic:
    case MaterialTag::kThinDielectric:
      return;
  }
}

}  // namespace ptlab
