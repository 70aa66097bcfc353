// Mitsuba <bsdf type="principled"> and <bsdf type="principledthin">: every parameter that Mitsuba
// lets a texture drive may be a <texture> (a texture-id column of PrincipledTable).
#include <cmath>
#include <string>
#include <vector>

#include "engine/bsdf/principled_lobes.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/xml_properties.h"  // FormatColor

namespace ptlab::internal {
namespace {

struct TexturableFloat {
  const char* name;
  PrincipledParam param;
  float lo, hi;  // the accepted range of a constant
};

// Mitsuba's get_flag: a lobe exists when its property is given and is not the number 0.
bool HasLobe(const MitsubaObject& obj, const char* name) {
  const MitsubaProperty* p = obj.Get(name);
  if (p == nullptr) return false;
  if (p->type == MitsubaProperty::Type::kFloat) return p->number != 0;
  if (p->type == MitsubaProperty::Type::kInteger) return p->integer != 0;
  return true;
}

bool IsTexture(const MitsubaProperty* p) {
  return p != nullptr && p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture";
}

}  // namespace

StatusOr<MaterialRef> MitsubaSceneBuilder::PrincipledBsdf(const MitsubaNode& node,
                                                          const MitsubaObject& obj) {
  const bool thin = obj.type() == "principledthin";
  std::vector<const char*> names = {"base_color", "roughness",  "anisotropic", "spec_trans",
                                    "sheen",      "sheen_tint", "flatness",    "spec_tint",
                                    "eta",        "diffuse_reflectance_sampling_rate"};
  std::vector<const char*> rates = {"diffuse_reflectance_sampling_rate"};
  if (thin) {
    for (const char* n : {"diff_trans", "specular_reflectance_sampling_rate",
                          "specular_transmittance_sampling_rate",
                          "diffuse_transmittance_sampling_rate"})
      names.push_back(n);
    rates.insert(rates.end(), {"specular_reflectance_sampling_rate",
                               "specular_transmittance_sampling_rate",
                               "diffuse_transmittance_sampling_rate"});
  } else {
    for (const char* n : {"metallic", "clearcoat", "clearcoat_gloss", "specular",
                          "main_specular_sampling_rate", "clearcoat_sampling_rate"})
      names.push_back(n);
    rates.insert(rates.end(), {"main_specular_sampling_rate", "clearcoat_sampling_rate"});
  }
  PTLAB_RETURN_IF_ERROR(obj.Expect(names));
  for (const char* rate : rates) {
    float r = 1.0f;
    PTLAB_RETURN_IF_ERROR(obj.Float(rate, &r));
    if (r != 1.0f) return Unsupported(node, std::string(rate) + " != 1");
  }

  PrincipledRow row;
  if (const MitsubaProperty* p = obj.Get("base_color"); IsTexture(p)) {
    StatusOr<uint32_t> texture = Texture(*p->object);
    if (!texture.ok()) return texture.status();
    row.base_color_texture = *texture;
  } else {
    PTLAB_RETURN_IF_ERROR(obj.Color("base_color", SpectrumUse::kReflectance, &row.base_color));
    const Color3f& c = row.base_color;
    if (!(c.r >= 0 && c.g >= 0 && c.b >= 0 && c.r <= 1 && c.g <= 1 && c.b <= 1))
      return obj.Error("base_color", "base_color (" + FormatColor(c) +
                                         ") is out of range; expected components in [0, 1]");
  }
  std::vector<TexturableFloat> floats = {
      {"roughness", kPrincipledRoughness, 0, 1},   {"anisotropic", kPrincipledAnisotropic, 0, 1},
      {"spec_trans", kPrincipledSpecTrans, 0, 1},  {"sheen", kPrincipledSheen, 0, 1},
      {"sheen_tint", kPrincipledSheenTint, 0, 1},  {"flatness", kPrincipledFlatness, 0, 1},
      {"spec_tint", kPrincipledSpecTint, 0, 1}};
  if (thin) {
    floats.push_back({"diff_trans", kPrincipledDiffTrans, 0, 2});
    floats.push_back({"eta", kPrincipledEta, 1e-4f, 1e4f});
  } else {
    floats.push_back({"metallic", kPrincipledMetallic, 0, 1});
    floats.push_back({"clearcoat", kPrincipledClearcoat, 0, 1});
    floats.push_back({"clearcoat_gloss", kPrincipledClearcoatGloss, 0, 1});
  }
  for (const TexturableFloat& f : floats) {
    if (const MitsubaProperty* p = obj.Get(f.name); IsTexture(p)) {
      StatusOr<uint32_t> texture = ScalarTexture(*p->object);
      if (!texture.ok()) return texture.status();
      row.texture[f.param] = *texture;
      continue;
    }
    float& v = row.value[f.param];
    PTLAB_RETURN_IF_ERROR(obj.Float(f.name, &v));
    if (!(v >= f.lo && v <= f.hi))
      return obj.Error(f.name, std::string(f.name) + " must be in [" + FormatNumber(f.lo) +
                                   ", " + FormatNumber(f.hi) + "]");
  }

  if (!thin) {
    // The relative IOR: `eta`, or `specular` s through η = 2 / (1 − √(0.08 s)) − 1 (s = 0.5:
    // η = 1.5), not both. With a transmission lobe, η = 1 and s = 0 are nudged off the
    // singular interface as Mitsuba does (η = 1.001, s = 1e-3).
    const bool transmission = HasLobe(obj, "spec_trans");
    if (obj.Has("eta") && obj.Has("specular"))
      return obj.Error("specular", "give either 'eta' or 'specular', not both");
    float& eta = row.value[kPrincipledEta];
    if (obj.Has("eta")) {
      if (IsTexture(obj.Get("eta")))
        return obj.Error("eta", "principled's eta is a number (not a texture)");
      PTLAB_RETURN_IF_ERROR(obj.Float("eta", &eta));
      if (!(eta >= 1e-4f && eta <= 1e4f)) return obj.Error("eta", "eta must be in [1e-4, 1e4]");
      if (transmission && eta == 1.0f) eta = 1.001f;
    } else {
      float specular = 0.5f;
      if (IsTexture(obj.Get("specular")))
        return obj.Error("specular", "principled's specular is a number (not a texture)");
      PTLAB_RETURN_IF_ERROR(obj.Float("specular", &specular));
      if (!(specular >= 0 && specular <= 12.0f))
        return obj.Error("specular", "specular must be in [0, 12]");
      if (transmission && specular == 0.0f) specular = 1e-3f;
      eta = PrincipledEtaFromSpecular(specular);
    }
  }
  const MaterialRef ref = scene_.materials.AddPrincipled(row, thin);
  // Mitsuba orients the anisotropic lobes by ∂p/∂u (its shading frame's tangent), as for the
  // rough conductor: a row that may be anisotropic gets the uv-aligned frame.
  if (row.value[kPrincipledAnisotropic] != 0.0f ||
      row.texture[kPrincipledAnisotropic] != kNoTexture)
    UvAlignedFrame(ref);
  if (!obj.children().empty())
    return obj.children()[0]->Error("<" + obj.children()[0]->tag + "> is not allowed inside " +
                                    DescribeMitsuba(node));
  bsdfs_[&node] = ref;
  return ref;
}

}  // namespace ptlab::internal
