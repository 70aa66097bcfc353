// The emitter stage's traced area-light requests, compacted: the rows of an area_request batch
// whose traced flag is set, in row order, for the shadow queue. The scalar oracle of
// simd/wavefront/shadow_rows8.h; the wavefront's `shadow_rows` slot.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ptlab {

/// An area_request batch's rows (AreaRequestOutputs, and each row's request).
struct ShadowRowInputs {
  const uint8_t *traced = nullptr;
  const uint32_t *request = nullptr;
  const float *o_x = nullptr, *o_y = nullptr, *o_z = nullptr;
  const float *d_x = nullptr, *d_y = nullptr, *d_z = nullptr;
  const float *r = nullptr, *g = nullptr, *b = nullptr;

  /// The rows from row i on.
  ShadowRowInputs From(size_t i) const {
    return {traced + i, request + i, o_x + i, o_y + i, o_z + i, d_x + i,
            d_y + i,    d_z + i,     r + i,   g + i,   b + i};
  }
};

/// The traced rows' request, shadow ray (o, d) and contribution, rows [0, count).
struct ShadowRowOutputs {
  uint32_t *request = nullptr;
  float *o_x = nullptr, *o_y = nullptr, *o_z = nullptr;
  float *d_x = nullptr, *d_y = nullptr, *d_z = nullptr;
  float *r = nullptr, *g = nullptr, *b = nullptr;

  ShadowRowOutputs From(size_t i) const {
    return {request + i, o_x + i, o_y + i, o_z + i, d_x + i, d_y + i, d_z + i, r + i, g + i, b + i};
  }
};

/// Copies the rows c < n with in.traced[c] != 0 to out's rows 0, 1, ... in order; returns how
/// many. out's rows past the count are not written.
size_t CompactShadowRows(size_t n, const ShadowRowInputs &in, const ShadowRowOutputs &out);

}  // namespace ptlab
