// normal: Mitsuba's `normalmap` and `bumpmap`: the nested bsdf's row, perturbed by a texture
// (engine/scene/shading_perturbation.h, engine/bsdf/perturbed_frame.h).
#include <cmath>

#include "engine/io/mitsuba_scene_builder.h"

namespace ptlab::internal {

StatusOr<MaterialRef> MitsubaSceneBuilder::PerturbedBsdf(const MitsubaNode& node,
                                                         const MitsubaObject& obj) {
  const bool normal = obj.type() == "normalmap";
  const std::vector<const MitsubaNode*>& kids = obj.children();
  const MitsubaNode* texture_node = nullptr;
  float scale = 1.0f;
  if (normal) {
    PTLAB_RETURN_IF_ERROR(obj.Expect({"normalmap", "flip_invalid_normals", "use_shadowing_function"}));
    PTLAB_RETURN_IF_ERROR(obj.Require("normalmap"));
    const MitsubaProperty* p = obj.Get("normalmap");
    if (p->type != MitsubaProperty::Type::kObject || p->object->tag != "texture")
      return obj.Error("normalmap", "normalmap must be a <texture>");
    texture_node = p->object;
  } else {
    // Mitsuba's bumpmap takes its one texture under any name.
    std::vector<const char*> names = {"scale", "flip_invalid_normals", "use_shadowing_function"};
    for (const MitsubaProperty& p : obj.properties()) {
      if (p.type != MitsubaProperty::Type::kObject || p.object->tag != "texture") continue;
      if (texture_node != nullptr)
        return obj.Error(p.name.c_str(), "bumpmap expects one <texture>");
      texture_node = p.object;
      names.push_back(p.name.c_str());
    }
    for (const MitsubaNode* k : kids) {
      if (k->tag != "texture") continue;
      if (texture_node != nullptr) return k->Error("bumpmap expects one <texture>");
      texture_node = k;
    }
    PTLAB_RETURN_IF_ERROR(obj.Expect(names));
    if (texture_node == nullptr) return node.Error("bumpmap expects one nested <texture>");
    PTLAB_RETURN_IF_ERROR(obj.Float("scale", &scale));
    if (!std::isfinite(scale)) return obj.Error("scale", "scale must be finite");
  }
  // The options at Mitsuba's defaults only (others change the image).
  PTLAB_RETURN_IF_ERROR(obj.OnlyDefault("flip_invalid_normals", true));
  PTLAB_RETURN_IF_ERROR(obj.OnlyDefault("use_shadowing_function", true));
  const MitsubaNode* nested = nullptr;
  for (const MitsubaNode* k : kids) {
    if (k->tag == "texture") continue;
    if (k->tag != "bsdf")
      return k->Error("<" + k->tag + "> is not allowed inside " + DescribeMitsuba(node));
    if (nested != nullptr) return k->Error(obj.type() + " expects one nested <bsdf>");
    nested = k;
  }
  if (nested == nullptr) return node.Error(obj.type() + " expects one nested <bsdf>");
  // The perturbation belongs to the nested row (as twosided's flag does): a row that other
  // shapes may use unperturbed cannot carry it.
  if (nested->Attribute("id") != nullptr || bsdfs_.count(nested) != 0)
    return Unsupported(node, "a nested bsdf that is referenced elsewhere (give " + obj.type() +
                                 " its own nested bsdf)");
  StatusOr<uint32_t> texture = Texture(*texture_node);
  if (!texture.ok()) return texture.status();
  StatusOr<MaterialRef> child = Bsdf(*nested);
  if (!child.ok()) return child.status();
  const PerturbationKind kind = normal ? PerturbationKind::kNormalMap : PerturbationKind::kBumpMap;
  ShadingPerturbations& perturbation = scene_.materials.perturbation;
  if (IsUvAlignedFrame(perturbation.Of(*child)))
    perturbation.Replace(*child, kind, *texture, scale);  // the map brings the frame itself
  else if (!perturbation.Add(*child, kind, *texture, scale))
    return Unsupported(node, "a normal or bump map around another one");
  bsdfs_[&node] = *child;
  return *child;
}

void MitsubaSceneBuilder::UvAlignedFrame(MaterialRef ref) {
  if (uv_frame_texture_ == kNoTexture) {
    TextureTable& t = scene_.textures;
    uv_frame_texture_ = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    float* c = &t.data[t.offset[uv_frame_texture_]];
    c[0] = c[3] = 0.5f, c[1] = c[4] = 0.5f, c[2] = c[5] = 1.0f;  // normal 2c − 1 = (0, 0, 1)
  }
  scene_.materials.perturbation.Add(ref, PerturbationKind::kNormalMap, uv_frame_texture_, 1.0f);
}

}  // namespace ptlab::internal
