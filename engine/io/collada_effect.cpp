// CS184's CGL material extras and the COLLADA common profile, mapped to ptlab's BSDF tables.
#include "engine/io/collada_effect.h"

#include <string>
#include <string_view>

#include "engine/scene/scene_limits.h"

namespace ptlab::collada {
namespace {

bool IsWhite(const Color3f& c) { return c.r == 1 && c.g == 1 && c.b == 1; }

// A required <name> color child of `node`.
Status RequiredColor(const Document& doc, const pugi::xml_node& node, const char* name,
                     Color3f* c) {
  const pugi::xml_node child = node.child(name);
  if (!child)
    return doc.Error(node, std::string("<") + std::string(node.name()) + "> has no <" + name +
                               ">; expected an RGB color");
  return doc.Color(child, c);
}

// A reflectance of `what` must not create energy: each channel <= 1 (>= 0 is Color's check).
Status CheckReflectance(const Document& doc, const pugi::xml_node& node, const Color3f& c,
                        const char* what) {
  if (!(c.r <= 1 && c.g <= 1 && c.b <= 1))
    return doc.Error(node, std::string(what) + " above 1; expected values in [0, 1]");
  return Status::Ok();
}

Status ReadCgl(const Document& doc, const pugi::xml_node& technique, Effect* e) {
  pugi::xml_node bsdf;
  for (const pugi::xml_node child : technique.children()) {
    if (child.type() != pugi::node_element) continue;
    if (bsdf)
      return doc.Error(child, std::string("a second BSDF <") + std::string(child.name()) +
                                  "> in the CGL technique (first <" + bsdf.name() + "> at " +
                                  doc.at.At(bsdf) + "); expected one");
    bsdf = child;
  }
  if (!bsdf) return doc.Error(technique, "the CGL technique has no BSDF element");
  e->node = bsdf;
  const std::string_view kind = bsdf.name();
  using M = Effect::Model;
  if (kind == "diffuse") {
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(bsdf, {"reflectance"}));
    e->model = M::kDiffuse;
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "reflectance", &e->reflectance));
    PTLAB_RETURN_IF_ERROR(CheckReflectance(doc, bsdf, e->reflectance, "diffuse reflectance"));
  } else if (kind == "mirror") {
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(bsdf, {"reflectance"}));
    e->model = M::kMirror;
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "reflectance", &e->reflectance));
    PTLAB_RETURN_IF_ERROR(CheckReflectance(doc, bsdf, e->reflectance, "mirror reflectance"));
  } else if (kind == "glass" || kind == "refraction") {
    PTLAB_RETURN_IF_ERROR(
        doc.CheckChildren(bsdf, {"reflectance", "transmittance", "roughness", "ior"}));
    e->model = kind == "glass" ? M::kGlass : M::kRefraction;
    e->reflectance = {1, 1, 1};
    if (bsdf.child("reflectance"))
      PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "reflectance", &e->reflectance));
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "transmittance", &e->transmittance));
    if (!bsdf.child("ior")) return doc.Error(bsdf, std::string("<") + std::string(kind) + "> has no <ior>");
    PTLAB_RETURN_IF_ERROR(doc.FixedFloats(bsdf.child("ior"), 1, &e->ior));
    if (!(e->ior > 0)) return doc.Error(bsdf.child("ior"), "ior must be > 0");
    float roughness = 0;
    PTLAB_RETURN_IF_ERROR(doc.OptionalFloat(bsdf, "roughness", &roughness));
    if (roughness != 0)
      return doc.NotSupported(bsdf.child("roughness"),
                              "rough glass; CS184 ignores it, ptlab refuses it");
  } else if (kind == "microfacet") {
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(bsdf, {"alpha", "eta", "k"}));
    e->model = M::kMicrofacet;
    if (!bsdf.child("alpha")) return doc.Error(bsdf, "<microfacet> has no <alpha>");
    PTLAB_RETURN_IF_ERROR(doc.FixedFloats(bsdf.child("alpha"), 1, &e->alpha));
    if (!(e->alpha > 0)) return doc.Error(bsdf.child("alpha"), "alpha must be > 0");
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "eta", &e->eta));
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "k", &e->k));
  } else if (kind == "emission") {
    PTLAB_RETURN_IF_ERROR(doc.CheckChildren(bsdf, {"radiance"}));
    e->model = M::kEmission;
    PTLAB_RETURN_IF_ERROR(RequiredColor(doc, bsdf, "radiance", &e->radiance));
  } else {
    return doc.NotSupported(bsdf, "CGL BSDF");
  }
  for (const Color3f* c : {&e->reflectance, &e->transmittance, &e->radiance, &e->eta, &e->k})
    if (!(c->r <= kMaxRadiance && c->g <= kMaxRadiance && c->b <= kMaxRadiance))
      return doc.Error(bsdf, "a value above " + std::to_string(kMaxRadiance) + " in <" +
                                 bsdf.name() + ">");
  return Status::Ok();
}

