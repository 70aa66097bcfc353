// The Mitsuba scene builder: one function per object kind, defined by concept in
// mitsuba_loader.cpp (scene, sampler, integrator), mitsuba_sensor.cpp (sensor, film, filter),
// mitsuba_shapes.cpp, mitsuba_bsdfs.cpp and mitsuba_emitters.cpp.
#pragma once

#include <map>
#include <utility>
#include <string>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_properties.h"
#include "engine/scene/scene.h"

namespace ptlab::internal {

/// Emission colour `name` of `obj` within [0, 1e20] per component; an error at it otherwise.
Status CheckEmission(const MitsubaObject& obj, const char* name, const Color3f& c);

/// Mitsuba's parse_fov: `fov` along `fov_axis` (x, y, diagonal, smaller, larger; default x) or
/// `focal_length` (35 mm film diagonal; default 50mm) of a sensor or projector whose image has
/// width / height = aspect, as the horizontal field of view in degrees, in (0, 180).
Status MitsubaHorizontalFov(const MitsubaObject& obj, double aspect, float* horizontal_fov);

class MitsubaSceneBuilder {
 public:
  MitsubaSceneBuilder(const MitsubaDocument* doc, const LoadOptions& options)
      : doc_(*doc), options_(options) {}

  Status Build();
  Scene TakeScene() { return std::move(scene_); }

 private:
  StatusOr<MitsubaObject> Read(const MitsubaNode& node) const {
    return MitsubaObject::Read(node, ids_, legacy_);
  }
  // The file `filename` resolved through the search paths; an error located at `node` if it
  // does not exist.
  StatusOr<std::string> Resolve(const MitsubaObject& obj, const char* property,
                                const std::string& filename) const;

  Status SceneChild(const MitsubaNode& node);
  Status Sensor(const MitsubaNode& node);
  Status Film(const MitsubaNode& node, const MitsubaNode** filter);
  Status Filter(const MitsubaNode& node);
  Status Sampler(const MitsubaNode& node);
  Status Integrator(const MitsubaNode& node);

  Status Shape(const MitsubaNode& node);
  // The object-space mesh of a mesh-file shape (obj; ply and serialized when their readers are
  // wired in).
  Status MeshFile(const MitsubaObject& obj, MeshData* mesh, std::string* name);

  StatusOr<MaterialRef> Bsdf(const MitsubaNode& node);
  // A <texture> as a row of scene_.textures (mitsuba_textures.cpp), read once per element.
  StatusOr<uint32_t> Texture(const MitsubaNode& node);
  // The same texture read as a scalar parameter (Mitsuba's eval_1): its row, or for a
  // checkerboard a copy with the two colours swapped (see mitsuba_textures.cpp).
  StatusOr<uint32_t> ScalarTexture(const MitsubaNode& node);
  // Fills the mesh_attribute texture that `material` reads (if any) from `mesh`'s attribute,
  // the mesh's triangles being scene rows first_triangle on.
  Status BindMeshAttribute(const MitsubaNode& shape, MaterialRef material, const MeshData& mesh,
                           uint32_t first_triangle);
  // mask: one mesh_attribute texture of BindMeshAttribute (others are left alone).
  Status BindMeshAttributeTexture(const MitsubaNode& shape, uint32_t id, const MeshData& mesh,
                                  uint32_t first_triangle);

