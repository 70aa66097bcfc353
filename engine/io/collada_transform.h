// COLLADA transforms: the <asset>'s unit and up axis, a <node>'s transform elements, and the
// affine helpers the scene assembly (collada_loader.cpp) applies them with.
#pragma once

#include <pugixml.hpp>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/io/collada_document.h"

namespace ptlab::collada {

/// m applied to the point p (the upper 3x4 of m).
Vec3f ApplyPoint(const Matrix4& m, const Vec3f& p);
/// m applied to the vector v (its translation ignored).
Vec3f ApplyVector(const Matrix4& m, const Vec3f& v);

/// The affine matrix with columns x, y, z and translation p.
Matrix4 Columns(const Vec3f& x, const Vec3f& y, const Vec3f& z, const Vec3f& p);

/// <unit meter> and <up_axis> of an <asset> (which may be null): *global = rotate(up axis to
/// +y) · scale(meter).
Status ReadAssetFrame(const Document& doc, const pugi::xml_node& asset, Matrix4* global);

/// A node's own transform: its matrix/translate/rotate/scale children in document order. A
/// camera-only node's short <matrix> (CBgems.dae) is read as CS184 does, with a warning.
Status ReadNodeTransform(const Document& doc, const pugi::xml_node& node,
                         std::vector<std::string>* warnings, Matrix4* local);

}  // namespace ptlab::collada
