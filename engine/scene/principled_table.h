// Mitsuba 3 `principled` and `principledthin` rows (SoA): Burley's Disney BSDF parameters, each
// optionally driven by a texture (docs/materials.md, "Principled BSDFs").
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/texture_tables.h"  // kNoTexture

namespace ptlab {

/// The scalar parameters of a principled row, in column order. `kEta` is the relative IOR
/// (principled: from `eta` or `specular`, never textured; principledthin: `eta`, textured or
/// not). `kDiffTrans` is principledthin's only (Mitsuba's range [0, 2]).
enum PrincipledParam : uint8_t {
  kPrincipledRoughness = 0,
  kPrincipledAnisotropic,
  kPrincipledMetallic,
  kPrincipledSpecTint,
  kPrincipledSheen,
  kPrincipledSheenTint,
  kPrincipledClearcoat,
  kPrincipledClearcoatGloss,
  kPrincipledSpecTrans,
  kPrincipledFlatness,
  kPrincipledDiffTrans,
  kPrincipledEta,
  kPrincipledParamCount,
};

/// One row as the loader gives it: constants and, per parameter, a texture id (kNoTexture:
/// the constant). Defaults are Mitsuba's.
struct PrincipledRow {
  Color3f base_color{0.5f, 0.5f, 0.5f};
  uint32_t base_color_texture = kNoTexture;
  float value[kPrincipledParamCount] = {0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1.5f};
  uint32_t texture[kPrincipledParamCount] = {kNoTexture, kNoTexture, kNoTexture, kNoTexture,
                                             kNoTexture, kNoTexture, kNoTexture, kNoTexture,
                                             kNoTexture, kNoTexture, kNoTexture, kNoTexture};
};

/// The rows of one of the two models (MaterialTables::principled, ::principled_thin). Texture-id
/// columns follow the textured-parameter pattern: `base_color_texture` and `texture[p]` stay
/// empty until a row's parameter is textured, then hold one id per row.
struct PrincipledTable {
  AlignedVector<float> base_r, base_g, base_b;
  AlignedVector<float> value[kPrincipledParamCount];
  AlignedVector<uint32_t> base_color_texture;
  AlignedVector<uint32_t> texture[kPrincipledParamCount];

  size_t size() const { return base_r.size(); }
  Color3f BaseColor(size_t i) const { return {base_r[i], base_g[i], base_b[i]}; }

  uint32_t Add(const PrincipledRow& row) {
    const size_t i = size();
    base_r.push_back(row.base_color.r), base_g.push_back(row.base_color.g),
        base_b.push_back(row.base_color.b);
    AddTexture(&base_color_texture, i, row.base_color_texture);
    for (int p = 0; p < kPrincipledParamCount; ++p) {
      value[p].push_back(row.value[p]);
      AddTexture(&texture[p], i, row.texture[p]);
    }
    return uint32_t(i);
  }

 private:
  static void AddTexture(AlignedVector<uint32_t>* column, size_t i, uint32_t id) {
    if (id == kNoTexture && column->empty()) return;
    column->resize(i, kNoTexture);
    column->push_back(id);
  }
};

}  // namespace ptlab
