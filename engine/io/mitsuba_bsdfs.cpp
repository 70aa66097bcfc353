// Mitsuba <bsdf>s that map exactly to ptlab's materials: diffuse, dielectric, and (matA) conductor,
// roughconductor, roughdielectric.
#include "engine/io/mitsuba_microfacet_bsdfs.h"  // matA
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/xml_properties.h"  // FormatColor

namespace ptlab::internal {
namespace {

// An IOR given as a number or as one of Mitsuba's names ("bk7", "air", ...).
Status Ior(const MitsubaObject& obj, const char* name, float* ior) {
  const MitsubaProperty* p = obj.Get(name);
  if (p && p->type == MitsubaProperty::Type::kString) {
    if (!LookupNamedIor(p->text, ior))
      return obj.Error(name, "unknown IOR name '" + p->text + "'; expected a number or one of " +
                                 NamedIorList());
    return Status::Ok();
  }
  PTLAB_RETURN_IF_ERROR(obj.Float(name, ior));
  if (!(*ior > 0)) return obj.Error(name, std::string(name) + " must be > 0");
  return Status::Ok();
}

}  // namespace

StatusOr<MaterialRef> MitsubaSceneBuilder::Bsdf(const MitsubaNode& node) {
  if (const auto it = bsdfs_.find(&node); it != bsdfs_.end()) return it->second;
  StatusOr<MitsubaObject> read = Read(node);
  if (!read.ok()) return read.status();
  const MitsubaObject& obj = *read;
  const std::string& type = obj.type();
  MaterialRef ref;
  if (type == "diffuse") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"reflectance"}));
    Color3f albedo{0.5f, 0.5f, 0.5f};
    PTLAB_RETURN_IF_ERROR(obj.Color("reflectance", SpectrumUse::kReflectance, &albedo));
    if (!(albedo.r >= 0 && albedo.g >= 0 && albedo.b >= 0 && albedo.r <= 1 && albedo.g <= 1 &&
          albedo.b <= 1))
      return obj.Error("reflectance", "reflectance (" + FormatColor(albedo) +
                                          ") is out of range; expected components in [0, 1]");
    ref = scene_.materials.AddDiffuse(albedo);
  } else if (type == "dielectric") {
    PTLAB_RETURN_IF_ERROR(
        obj.Expect({"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"}));
    float int_ior = 1.5046f, ext_ior = 1.000277f;  // Mitsuba's defaults: bk7 in air
    PTLAB_RETURN_IF_ERROR(Ior(obj, "int_ior", &int_ior));
    PTLAB_RETURN_IF_ERROR(Ior(obj, "ext_ior", &ext_ior));
    for (const char* name : {"specular_reflectance", "specular_transmittance"}) {
      Color3f c{1, 1, 1};
      PTLAB_RETURN_IF_ERROR(obj.Color(name, SpectrumUse::kReflectance, &c));
      if (c.r != 1 || c.g != 1 || c.b != 1)
        return obj.Error(name,
                         "unsupported: bsdf \"dielectric\" with " + std::string(name) + " != 1");
    }
    // Mitsuba scales radiance by (η_o/η_i)² on refraction.
    ref = scene_.materials.AddDielectric(int_ior, ext_ior, kDielectricScaleRadiance);
  } else if (type == "twosided") {
    return Unsupported(node,
                       "ptlab's diffuse is one-sided like Mitsuba's, and has no two-sided "
                       "form");
  } else if (type == "conductor" || type == "roughconductor" || type == "roughdielectric") {
    // matA: the microfacet family (engine/io/mitsuba_microfacet_bsdfs.cpp).
    StatusOr<MaterialRef> added = AddMitsubaMicrofacetBsdf(obj, doc_.search_paths, &scene_.materials);
    if (!added.ok()) return added.status();
    ref = *added;
  } else if (type == "plastic" || type == "roughplastic" || type == "thindielectric" ||
             type == "principled" || type == "principledthin" || type == "mask" ||
             type == "normalmap" || type == "bumpmap" || type == "blendbsdf" || type == "null" ||
             type == "polarizer" || type == "retarder" || type == "circular" ||
             type == "measured" || type == "pplastic" || type == "hair") {
    return Unsupported(node);
  } else {
    return node.Error("unknown bsdf type '" + type + "'");
  }
  if (!obj.children().empty())
    return obj.children()[0]->Error("<" + obj.children()[0]->tag + "> is not allowed inside " +
                                    DescribeMitsuba(node));
  bsdfs_[&node] = ref;
  return ref;
}

}  // namespace ptlab::internal
