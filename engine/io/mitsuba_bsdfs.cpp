// Mitsuba <bsdf>s that map exactly to ptlab's materials: diffuse, dielectric, (matA) conductor,
// roughconductor, roughdielectric, (matB) plastic, roughplastic, thindielectric, twosided, blendbsdf.
#include <string_view>

#include "engine/bsdf/plastic_precompute.h"      // matB
#include "engine/io/mitsuba_microfacet_bsdfs.h"  // matA
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/xml_properties.h"  // FormatColor

namespace ptlab::internal {
namespace {

// matB: a colour property that must be ≥ 0 (and ≤ 1 when `at_most_one`).
Status CheckedColor(const MitsubaObject& obj, const char* name, bool at_most_one, Color3f* c) {
  PTLAB_RETURN_IF_ERROR(obj.Color(name, SpectrumUse::kReflectance, c));
  const bool ok = c->r >= 0 && c->g >= 0 && c->b >= 0 &&
                  (!at_most_one || (c->r <= 1 && c->g <= 1 && c->b <= 1));
  if (!ok)
    return obj.Error(name, std::string(name) + " (" + FormatColor(*c) +
                               ") is out of range; expected components in " +
                               (at_most_one ? "[0, 1]" : "[0, inf)"));
  return Status::Ok();
}

// matB: Mitsuba's `plastic` and `roughplastic`.
StatusOr<PlasticDesc> ReadPlastic(const MitsubaObject& obj, bool rough) {
  std::vector<const char*> names = {"int_ior", "ext_ior", "diffuse_reflectance",
                                    "specular_reflectance", "nonlinear"};
  if (rough) names.insert(names.end(), {"distribution", "alpha", "sample_visible"});
  PTLAB_RETURN_IF_ERROR(obj.Expect(names));
  PlasticDesc p;
  PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "int_ior", &p.int_ior));
  PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "ext_ior", &p.ext_ior));
  PTLAB_RETURN_IF_ERROR(CheckedColor(obj, "diffuse_reflectance", true, &p.diffuse));
  PTLAB_RETURN_IF_ERROR(CheckedColor(obj, "specular_reflectance", false, &p.specular));
  PTLAB_RETURN_IF_ERROR(obj.Boolean("nonlinear", &p.nonlinear));
  if (!rough) return p;
  std::string distribution = "beckmann";
  PTLAB_RETURN_IF_ERROR(obj.String("distribution", &distribution));
  if (distribution == "beckmann") p.distribution = CoatingDistribution::kBeckmann;
  else if (distribution == "ggx") p.distribution = CoatingDistribution::kGgx;
  else
    return obj.Error("distribution", "unknown distribution '" + distribution +
                                         "'; expected beckmann or ggx");
  PTLAB_RETURN_IF_ERROR(obj.Float("alpha", &p.alpha));
  if (!(p.alpha >= 1e-4f && p.alpha <= 1.0f))
    return obj.Error("alpha", "alpha must be in [1e-4, 1]");
  PTLAB_RETURN_IF_ERROR(obj.OnlyDefault("sample_visible", true));
  return p;
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
    // A textured reflectance (<texture name="reflectance"> or <ref name="reflectance">).
    if (const MitsubaProperty* p = obj.Get("reflectance");
        p && p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture") {
      StatusOr<uint32_t> texture = Texture(*p->object);
      if (!texture.ok()) return texture.status();
      ref = scene_.materials.AddTexturedDiffuse(*texture);
      bsdfs_[&node] = ref;
      return ref;
    }
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
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "int_ior", &int_ior));
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "ext_ior", &ext_ior));
    for (const char* name : {"specular_reflectance", "specular_transmittance"}) {
      Color3f c{1, 1, 1};
      PTLAB_RETURN_IF_ERROR(obj.Color(name, SpectrumUse::kReflectance, &c));
      if (c.r != 1 || c.g != 1 || c.b != 1)
        return obj.Error(name,
                         "unsupported: bsdf \"dielectric\" with " + std::string(name) + " != 1");
    }
    // Mitsuba scales radiance by (η_o/η_i)² on refraction.
    ref = scene_.materials.AddDielectric(int_ior, ext_ior, kDielectricScaleRadiance);
  } else if (type == "plastic" || type == "roughplastic") {  // matB
    StatusOr<PlasticDesc> desc = ReadPlastic(obj, type == "roughplastic");
    if (!desc.ok()) return desc.status();
    StatusOr<PlasticRow> row = MakePlasticRow(*desc);
    if (!row.ok()) return Unsupported(node, row.status().message());
    ref = scene_.materials.AddPlastic(*row);
  } else if (type == "thindielectric") {  // matB
    PTLAB_RETURN_IF_ERROR(
        obj.Expect({"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"}));
    float int_ior = 1.5046f, ext_ior = 1.000277f;  // Mitsuba's defaults: bk7 in air
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "int_ior", &int_ior));
    PTLAB_RETURN_IF_ERROR(MitsubaIor(obj, "ext_ior", &ext_ior));
    Color3f refl{1, 1, 1}, trans{1, 1, 1};
    PTLAB_RETURN_IF_ERROR(CheckedColor(obj, "specular_reflectance", false, &refl));
    PTLAB_RETURN_IF_ERROR(CheckedColor(obj, "specular_transmittance", false, &trans));
    ref = scene_.materials.AddThinDielectric(int_ior / ext_ior, refl, trans);
  } else if (type == "twosided" || type == "blendbsdf") {  // matB: wrappers of nested bsdfs
    return WrapperBsdf(node, obj);
  } else if (type == "conductor" || type == "roughconductor" || type == "roughdielectric") {
    // matA: the microfacet family (engine/io/mitsuba_microfacet_bsdfs.cpp).
    // mask: a textured alpha / alpha_u / alpha_v (resolved here, where textures are built).
    MicrofacetRoughnessTextures rough;
    for (const char* name : {"alpha", "alpha_u", "alpha_v"}) {
      const MitsubaProperty* p = obj.Get(name);
      if (p == nullptr || p->type != MitsubaProperty::Type::kObject || p->object->tag != "texture")
        continue;
      StatusOr<uint32_t> texture = ScalarTexture(*p->object);
      if (!texture.ok()) return texture.status();
      const std::string_view n = name;
      if (n != "alpha_v") rough.alpha_u = *texture;
      if (n != "alpha_u") rough.alpha_v = *texture;
    }
    StatusOr<MaterialRef> added =
        AddMitsubaMicrofacetBsdf(obj, doc_.search_paths, &scene_.materials, rough);
    if (!added.ok()) return added.status();
    ref = *added;
    // Mitsuba orients an anisotropic lobe by ∂p/∂u (its shading frame's tangent).
    const MaterialTables& m = scene_.materials;
    const uint32_t row = ref.index();
    bool anisotropic = false;
    if (ref.tag() == MaterialTag::kConductor && m.conductor.microfacet()) {
      const ConductorTable& c = m.conductor;
      anisotropic = c.alpha[row] != c.alpha_v[row] ||
                    (c.textured() && (c.alpha_texture[row] != kNoTexture ||
                                      c.alpha_v_texture[row] != kNoTexture));
    } else if (ref.tag() == MaterialTag::kRoughDielectric) {
      const RoughDielectricTable& r = m.rough_dielectric;
      anisotropic = r.alpha_u[row] != r.alpha_v[row] ||
                    (r.textured() && (r.alpha_texture[row] != kNoTexture ||
                                      r.alpha_v_texture[row] != kNoTexture));
    }
    if (anisotropic) UvAlignedFrame(ref);
  } else if (type == "normalmap" || type == "bumpmap") {  // normal
    return PerturbedBsdf(node, obj);
  } else if (type == "principled" || type == "principledthin") {  // principled
    return PrincipledBsdf(node, obj);
  } else if (type == "mask") {  // mask: engine/io/mitsuba_mask_bsdf.cpp
    return MaskBsdf(node, obj);
  } else if (type == "null" ||
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

// matB: `twosided` (one nested bsdf, flagged two-sided: engine/scene/two_sided.h) and
// `blendbsdf` (two nested bsdfs, a scalar weight).
StatusOr<MaterialRef> MitsubaSceneBuilder::WrapperBsdf(const MitsubaNode& node,
                                                       const MitsubaObject& obj) {
  const std::vector<const MitsubaNode*>& kids = obj.children();
  for (const MitsubaNode* k : kids)
    if (k->tag != "bsdf")
      return k->Error("<" + k->tag + "> is not allowed inside " + DescribeMitsuba(node));
  MaterialRef ref;
  if (obj.type() == "twosided") {
    PTLAB_RETURN_IF_ERROR(obj.Expect({}));
    if (kids.size() == 2)
      return Unsupported(node, "a different bsdf on the back side (two nested bsdfs)");
    if (kids.size() != 1) return node.Error("twosided expects one nested <bsdf>");
    // The flag belongs to the child's row: a child that other shapes may use one-sided (a
    // bsdf with an id, or one already built) would become two-sided for them too.
    if (kids[0]->Attribute("id") != nullptr || bsdfs_.count(kids[0]) != 0)
      return Unsupported(node, "a nested bsdf that is referenced elsewhere (give twosided its "
                               "own nested bsdf)");
    StatusOr<MaterialRef> child = Bsdf(*kids[0]);
    if (!child.ok()) return child.status();
    ref = *child;
    scene_.materials.two_sided.Set(ref);
  } else {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"weight"}));
    const MitsubaProperty* p = obj.Get("weight");
    float weight = 0.5f;
    uint32_t weight_texture = kNoTexture;  // mask: a textured weight
    if (p != nullptr && p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture") {
      StatusOr<uint32_t> texture = ScalarTexture(*p->object);
      if (!texture.ok()) return texture.status();
      weight_texture = *texture;
    } else {
      PTLAB_RETURN_IF_ERROR(obj.Float("weight", &weight));
      if (!(weight >= 0 && weight <= 1)) return obj.Error("weight", "weight must be in [0, 1]");
    }
    if (kids.size() != 2) return node.Error("blendbsdf expects two nested <bsdf>s");
    StatusOr<MaterialRef> a = Bsdf(*kids[0]);
    if (!a.ok()) return a.status();
    StatusOr<MaterialRef> b = Bsdf(*kids[1]);
    if (!b.ok()) return b.status();
    // normal: a blend's children are evaluated without their shading point's frame.
    const ShadingPerturbations& perturbation = scene_.materials.perturbation;
    if ((perturbation.Of(*a) >= 0 && !IsUvAlignedFrame(perturbation.Of(*a))) ||
        (perturbation.Of(*b) >= 0 && !IsUvAlignedFrame(perturbation.Of(*b))))
      return Unsupported(node, "a normalmap or bumpmap inside a blendbsdf");
    ref = scene_.materials.AddBlend(weight, *a, *b, weight_texture);
  }
  bsdfs_[&node] = ref;
  return ref;
}

}  // namespace ptlab::internal
