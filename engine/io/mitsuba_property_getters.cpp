// Typed getters of a Mitsuba object's properties (Boolean, Float, Color, ...), their errors.
#include "engine/io/mitsuba_properties.h"

#include <algorithm>

#include "engine/io/mitsuba_values.h"

namespace ptlab::internal {

using mitsuba_values::Join;

namespace {

const char* TypeTag(MitsubaProperty::Type t) {
  using T = MitsubaProperty::Type;
  switch (t) {
    case T::kBoolean:
      return "boolean";
    case T::kInteger:
      return "integer";
    case T::kFloat:
      return "float";
    case T::kString:
      return "string";
    case T::kPoint:
      return "point";
    case T::kVector:
      return "vector";
    case T::kRgb:
      return "rgb";
    case T::kSpectrum:
      return "spectrum";
    case T::kTransform:
      return "transform";
    case T::kObject:
      return "texture (or other object)";
  }
  return "?";
}

}  // namespace

Status MitsubaObject::Expect(const std::vector<const char*>& names) const {
  for (const MitsubaProperty& p : props_)
    if (std::none_of(names.begin(), names.end(), [&](const char* n) { return p.name == n; }))
      return p.node->Error(
          "unknown property '" + p.name + "' for " + DescribeMitsuba(*node_) + "; expected " +
          (names.empty() ? std::string("no properties") : "one of: " + Join(names)));
  return Status::Ok();
}

const MitsubaProperty* MitsubaObject::Get(const char* name) const {
  for (const MitsubaProperty& p : props_)
    if (p.name == name) return &p;
  return nullptr;
}

Status MitsubaObject::Find(const char* name, std::initializer_list<MitsubaProperty::Type> types,
                           const char* expected, const MitsubaProperty** found) const {
  *found = Get(name);
  if (*found && std::find(types.begin(), types.end(), (*found)->type) == types.end()) {
    if ((*found)->type == MitsubaProperty::Type::kObject)
      return Unsupported(*(*found)->object,
                         std::string("as property '") + name + "' of " + DescribeMitsuba(*node_));
    return (*found)->node->Error(std::string("property '") + name + "' of " +
                                 DescribeMitsuba(*node_) + " has the wrong type <" +
                                 TypeTag((*found)->type) + ">; expected " + expected);
  }
  return Status::Ok();
}

Status MitsubaObject::Boolean(const char* name, bool* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kBoolean}, "<boolean>", &p));
  if (p) *v = p->boolean;
  return Status::Ok();
}

Status MitsubaObject::Integer(const char* name, int* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kInteger}, "<integer>", &p));
  if (p) *v = int(p->integer);
  return Status::Ok();
}

Status MitsubaObject::Float(const char* name, float* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kFloat, MitsubaProperty::Type::kInteger}, "<float>", &p));
  if (p) *v = p->type == MitsubaProperty::Type::kFloat ? float(p->number) : float(p->integer);
  return Status::Ok();
}

Status MitsubaObject::String(const char* name, std::string* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kString}, "<string>", &p));
  if (p) *v = p->text;
  return Status::Ok();
}

Status MitsubaObject::Point(const char* name, Vec3f* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kPoint, MitsubaProperty::Type::kVector}, "<point>", &p));
  if (p) *v = p->vec;
  return Status::Ok();
}

Status MitsubaObject::Vector(const char* name, Vec3f* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(
      Find(name, {MitsubaProperty::Type::kVector, MitsubaProperty::Type::kPoint}, "<vector>", &p));
  if (p) *v = p->vec;
  return Status::Ok();
}

Status MitsubaObject::TransformProperty(const char* name, Transform* v) const {
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {MitsubaProperty::Type::kTransform}, "<transform>", &p));
  if (p) *v = p->transform;
  return Status::Ok();
}

Status MitsubaObject::Color(const char* name, SpectrumUse use, Color3f* v) const {
  using T = MitsubaProperty::Type;
  const MitsubaProperty* p;
  PTLAB_RETURN_IF_ERROR(Find(name, {T::kRgb, T::kSpectrum, T::kFloat, T::kInteger},
                             "<rgb>, <spectrum> or <float>", &p));
  if (!p) return Status::Ok();
  switch (p->type) {
    case T::kRgb:
      *v = p->rgb;
      break;
    case T::kFloat:
    case T::kInteger: {
      const float x = p->type == T::kFloat ? float(p->number) : float(p->integer);
      *v = {x, x, x};
      break;
    }
    case T::kSpectrum:
      if (!p->wavelengths.empty()) {
        *v = SpectrumToRgb(p->wavelengths, p->values, use);
      } else if (use == SpectrumUse::kEmission) {
        // Mitsuba's rgb variants turn a uniform emission spectrum into the sRGB of an
        // equal-energy spectrum: value · xyz_to_srgb(1, 1, 1) (not grey: sRGB's white is D65).
        const float x = float(p->number);
        *v = {x * (3.240479f - 1.537150f - 0.498535f), x * (-0.969256f + 1.875991f + 0.041556f),
              x * (0.055648f - 0.204043f + 1.057311f)};
      } else {
        const float x = float(p->number);
        *v = {x, x, x};
      }
      break;
    default:
      break;
  }
  return Status::Ok();
}

Status MitsubaObject::OnlyDefault(const char* name, bool fallback) const {
  bool value = fallback;
  PTLAB_RETURN_IF_ERROR(Boolean(name, &value));
  if (value == fallback) return Status::Ok();
  return Error(name, "unsupported: " + node_->tag + " \"" + type_ + "\" with " + name + " = " +
                         (value ? "true" : "false"));
}

Status MitsubaObject::SamplingWeight() const {
  float weight = 1;
  PTLAB_RETURN_IF_ERROR(Float("sampling_weight", &weight));
  if (!(weight > 0)) return Error("sampling_weight", "sampling_weight must be > 0");
  return Status::Ok();
}

Status MitsubaObject::Error(const char* name, const std::string& message) const {
  const MitsubaProperty* p = Get(name);
  return (p ? *p->node : *node_).Error(message);
}

Status MitsubaObject::Require(const char* name) const {
  if (Has(name)) return Status::Ok();
  return node_->Error(DescribeMitsuba(*node_) + " is missing the required property '" + name + "'");
}

}  // namespace ptlab::internal
