// Mitsuba <bsdf>s of the microfacet family: conductor, roughconductor, roughdielectric.
#include "engine/io/mitsuba_microfacet_bsdfs.h"

#include <string_view>

#include <cmath>

#include "engine/io/mitsuba_loader.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/xml_properties.h"  // FormatColor

namespace ptlab::internal {
namespace {

// η and k: a `material` name or explicit colours (not both), Mitsuba's default "none".
Status ComplexIor(const MitsubaObject& obj, const std::vector<std::string>& search_paths,
                  Color3f* eta, Color3f* k) {
  std::string material = "none";
  PTLAB_RETURN_IF_ERROR(obj.String("material", &material));
  if (obj.Has("eta") || obj.Has("k")) {
    if (obj.Has("material"))
      return obj.Error("material", "give either string 'material' or 'eta' and 'k', not both");
    *eta = {0, 0, 0}, *k = {1, 1, 1};  // Mitsuba's defaults of the two
    PTLAB_RETURN_IF_ERROR(obj.Color("eta", SpectrumUse::kUnbounded, eta));
    PTLAB_RETURN_IF_ERROR(obj.Color("k", SpectrumUse::kUnbounded, k));
    for (const char* name : {"eta", "k"}) {
      const Color3f c = name[0] == 'e' ? *eta : *k;
      if (!(c.r >= 0 && c.g >= 0 && c.b >= 0 && IsFinite(c)))
        return obj.Error(name, std::string(name) + " (" + FormatColor(c) +
                                   ") is out of range; expected finite components >= 0");
    }
    return Status::Ok();
  }
  const Status s = LookupMitsubaConductor(search_paths, material, eta, k);
  if (!s.ok()) return obj.Error("material", s.message());
  return Status::Ok();
}

// specular_reflectance / specular_transmittance: a constant colour in [0, 1].
Status Specular(const MitsubaObject& obj, const char* name, Color3f* c) {
  *c = {1, 1, 1};
  PTLAB_RETURN_IF_ERROR(obj.Color(name, SpectrumUse::kReflectance, c));
  if (!(c->r >= 0 && c->g >= 0 && c->b >= 0 && c->r <= 1 && c->g <= 1 && c->b <= 1))
    return obj.Error(name, std::string(name) + " (" + FormatColor(*c) +
                               ") is out of range; expected components in [0, 1]");
  return Status::Ok();
}

// distribution, alpha | alpha_u + alpha_v, sample_visible → αu, αv, MicrofacetFlags.
Status Roughness(const MitsubaObject& obj, float* alpha_u, float* alpha_v, uint8_t* flags,
                 const MicrofacetRoughnessTextures& textures = {}) {
  std::string distribution = "beckmann";
  PTLAB_RETURN_IF_ERROR(obj.String("distribution", &distribution));
  for (char& ch : distribution) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (distribution != "beckmann" && distribution != "ggx")
    return obj.Error("distribution", "unknown distribution '" + distribution +
                                         "'; expected beckmann or ggx");
  *flags = distribution == "ggx" ? uint8_t{kMicrofacetGgx} : uint8_t{0};
  bool visible = true;
  PTLAB_RETURN_IF_ERROR(obj.Boolean("sample_visible", &visible));
  if (visible) *flags |= kMicrofacetSampleVisible;
  const bool has_u = obj.Has("alpha_u"), has_v = obj.Has("alpha_v");
  if (has_u || has_v) {
    if (obj.Has("alpha"))
      return obj.Error("alpha", "give either 'alpha' or 'alpha_u' and 'alpha_v', not both");
    if (!has_u || !has_v)
      return obj.Error(has_u ? "alpha_u" : "alpha_v", "both 'alpha_u' and 'alpha_v' are needed");
    // mask: a textured αu / αv is not read as a number (its constant stays 0.1, unused).
    *alpha_u = *alpha_v = 0.1f;
    if (textures.alpha_u == kNoTexture) PTLAB_RETURN_IF_ERROR(obj.Float("alpha_u", alpha_u));
    if (textures.alpha_v == kNoTexture) PTLAB_RETURN_IF_ERROR(obj.Float("alpha_v", alpha_v));
  } else {
    *alpha_u = 0.1f;
    if (textures.alpha_u == kNoTexture) PTLAB_RETURN_IF_ERROR(obj.Float("alpha", alpha_u));
    *alpha_v = *alpha_u;
  }
  for (const char* name : {"alpha", "alpha_u", "alpha_v"}) {
    // mask: "alpha_v"[5] is '_': compare the name (the old test read αu for alpha_v).
    const float a = std::string_view(name) == "alpha_v" ? *alpha_v : *alpha_u;
    // Mitsuba clamps α to 1e-4 (with a warning for 0); so does ptlab (MakeMicrofacet).
    if (obj.Has(name) && !(a >= 0 && std::isfinite(a)))
      return obj.Error(name, std::string(name) + " = " + std::to_string(a) +
                                 " is out of range; expected a finite value >= 0");
  }
  return Status::Ok();
}

}  // namespace

Status MitsubaIor(const MitsubaObject& obj, const char* name, float* ior) {
  const MitsubaProperty* p = obj.Get(name);
  if (p && p->type == MitsubaProperty::Type::kString) {
    if (!LookupNamedIor(p->text, ior))
      return obj.Error(name, "unknown IOR name '" + p->text + "'; expected a number or one of " +
                                 NamedIorList());
    return Status::Ok();
  }
  PTLAB_RETURN_IF_ERROR(obj.Float(name, ior));
  if (!(*ior > 0) || !std::isfinite(*ior))
    return obj.Error(name, std::string(name) + " must be a finite number > 0");
  return Status::Ok();
}

StatusOr<MaterialRef> AddMitsubaMicrofacetBsdf(const MitsubaObject& obj,
                                               const std::vector<std::string>& search_paths,
                                               MaterialTables* materials,
                                               const MicrofacetRoughnessTextures& textures) {
  const std::string& type = obj.type();
  // mask: roughconductor and roughdielectric take a textured roughness.
  if (type != "roughconductor" && type != "roughdielectric" &&
      (textures.alpha_u != kNoTexture || textures.alpha_v != kNoTexture)) {
    const char* name = obj.Has("alpha") ? "alpha" : "alpha_u";
    return obj.Error(name, "unsupported: bsdf \"" + type + "\" with a textured " + name);
  }
  if (type == "conductor") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"material", "eta", "k", "specular_reflectance"}));
    Color3f eta, k, specular;
    PTLAB_RETURN_IF_ERROR(ComplexIor(obj, search_paths, &eta, &k));
    PTLAB_RETURN_IF_ERROR(Specular(obj, "specular_reflectance", &specular));
    return materials->AddSmoothConductor(eta, k, specular);
  }
  if (type == "roughconductor") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"material", "eta", "k", "specular_reflectance",
                                      "distribution", "alpha", "alpha_u", "alpha_v",
                                      "sample_visible"}));
    Color3f eta, k, specular;
    PTLAB_RETURN_IF_ERROR(ComplexIor(obj, search_paths, &eta, &k));
    PTLAB_RETURN_IF_ERROR(Specular(obj, "specular_reflectance", &specular));
    float alpha_u, alpha_v;
    uint8_t flags;
    PTLAB_RETURN_IF_ERROR(Roughness(obj, &alpha_u, &alpha_v, &flags, textures));
    if (textures.alpha_u != kNoTexture || textures.alpha_v != kNoTexture)  // mask
      return materials->AddTexturedRoughConductor(alpha_u, alpha_v, textures.alpha_u,
                                                  textures.alpha_v, flags, eta, k, specular);
    return materials->AddRoughConductor(alpha_u, alpha_v, flags, eta, k, specular);
  }
  if (type == "roughdielectric") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"int_ior", "ext_ior", "specular_reflectance",
                                      "specular_transmittance", "distribution", "alpha",
                                      "alpha_u", "alpha_v", "sample_visible"}));
    float int_ior = 1.5046f, ext_ior = 1.000277f;  // Mitsuba's defaults: bk7 in air
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "int_ior", &int_ior));
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "ext_ior", &ext_ior));
    Color3f reflectance, transmittance;
    PTLAB_RETURN_IF_ERROR(Specular(obj, "specular_reflectance", &reflectance));
    PTLAB_RETURN_IF_ERROR(Specular(obj, "specular_transmittance", &transmittance));
    float alpha_u, alpha_v;
    uint8_t flags;
    PTLAB_RETURN_IF_ERROR(Roughness(obj, &alpha_u, &alpha_v, &flags, textures));
    if (textures.alpha_u != kNoTexture || textures.alpha_v != kNoTexture)
      return materials->AddTexturedRoughDielectric(alpha_u, alpha_v, textures.alpha_u,
                                                   textures.alpha_v, flags, int_ior, ext_ior,
                                                   reflectance, transmittance);
    return materials->AddRoughDielectric(alpha_u, alpha_v, flags, int_ior, ext_ior, reflectance,
                                         transmittance);
  }
  return obj.Error("type", "not a microfacet bsdf: '" + type + "'");
}

}  // namespace ptlab::internal
