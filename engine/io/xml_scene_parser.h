// The Nori XML scene parser: one builder per object type, defined by concept in xml_loader.cpp
// (scene, camera, filter, sampler, integrator), xml_shapes.cpp, xml_bsdfs.cpp and
// xml_emitters.cpp.
#pragma once

#include <cstdint>
#include <map>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/xml_properties.h"
#include "engine/scene/scene.h"

namespace ptlab::internal {

class SceneParser {
 public:
  SceneParser(const Locator* at, std::string base_dir) : at_(*at), base_dir_(std::move(base_dir)) {}

  Status ParseRoot(const pugi::xml_document& doc);

  Scene TakeScene() { return std::move(scene_); }

  /// Bytes of the scene's text: with the OBJ files' bytes, what its shapes may expand into
  /// (engine/core/memory_budget.h's ExpansionBudgetBytes).
  void set_input_bytes(uint64_t bytes) { input_bytes_ = bytes; }

  // One <scene> or <bsdf> element of a larger document (xml_loader_internal.h).
  Status ParseSceneElement(const pugi::xml_node& node) { return ParseScene(node); }
  StatusOr<MaterialRef> ParseBsdfElement(const pugi::xml_node& node) { return ParseBsdf(node); }

 private:
  // Splits `node`'s children into properties (parsed into `props`) and child objects, which
  // must be among `allowed`.
  Status Collect(const pugi::xml_node& node, const std::vector<const char*>& allowed,
                 PropertyList* props, std::vector<pugi::xml_node>* children);

  // Objects that take only properties.
  Status CollectLeafObject(const pugi::xml_node& node, PropertyList* props);

  // Enforces "at most one" for `slot`, remembering where the first one was.
  Status TakeSingleton(const pugi::xml_node& node, pugi::xml_node* slot);

  Status ParseScene(const pugi::xml_node& node);

  std::string Resolve(const std::string& filename) const;

  Status ParseShape(const pugi::xml_node& node);

  // Reflectances must lie in [0, 1]; radiance, power, eta and k in [0, kMaxRadiance].
  enum class Range { kUnit, kNonNegative };
  Status CheckColor(PropertyList& props, const char* name, const Color3f& c, Range range);
  Status CheckPositive(PropertyList& props, const char* name, float v);

  StatusOr<MaterialRef> ParseBsdf(const pugi::xml_node& node);

  // Mitsuba emitter types we recognise but do not render yet (a clear "not supported yet").
  static bool IsUnsupportedEmitter(const std::string& type);
  // Emitters that stand on their own, directly inside <scene>.
  static bool IsSceneEmitter(const std::string& type);

  Status ParseAreaEmitter(const pugi::xml_node& node, Color3f* radiance);

  Status ParseSceneEmitter(const pugi::xml_node& node);

  // Mitsuba `constant`: uniform radiance from every direction (color radiance, required), a
  // distant disk of half-angle 180°: sampled uniformly over the sphere, with MIS as envmaps.
  Status ParseConstantEmitter(const pugi::xml_node& node);

  // Nori's `point`: point position and color power (W), both required; power >= 0.
  Status ParsePointEmitter(const pugi::xml_node& node);

  // The rotation of an infinite emitter's toWorld: its upper 3x3 must be orthonormal
  // (translation is ignored: the emitter is infinitely far away).
  Status RotationOf(const pugi::xml_node& node, PropertyList& props, const Transform& to_world,
                    Frame* frame);

  // Mitsuba `envmap`: string filename (EXR/HDR/PFM/PNG lat-long image, required), float scale
  // = 1, transform toWorld (rotation), string sampling = importance|uniform.
  Status ParseEnvironmentEmitter(const pugi::xml_node& node);

  // Nori (ETH) `distantdisk`: color radiance and float thetaA (half-angle in degrees, (0, 180])
  // required, transform toWorld (rotation; the cone is around its local +z).
  Status ParseDistantDiskEmitter(const pugi::xml_node& node);

  Status ParseCamera(const pugi::xml_node& node);

  Status ParseFilter(const pugi::xml_node& node);

  Status ParseSampler(const pugi::xml_node& node);

  Status ParseIntegrator(const pugi::xml_node& node);

  const Locator& at_;
  std::string base_dir_;
  Scene scene_;
  pugi::xml_node camera_, integrator_, filter_;
  std::map<std::string, MeshData> obj_cache_;  // one OBJ used by several meshes loads once
  uint64_t input_bytes_ = 0;  // the XML's and the loaded OBJ files' bytes
};

}  // namespace ptlab::internal
