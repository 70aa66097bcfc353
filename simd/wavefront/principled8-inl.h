// The principled and principledthin tags' batches in the SIMD shading stage (re-included once
// per Highway target). No 8-wide twin yet: the rows go through the scalar oracle
// (engine/bsdf/principled.h, principled_thin.h via ptlab::ShadeBatch), so they are exactly
// the oracle's, textured parameters included.

#if defined(PTLAB_SIMD_PRINCIPLED8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_PRINCIPLED8_INL_H_
#undef PTLAB_SIMD_PRINCIPLED8_INL_H_
#else
#define PTLAB_SIMD_PRINCIPLED8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/scene/material_tables.h"
#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

/// ShadeBatch for tag kPrincipled or kPrincipledThin: the scalar oracle over the n rows (their
/// texture sites from in.texture, two-sided rows already mirrored by the caller).
inline void ShadePrincipledRows(const MaterialTables& m, MaterialTag tag,
                                const uint32_t* material_index, size_t n, const ShadeInputs& in,
                                const ShadeOutputs& out) {
  ptlab::ShadeBatch(m, tag, material_index, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_PRINCIPLED8_INL_H_