  // Instancing (mitsuba_instances.cpp): a <shape> of the scene, dispatched to ShapeGroup,
  // Instance or Shape; a shape group built once (its InstanceTable group); an instance.
  Status SceneShape(const MitsubaNode& node);
  StatusOr<uint32_t> ShapeGroup(const MitsubaNode& node);
  Status Instance(const MitsubaNode& node);
  // matB: twosided and blendbsdf (engine/io/mitsuba_bsdfs.cpp).
  StatusOr<MaterialRef> WrapperBsdf(const MitsubaNode& node, const MitsubaObject& obj);
  // normal: `normalmap` and `bumpmap` (engine/io/mitsuba_perturbed_bsdfs.cpp).
  StatusOr<MaterialRef> PerturbedBsdf(const MitsubaNode& node, const MitsubaObject& obj);
  // Gives an anisotropic row Mitsuba's shading frame, whose tangent follows ∂p/∂u: an identity
  // normal map (a constant texture of normal (0, 0, 1)); a later normalmap or bumpmap around
  // the row replaces it (engine/io/mitsuba_perturbed_bsdfs.cpp).
  void UvAlignedFrame(MaterialRef ref);
  // True when `id` is the perturbation UvAlignedFrame added.
  bool IsUvAlignedFrame(int64_t id) const {
    return id >= 0 && uv_frame_texture_ != kNoTexture &&
           scene_.materials.perturbation.texture[size_t(id)] == uv_frame_texture_;
  }
  // principled: principled and principledthin (engine/io/mitsuba_principled.cpp).
  StatusOr<MaterialRef> PrincipledBsdf(const MitsubaNode& node, const MitsubaObject& obj);
  // mask: Mitsuba's `mask` (engine/io/mitsuba_mask_bsdf.cpp).
  StatusOr<MaterialRef> MaskBsdf(const MitsubaNode& node, const MitsubaObject& obj);

  Status SceneEmitter(const MitsubaNode& node);
  // An area emitter's radiance: constant, or a texture row (*texture; else kNoTexture).
  Status AreaEmitter(const MitsubaNode& node, Color3f* radiance, uint32_t* texture);
  Status Rotation(const MitsubaObject& obj, const Transform& to_world, Frame* frame) const;
  // mitsuba_delta_emitters.cpp: Mitsuba's spot and projector.
  Status SpotEmitter(const MitsubaObject& obj);
  Status ProjectorEmitter(const MitsubaObject& obj);
  // mitsuba_emitter_textures.cpp: the texture row of an emitter's textured property (a
  // bitmap or checkerboard <texture>); `what` names the use in the unsupported message.
  StatusOr<uint32_t> EmitterTexture(const MitsubaProperty& property, const std::string& what);

  const MitsubaDocument& doc_;
  const LoadOptions& options_;
  bool legacy_ = false;  // version < 2: camelCase property names
  std::map<std::string, const MitsubaNode*> ids_;
  Scene scene_;
  bool have_sensor_ = false, have_integrator_ = false;
  const MitsubaNode* multi_sample_direct_ = nullptr;  // a direct integrator, emitter_samples > 1
  const MitsubaNode* hide_emitters_ = nullptr;        // an integrator with hide_emitters
  std::map<const MitsubaNode*, MaterialRef> bsdfs_;   // one row per <bsdf> element
  uint32_t uv_frame_texture_ = kNoTexture;             // UvAlignedFrame's constant normal
  std::map<std::string, MeshData> meshes_;            // one read per mesh file
  std::map<const MitsubaNode*, uint32_t> textures_;
  std::map<const MitsubaNode*, uint32_t> scalar_textures_;  // ScalarTexture   // one row per <texture> element
  // mesh_attribute rows: the attribute's name and the <texture> element.
  std::map<uint32_t, std::pair<std::string, const MitsubaNode*>> attribute_names_;
  // Shape groups by element: their group row, group-space spheres and triangle bounds.
  struct GroupShapes {
    uint32_t group = 0;
    SphereTable spheres;
    SdfGridTable sdf_grids;  // in group space; each instance places its own rows
    Vec3f lo, hi;
  };
  std::map<const MitsubaNode*, GroupShapes> shape_groups_;
  /// <shape type="sdfgrid"> (engine/io/mitsuba_sdf_grid.cpp): one row of scene_.sdf_grids.
  Status SdfGridShape(const MitsubaObject& obj, const Transform& to_world, MaterialRef material);
};

}  // namespace ptlab::internal
