// Mitsuba's `mask` bsdf: an opacity (a float in [0, 1] or a texture) over one nested bsdf.
#include "engine/io/mitsuba_scene_builder.h"

namespace ptlab::internal {

StatusOr<MaterialRef> MitsubaSceneBuilder::MaskBsdf(const MitsubaNode& node,
                                                    const MitsubaObject& obj) {
  PTLAB_RETURN_IF_ERROR(obj.Expect({"opacity"}));
  const std::vector<const MitsubaNode*>& kids = obj.children();
  for (const MitsubaNode* k : kids)
    if (k->tag != "bsdf")
      return k->Error("<" + k->tag + "> is not allowed inside " + DescribeMitsuba(node));
  if (kids.size() != 1) return node.Error("mask expects one nested <bsdf>");
  float opacity = 0.5f;  // Mitsuba's default
  uint32_t texture = kNoTexture;
  const MitsubaProperty* p = obj.Get("opacity");
  if (p != nullptr && p->type == MitsubaProperty::Type::kObject && p->object->tag == "texture") {
    StatusOr<uint32_t> t = ScalarTexture(*p->object);
    if (!t.ok()) return t.status();
    texture = *t;
  } else {
    PTLAB_RETURN_IF_ERROR(obj.Float("opacity", &opacity));
    if (!(opacity >= 0 && opacity <= 1)) return obj.Error("opacity", "opacity must be in [0, 1]");
  }
  StatusOr<MaterialRef> nested = Bsdf(*kids[0]);
  if (!nested.ok()) return nested.status();
  const MaterialRef ref = scene_.materials.AddMask(opacity, *nested, texture);
  bsdfs_[&node] = ref;
  return ref;
}

}  // namespace ptlab::internal
