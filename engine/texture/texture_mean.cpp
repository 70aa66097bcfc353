// TextureMean (texture_mean.h).
#include "engine/texture/texture_mean.h"

namespace ptlab {

Color3f TextureMean(const TextureTable& t, uint32_t id) {
  size_t count = 0;
  switch (t.Kind(id)) {
    case TextureKind::kBitmap: count = size_t(t.width[id]) * size_t(t.height[id]); break;
    case TextureKind::kCheckerboard: count = 2; break;
    case TextureKind::kFaceAttribute:
    case TextureKind::kVertexAttribute: return {};
  }
  if (count == 0) return {};
  // Summed in double: a 4k image's 16 M texels would lose float precision.
  double r = 0, g = 0, b = 0;
  const float* data = t.data.data() + t.offset[id];
  for (size_t k = 0; k < count; ++k)
    r += double(data[3 * k]), g += double(data[3 * k + 1]), b += double(data[3 * k + 2]);
  const double inv = 1.0 / double(count);
  return {float(r * inv), float(g * inv), float(b * inv)};
}

}  // namespace ptlab
