// CS184 camera settings files: the numbers of Camera::dump_settings onto a CameraDesc.
#include "engine/io/cs184_camera_file.h"

#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include "engine/core/input_file.h"
#include "engine/core/transform.h"
#include "engine/core/parse_number.h"
#include "engine/io/text_parsing.h"
#include "engine/scene/scene_limits.h"

namespace ptlab {
namespace {

constexpr size_t kNumbers = 28;          // without the lens line
constexpr size_t kNumbersWithLens = 30;  // with focalDistance lensRadius

struct Number {
  float value;
  int line;
};

std::string At(const std::string& name, int line) {
  return name + ":" + std::to_string(line) + ": ";
}

}  // namespace

Status ApplyCs184CameraSettings(const std::string& text, const std::string& display_name,
                                CameraDesc* camera) {
  std::vector<Number> v;
  int line = 1;
  for (size_t i = 0; i < text.size();) {
    if (text[i] == '\n') ++line;
    if (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n') {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < text.size() && text[end] != ' ' && text[end] != '\t' && text[end] != '\r' &&
           text[end] != '\n')
      ++end;
    const std::string_view token(text.data() + i, end - i);
    float value = 0;
    const std::string number = ParseNumber<float>(token, -kMaxWorldCoordinate, kMaxWorldCoordinate, &value);
    if (!number.empty())
      return Status::Error(At(display_name, line) + number +
                           " (CS184 camera settings are finite numbers)");
    if (v.size() == kNumbersWithLens)
      return Status::Error(At(display_name, line) + "more than " +
                           std::to_string(kNumbersWithLens) + " numbers; expected " +
                           std::to_string(kNumbers) + " or " + std::to_string(kNumbersWithLens));
    v.push_back({value, line});
    i = end;
  }
  if (v.size() != kNumbers && v.size() != kNumbersWithLens)
    return Status::Error(At(display_name, v.empty() ? 1 : v.back().line) + "the file holds " +
                         std::to_string(v.size()) + " numbers; expected " +
                         std::to_string(kNumbers) + " or " + std::to_string(kNumbersWithLens) +
                         " (hFov vFov ar nClip fClip, pos, targetPos, phi theta r minR maxR, c2w "
                         "3x3, screenW screenH screenDist[, focalDistance lensRadius])");
  const auto error = [&](size_t index, const std::string& what) {
    return Status::Error(At(display_name, v[index].line) + what);
  };
  for (size_t i : {size_t{0}, size_t{1}})
    if (!(v[i].value > 0 && v[i].value < 180))
      return error(i, std::string(i == 0 ? "hFov" : "vFov") + " " + std::to_string(v[i].value) +
                          " is out of range; expected degrees in (0, 180)");
  if (!(v[2].value >= 1e-3f && v[2].value <= 1e3f))
    return error(2, "ar " + FormatLimit(v[2].value) + " is out of range [1e-3, 1e3]");
  if (!(v[3].value > 0 && v[4].value > v[3].value))
    return error(3, "expected clip planes 0 < nClip < fClip");
  const Vec3f pos{v[5].value, v[6].value, v[7].value};
  // c2w(i / 3, i % 3) for i < 9: row-major; its columns are the camera's right, up and back
  // axes in world space (CS184's camera looks down its -z).
  const auto column = [&](int c) {
    return Vec3f{v[16 + c].value, v[19 + c].value, v[22 + c].value};
  };
  const Vec3f up_hint = column(1), back = column(2);
  if (!(Length(back) > 0))
    return error(16, "c2w has a zero third column; expected the camera's back axis");
  const Vec3f forward = -Normalize(back);
  const Vec3f left = Cross(up_hint, forward);
  if (!(Length(left) > 1e-6f * Length(up_hint)))
    return error(16, "c2w's up axis (second column) is zero or along the view direction");
  // ptlab's camera space looks along +z with +y up and +x to the image's left.
  const Vec3f l = Normalize(left), u = Cross(forward, l);
  Matrix4 m;
  const Vec3f cols[4] = {l, u, forward, pos};
  for (int j = 0; j < 4; ++j) m.m[0][j] = cols[j].x, m.m[1][j] = cols[j].y, m.m[2][j] = cols[j].z;
  Matrix4 inv;
  if (!Inverse(m, &inv)) return error(16, "the camera frame is singular");
  const float focal = v.size() == kNumbersWithLens ? v[28].value : camera->focus_distance;
  const float lens = v.size() == kNumbersWithLens ? v[29].value : camera->aperture_radius;
  if (!(focal > 0)) return error(kNumbers, "focalDistance must be > 0");
  if (!(lens >= 0)) return error(kNumbers + 1, "lensRadius must be >= 0");
  camera->camera_to_world = Transform(m, inv);
  camera->near_clip = v[3].value;
  camera->far_clip = v[4].value;
  // The vertical field of view; the horizontal one follows the film (ptlab stores that).
  const double tan_v = std::tan(double(v[1].value) * std::numbers::pi / 360.0);
  const double aspect = double(camera->width) / double(camera->height);
  camera->fov_deg = float(std::atan(tan_v * aspect) * 360.0 / std::numbers::pi);
  camera->keep_vertical_fov = true;
  camera->focus_distance = focal;
  camera->aperture_radius = lens;
  return Status::Ok();
}

Status ReadCs184CameraFile(const std::string& path, CameraDesc* camera) {
  std::string text;
  PTLAB_RETURN_IF_ERROR(ReadInputFile(path, "camera settings", &text));
  return ApplyCs184CameraSettings(text, path, camera);
}

}  // namespace ptlab
