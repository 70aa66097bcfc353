// Textured emitter properties of Mitsuba scenes: a spot's `texture`, a projector's
// `irradiance`, an area emitter's `radiance`, as rows of the scene's TextureTable.
#include "engine/io/mitsuba_scene_builder.h"

namespace ptlab::internal {

StatusOr<uint32_t> MitsubaSceneBuilder::EmitterTexture(const MitsubaProperty& property,
                                                       const std::string& what) {
  const MitsubaNode& node = *property.object;
  if (node.tag != "texture") return Unsupported(node, what);
  StatusOr<uint32_t> row = Texture(node);
  if (!row.ok()) return row.status();
  // Emitters read a texture at a uv of their own, never at a mesh's triangle.
  const TextureKind kind = scene_.textures.Kind(*row);
  if (kind != TextureKind::kBitmap && kind != TextureKind::kCheckerboard)
    return Unsupported(node, what + " (a mesh attribute; expected bitmap or checkerboard)");
  return *row;
}

}  // namespace ptlab::internal
