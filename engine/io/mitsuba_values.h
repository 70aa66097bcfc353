// Mitsuba value syntax shared by the property and transform readers: attribute checks, number
// lists, vectors, colours and spectra (engine/io/mitsuba_values.cpp).
#pragma once

#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/vec.h"
#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_properties.h"

namespace ptlab::internal::mitsuba_values {

/// "a, b, c" ("none" when empty), for the accepted names in messages.
std::string Join(const std::vector<const char*>& names);

/// "toWorld" -> "to_world", "intIOR" -> "int_ior": an underscore where an upper-case letter
/// follows a lower-case letter or a digit.
std::string CamelToSnake(const std::string& name);

/// Checks that the node's attributes are among `allowed`, each of `required` present.
Status CheckAttributes(const MitsubaNode& node, const std::vector<const char*>& allowed,
                       const std::vector<const char*>& required);

/// An error unless `node` has no child elements.
Status Leaf(const MitsubaNode& node);

/// The comma/space separated finite numbers of `attribute` (which must be present).
Status Numbers(const MitsubaNode& node, const char* attribute, std::vector<double>* out);

/// A vector given as value="a, b, c" (or one number, repeated when `splat`) or as x, y, z
/// attributes, each defaulting to `fallback`.
Status XyzVector(const MitsubaNode& node, float fallback, bool splat, Vec3f* v);

/// Exactly three numbers in `attribute`.
Status ParseVec3Attribute(const MitsubaNode& node, const char* attribute, Vec3f* v);

/// <rgb>/<color> value (three numbers or one, repeated) or <srgb> (also #rrggbb), as linear RGB.
Status ParseColor(const MitsubaNode& node, bool srgb, Color3f* c);

/// <spectrum value>: one number (p->number) or increasing wavelength:value pairs.
Status ParseSpectrum(const MitsubaNode& node, MitsubaProperty* p);

}  // namespace ptlab::internal::mitsuba_values