// profile_COMMON: <technique sid=..> holding one shading model; only its diffuse color is used.
Status ReadCommon(const Document& doc, const pugi::xml_node& profile, Effect* e) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(profile, {"technique", "newparam", "asset"}, true));
  if (profile.child("newparam"))
    return doc.NotSupported(profile.child("newparam"), "effect parameters (textures)");
  const pugi::xml_node technique = profile.child("technique");
  if (!technique) return doc.Error(profile, "<profile_COMMON> has no <technique>");
  PTLAB_RETURN_IF_ERROR(
      doc.CheckChildren(technique, {"phong", "blinn", "lambert", "constant"}, true));
  pugi::xml_node model;
  for (const pugi::xml_node child : technique.children())
    if (child.type() == pugi::node_element && std::string_view(child.name()) != "extra")
      model = child;
  if (!model) return doc.Error(technique, "the common technique has no shading model");
  // The shading model's other terms (specular, shininess, ambient, reflective, transparency,
  // index_of_refraction) are what Blender exports for its own renderer; CS184 renders the
  // diffuse color only, and so does ptlab (docs/cs184.md).
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(
      model, {"emission", "ambient", "diffuse", "specular", "shininess", "reflective",
              "reflectivity", "transparent", "transparency", "index_of_refraction"}));
  e->node = model;
  e->model = Effect::Model::kDiffuse;
  if (const pugi::xml_node emission = model.child("emission")) {
    if (emission.child("texture")) return doc.NotSupported(emission.child("texture"));
    Color3f c;
    if (emission.child("color")) PTLAB_RETURN_IF_ERROR(doc.Color(emission.child("color"), &c));
    if (!IsBlack(c))
      return doc.NotSupported(emission, "emission in the common profile; use the CGL "
                                        "<emission> extra");
  }
  if (const pugi::xml_node diffuse = model.child("diffuse")) {
    if (diffuse.child("texture"))
      return doc.NotSupported(diffuse.child("texture"), "textured diffuse color");
    if (!diffuse.child("color")) return doc.Error(diffuse, "<diffuse> has no <color>");
    PTLAB_RETURN_IF_ERROR(doc.Color(diffuse.child("color"), &e->reflectance));
    PTLAB_RETURN_IF_ERROR(CheckReflectance(doc, diffuse, e->reflectance, "diffuse color"));
  }
  return Status::Ok();
}

}  // namespace

StatusOr<Effect> ReadEffect(const Document& doc, const pugi::xml_node& effect) {
  PTLAB_RETURN_IF_ERROR(doc.CheckChildren(effect, {"profile_COMMON", "asset"}, true));
  Effect e;
  e.node = effect;
  if (const pugi::xml_node cgl = doc.CglTechnique(effect)) {
    PTLAB_RETURN_IF_ERROR(ReadCgl(doc, cgl, &e));
    return e;
  }
  if (const pugi::xml_node common = effect.child("profile_COMMON"))
    PTLAB_RETURN_IF_ERROR(ReadCommon(doc, common, &e));
  return e;
}

StatusOr<MaterialRef> AddEffectMaterial(const Document& doc, const Effect& e,
                                        MaterialTables* materials) {
  using M = Effect::Model;
  switch (e.model) {
    case M::kDiffuse: return materials->AddDiffuse(e.reflectance);
    case M::kEmission: return materials->AddDiffuse({0, 0, 0});
    case M::kMirror: return materials->AddMirror(e.reflectance);
    case M::kGlass:
    case M::kRefraction: {
      uint8_t flags = kDielectricSchlick | kDielectricScaleRadiance;
      if (e.model == M::kRefraction) flags |= kDielectricRefractOnly;
      if (!IsWhite(e.reflectance) || !IsWhite(e.transmittance))
        return materials->AddTintedDielectric(e.ior, 1.0f, flags, e.reflectance,
                                              e.transmittance);
      return materials->AddDielectric(e.ior, 1.0f, flags);
    }
    case M::kMicrofacet: return materials->AddConductor(e.alpha, e.eta, e.k);
  }
  return doc.Error(e.node, "unknown material model");
}

}  // namespace ptlab::collada
