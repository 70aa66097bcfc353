// COLLADA transforms (collada_transform.h).
#include "engine/io/collada_transform.h"

#include <cmath>
#include <string_view>

#include "engine/io/text_parsing.h"

namespace ptlab::collada {

Vec3f ApplyPoint(const Matrix4& m, const Vec3f& p) {
  return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
          m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
          m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}

Vec3f ApplyVector(const Matrix4& m, const Vec3f& v) {
  return ApplyPoint(m, v) - ApplyPoint(m, {0, 0, 0});
}

Matrix4 Columns(const Vec3f& x, const Vec3f& y, const Vec3f& z, const Vec3f& p) {
  Matrix4 m;
  const Vec3f c[4] = {x, y, z, p};
  for (int j = 0; j < 4; ++j) m.m[0][j] = c[j].x, m.m[1][j] = c[j].y, m.m[2][j] = c[j].z;
  return m;
}

Status ReadAssetFrame(const Document& doc, const pugi::xml_node& asset, Matrix4* global) {
  *global = Matrix4::Identity();
  if (!asset) return Status::Ok();
  float meter = 1;
  if (const pugi::xml_node unit = asset.child("unit")) {
    if (const pugi::xml_attribute m = unit.attribute("meter")) {
      if (!ParseFloat(m.value(), &meter) || !(meter > 0))
        return doc.Error(unit, std::string("<unit> meter=\"") + std::string(m.value()) +
                                    "\" is not a number > 0");
    }
  }
  Matrix4 up;
  if (const pugi::xml_node axis = asset.child("up_axis")) {
    const std::string_view text = axis.child_value();
    // COLLADA 1.4.1 §5 <up_axis>: X_UP has right = -y, up = +x; Z_UP has up = +z, in = -y.
    if (text == "X_UP") {
      up.m[0][0] = 0, up.m[0][1] = -1, up.m[1][0] = 1, up.m[1][1] = 0;
    } else if (text == "Z_UP") {
      up.m[1][1] = 0, up.m[1][2] = 1, up.m[2][1] = -1, up.m[2][2] = 0;
    } else if (text != "Y_UP") {
      return doc.Error(axis, std::string("<up_axis> \"") + std::string(text) +
                                  "\"; expected X_UP, Y_UP or Z_UP");
    }
  }
  *global = up * Transform::Scale({meter, meter, meter}).matrix();
  return Status::Ok();
}

Status ReadNodeTransform(const Document& doc, const pugi::xml_node& node,
                         std::vector<std::string>* warnings, Matrix4* local) {
  *local = Matrix4::Identity();
  // A node holding only a camera instance (its transform reaches nothing else).
  bool camera_only = bool(node.child("instance_camera"));
  for (const char* other : {"node", "instance_node", "instance_geometry", "instance_light"})
    camera_only = camera_only && !node.child(other);
  for (const pugi::xml_node child : node.children()) {
    if (child.type() != pugi::node_element) continue;
    const std::string_view name = child.name();
    Matrix4 t;
    if (name == "matrix") {
      std::vector<float> v;
      PTLAB_RETURN_IF_ERROR(doc.Floats(child, &v));
      if (v.size() < 16 && v.size() >= 12 && camera_only) {
        // CBgems.dae's camera matrix lacks a number. CS184 reads the missing ones as 0 and
        // keeps only the camera's view direction (the upper 3x3), so ptlab does the same.
        warnings->push_back(
            doc.at.At(child) + ": <matrix> holds " + std::to_string(v.size()) +
            " numbers; expected 16. Read as CS184 does: the missing ones are 0 and only the "
            "camera's view direction is used");
        v.resize(16, 0.0f);
        v[15] = 1.0f;
        v[12] = v[13] = v[14] = 0.0f;
      }
      if (v.size() != 16)
        return doc.Error(child, "<matrix> holds " + std::to_string(v.size()) +
                                     " numbers; expected 16");
      for (int i = 0; i < 16; ++i) t.m[i / 4][i % 4] = v[i];
      if (t.m[3][0] != 0 || t.m[3][1] != 0 || t.m[3][2] != 0 || t.m[3][3] != 1)
        return doc.NotSupported(child, "a projective matrix; expected the last row 0 0 0 1");
    } else if (name == "translate") {
      float v[3];
      PTLAB_RETURN_IF_ERROR(doc.FixedFloats(child, 3, v));
      t = Transform::Translate({v[0], v[1], v[2]}).matrix();
    } else if (name == "rotate") {
      float v[4];
      PTLAB_RETURN_IF_ERROR(doc.FixedFloats(child, 4, v));
      if (v[0] == 0 && v[1] == 0 && v[2] == 0)
        return doc.Error(child, "<rotate> has a zero axis");
      t = Transform::Rotate({v[0], v[1], v[2]}, v[3]).matrix();
    } else if (name == "scale") {
      float v[3];
      PTLAB_RETURN_IF_ERROR(doc.FixedFloats(child, 3, v));
      // The matrix itself, not Transform::Scale (which inverts it): a zero factor is legal
      // here and an error only where a singular transform matters (meshes, light axes).
      t.m[0][0] = v[0], t.m[1][1] = v[1], t.m[2][2] = v[2];
    } else {
      continue;
    }
    *local = *local * t;
  }
  return Status::Ok();
}

}  // namespace ptlab::collada
