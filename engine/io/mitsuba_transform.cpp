// Mitsuba <transform> steps: translate, scale, rotate, matrix, lookat.
#include "engine/io/mitsuba_properties.h"

#include <cmath>
#include <vector>

#include "engine/io/lookat_range.h"
#include "engine/io/mitsuba_values.h"
#include "engine/io/text_parsing.h"

namespace ptlab::internal {

using mitsuba_values::CheckAttributes;
using mitsuba_values::Leaf;
using mitsuba_values::Numbers;
using mitsuba_values::XyzVector;
using mitsuba_values::ParseVec3Attribute;

Status ParseMitsubaTransform(const MitsubaNode& node, Transform* result) {
  Transform t;
  for (const MitsubaNode& step : node.children) {
    PTLAB_RETURN_IF_ERROR(Leaf(step));
    Transform s;
    if (step.tag == "translate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value"}, {}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 0.0f, true, &v));
      s = Transform::Translate(v);
    } else if (step.tag == "scale") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value"}, {}));
      Vec3f v;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 1.0f, true, &v));
      if (v.x == 0 || v.y == 0 || v.z == 0)
        return step.Error("singular <scale>; expected non-zero scale factors");
      s = Transform::Scale(v);
    } else if (step.tag == "rotate") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"x", "y", "z", "value", "angle"}, {"angle"}));
      Vec3f axis;
      PTLAB_RETURN_IF_ERROR(XyzVector(step, 0.0f, false, &axis));
      float angle = 0;
      if (!ParseFloat(*step.Attribute("angle"), &angle))
        return step.Error("malformed angle '" + *step.Attribute("angle") +
                          "'; expected degrees as a finite decimal number");
      if (!(Length(axis) > 0)) return step.Error("zero <rotate> axis; expected a non-zero axis");
      s = Transform::Rotate(axis, angle);
    } else if (step.tag == "matrix") {
      PTLAB_RETURN_IF_ERROR(CheckAttributes(step, {"value"}, {"value"}));
      std::vector<double> n;
      PTLAB_RETURN_IF_ERROR(Numbers(step, "value", &n));
      if (n.size() != 16 && n.size() != 9)
        return step.Error("<matrix> has " + std::to_string(n.size()) +
                          " numbers; expected 16 (4x4) or 9 (3x3), row-major");
      const int dim = n.size() == 16 ? 4 : 3;
      Matrix4 m, inv;
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) m.m[i][j] = float(n[size_t(dim * i + j)]);
      if (!Inverse(m, &inv)) return step.Error("singular <matrix>; expected an invertible matrix");
      s = Transform(m, inv);
    } else if (step.tag == "lookat") {
      PTLAB_RETURN_IF_ERROR(
          CheckAttributes(step, {"origin", "target", "up"}, {"origin", "target"}));
      Vec3f origin, target, up{0, 0, 0};
      PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "origin", &origin));
      PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "target", &target));
      if (step.Attribute("up")) PTLAB_RETURN_IF_ERROR(ParseVec3Attribute(step, "up", &up));
      if (const std::string range = LookatRangeError(origin, target, up); !range.empty())
        return step.Error(range);
      if (!(Length(target - origin) > 0))
        return step.Error("degenerate <lookat>: expected target != origin");
      const Vec3f dir = Normalize(target - origin);
      if (!(Length(up) > 0)) {
        // Mitsuba picks some up vector perpendicular to dir.
        up =
            std::fabs(dir.x) > std::fabs(dir.y) ? Vec3f{-dir.z, 0, dir.x} : Vec3f{0, dir.z, -dir.y};
      }
      const Vec3f left_raw = Cross(Normalize(up), dir);
      if (!(Length(left_raw) > 1e-6f))
        return step.Error("degenerate <lookat>: expected 'up' not parallel to target - origin");
      const Vec3f left = Normalize(left_raw), new_up = Normalize(Cross(dir, left));
      Matrix4 m, inv;
      const Vec3f columns[4] = {left, new_up, dir, origin};
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) m.m[r][c] = columns[c][r];
      if (!Inverse(m, &inv)) return step.Error("degenerate <lookat>");
      s = Transform(m, inv);
    } else {
      return step.Error("unknown transform step <" + step.tag +
                        ">; expected translate, scale, rotate, matrix or lookat");
    }
    t = s * t;
    for (const Matrix4* m : {&t.matrix(), &t.inverse_matrix()})
      for (const auto& row : m->m)
        for (const float x : row)
          if (!(std::fabs(x) <= 1e30f))
            return step.Error("<" + step.tag +
                              "> makes the transform (or its inverse) overflow; expected "
                              "matrix entries of magnitude <= 1e30");
  }
  *result = t;
  return Status::Ok();
}

}  // namespace ptlab::internal
