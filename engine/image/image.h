// A linear RGB float image, the exchange type of the film, imgdiff and the environment map.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"

namespace ptlab {

/// width x height pixels, RGB interleaved, row 0 at the top.
struct Image {
  int width = 0, height = 0;
  AlignedVector<float> rgb;  // huge pages from 2 MiB on (engine/core/aligned.h)

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0.0f) {}
  Color3f At(int x, int y) const {
    const float* p = &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }
  void Set(int x, int y, const Color3f& c) {
    float* p = &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
};

}  // namespace ptlab
