// The properties and child objects of one Mitsuba object (<bsdf>, <shape>, ...), typed, with
// Mitsuba's value syntax (x/y/z attributes, <rgb>, <spectrum>, named <ref>s, transforms).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_spectrum.h"

namespace ptlab::internal {

/// Tags of the Mitsuba object types (a closed set).
bool IsMitsubaObjectTag(const std::string& tag);

/// "<bsdf type="diffuse">" for messages.
std::string DescribeMitsuba(const MitsubaNode& node);

/// "file:line:col: unsupported: bsdf "roughplastic"" (exit status 2 in ptlab), optionally with
/// a note after it.
Status Unsupported(const MitsubaNode& node, const std::string& note = "");

/// Mitsuba's <transform> steps applied in order, each multiplied from the left: translate
/// (x, y, z or value; missing components 0), scale (missing 1; one value = uniform), rotate
/// (angle in degrees and an axis x, y, z or value), matrix (16 or 9 numbers, row-major) and
/// lookat (origin, target, optional up; left = normalize(up × dir), as Nori).
Status ParseMitsubaTransform(const MitsubaNode& node, Transform* result);

/// Every element in the tree that has an `id`, by id; a duplicate id is an error.
Status CollectMitsubaIds(const MitsubaNode& root, std::map<std::string, const MitsubaNode*>* ids);

struct MitsubaProperty {
  enum class Type {
    kBoolean,
    kInteger,
    kFloat,
    kString,
    kPoint,
    kVector,
    kRgb,
    kSpectrum,
    kTransform,
    kObject
  };
  std::string name;  // snake_case (camelCase names of version < 2 scenes are converted)
  Type type = Type::kFloat;
  const MitsubaNode* node = nullptr;    // the property element
  const MitsubaNode* object = nullptr;  // kObject: the nested or referenced object
  bool boolean = false;
  long long integer = 0;
  double number = 0;
  std::string text;
  Vec3f vec;
  Color3f rgb;
  std::vector<double> wavelengths, values;  // kSpectrum: a list (empty: uniform `number`)
  Transform transform;
};

/// One object element: `type` attribute, optional `id` (and `name` when nested as a
/// property), its properties, and its unnamed child objects (refs resolved to the element
/// they name).
class MitsubaObject {
 public:
  /// Reads `node`'s children. `ids` resolves <ref id>; `legacy` converts camelCase property
  /// names (scene version < 2.0) to snake_case, as Mitsuba 3 upgrades old scenes.
  static StatusOr<MitsubaObject> Read(const MitsubaNode& node,
                                      const std::map<std::string, const MitsubaNode*>& ids,
                                      bool legacy);

  const MitsubaNode& node() const { return *node_; }
  const std::string& type() const { return type_; }
  const std::vector<const MitsubaNode*>& children() const { return children_; }
  const std::vector<MitsubaProperty>& properties() const { return props_; }  // normal

  /// Fails on the first property whose name is not in `names`.
  Status Expect(const std::vector<const char*>& names) const;
  /// Properties that are accepted and ignored (they do not change the image ptlab renders).
  bool Has(const char* name) const { return Get(name) != nullptr; }
  const MitsubaProperty* Get(const char* name) const;

  Status Boolean(const char* name, bool* v) const;
  Status Integer(const char* name, int* v) const;
  Status Float(const char* name, float* v) const;  // <float> or <integer>
  Status String(const char* name, std::string* v) const;
  Status Point(const char* name, Vec3f* v) const;   // <point> or <vector>
  Status Vector(const char* name, Vec3f* v) const;  // <vector> or <point>
  Status TransformProperty(const char* name, Transform* v) const;
  /// A constant colour: <rgb>, <float>, <spectrum> (uniform or wavelength:value list, converted
  /// as Mitsuba's rgb variant does for `use`); a texture is reported as unsupported.
  Status Color(const char* name, SpectrumUse use, Color3f* v) const;

  /// Boolean `name` is accepted only at its default `fallback` (other values change the image
  /// in a way ptlab does not render): "unsupported: <tag> \"type\" with name = value".
  Status OnlyDefault(const char* name, bool fallback) const;
  /// Mitsuba's `sampling_weight` of an emitter (> 0): it changes how often emitter sampling
  /// picks the emitter, not the image; ptlab picks uniformly, so it is checked and ignored.
  Status SamplingWeight() const;

  /// An error located at property `name` if present, else at the object.
  Status Error(const char* name, const std::string& message) const;
  Status Require(const char* name) const;

 private:
  Status Find(const char* name, std::initializer_list<MitsubaProperty::Type> types,
              const char* expected, const MitsubaProperty** found) const;

  const MitsubaNode* node_ = nullptr;
  std::string type_;
  std::vector<MitsubaProperty> props_;
  std::vector<const MitsubaNode*> children_;
};

}  // namespace ptlab::internal
