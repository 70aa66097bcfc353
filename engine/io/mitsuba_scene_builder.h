// The Mitsuba scene builder: one function per object kind, defined by concept in
// mitsuba_loader.cpp (scene, sensor, film, sampler, integrator), mitsuba_shapes.cpp,
// mitsuba_bsdfs.cpp and mitsuba_emitters.cpp.
#pragma once

#include <map>
#include <string>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_properties.h"
#include "engine/scene/scene.h"

namespace ptlab::internal {

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
  // matB: twosided and blendbsdf (engine/io/mitsuba_bsdfs.cpp).
  StatusOr<MaterialRef> WrapperBsdf(const MitsubaNode& node, const MitsubaObject& obj);

  Status SceneEmitter(const MitsubaNode& node);
  Status AreaEmitter(const MitsubaNode& node, Color3f* radiance);
  Status Rotation(const MitsubaObject& obj, const Transform& to_world, Frame* frame) const;

  const MitsubaDocument& doc_;
  const LoadOptions& options_;
  bool legacy_ = false;  // version < 2: camelCase property names
  std::map<std::string, const MitsubaNode*> ids_;
  Scene scene_;
  bool have_sensor_ = false, have_integrator_ = false;
  const MitsubaNode* multi_sample_direct_ = nullptr;  // a direct integrator, emitter_samples > 1
  std::map<const MitsubaNode*, MaterialRef> bsdfs_;   // one row per <bsdf> element
  std::map<std::string, MeshData> meshes_;            // one read per mesh file
};

}  // namespace ptlab::internal
