// Vectorized compaction of the traced area-light requests for the shadow queue (plain API).
#pragma once

#include <cstddef>

#include "engine/wavefront/shadow_rows.h"

namespace ptlab::simd {

/// ptlab::CompactShadowRows, eight rows per step (hn::CappedTag<float, 8>): the flags of a
/// vector of rows as a mask, every column compress-stored (CompressBlendedStore: exactly the
/// selected lanes are written), no branch per row; the rows after the last whole vector take
/// the oracle. Oracle: ptlab::CompactShadowRows. Contract: bit-identical outputs and count on
/// every target, out's rows past the count untouched. tests/simd/wavefront/shadow_rows8_test.cpp.
size_t CompactShadowRows(size_t n, const ShadowRowInputs& in, const ShadowRowOutputs& out);

}  // namespace ptlab::simd
