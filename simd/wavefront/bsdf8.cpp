// Vectorized shading entry points: per-target instantiation and dispatch of simd/wavefront/bsdf8-inl.h.
#include "simd/targets.h"  // first: the target policy

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/wavefront/bsdf8.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
#include "simd/wavefront/bsdf8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

void BeckmannEvalPdfTarget(const float* alpha, DirectionArrays wo, DirectionArrays wi, size_t n,
                           float* d, float* pdf) {
  BeckmannEvalPdfKernel(alpha, wo, wi, n, d, pdf);
}
void SampleBeckmannReflectionTarget(const float* alpha, DirectionArrays wo, const float* u_x,
                                    const float* u_y, size_t n, DirectionOutArrays wi, float* pdf) {
  SampleBeckmannReflectionKernel(alpha, wo, u_x, u_y, n, wi, pdf);
}
void ConductorFresnelTarget(const float* cos_i, const float* eta, const float* k, size_t n,
                            float* f) {
  ConductorFresnelKernel(cos_i, eta, k, n, f);
}
void DielectricFresnelTarget(const float* cos_i, const float* eta, size_t n, float* f,
                             float* cos_t) {
  DielectricFresnelKernel(cos_i, eta, n, f, cos_t);
}
void ShadeBatchTarget(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index,
                      size_t n, const ShadeInputs& in, const ShadeOutputs& out) {
  ShadeBatchKernel(m, tag, material_index, n, in, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/wavefront/bsdf8.h"

namespace ptlab::simd {

HWY_EXPORT(BeckmannEvalPdfTarget);
HWY_EXPORT(SampleBeckmannReflectionTarget);
HWY_EXPORT(ConductorFresnelTarget);
HWY_EXPORT(DielectricFresnelTarget);
HWY_EXPORT(ShadeBatchTarget);

void BeckmannEvalPdfBatch(const float* alpha, DirectionArrays wo, DirectionArrays wi, size_t n,
                          float* d, float* pdf) {
  HWY_DYNAMIC_DISPATCH(BeckmannEvalPdfTarget)(alpha, wo, wi, n, d, pdf);
}

void SampleBeckmannReflectionBatch(const float* alpha, DirectionArrays wo, const float* u_x,
                                   const float* u_y, size_t n, DirectionOutArrays wi, float* pdf) {
  HWY_DYNAMIC_DISPATCH(SampleBeckmannReflectionTarget)(alpha, wo, u_x, u_y, n, wi, pdf);
}

void ConductorFresnelBatch(const float* cos_i, const float* eta, const float* k, size_t n,
                           float* f) {
  HWY_DYNAMIC_DISPATCH(ConductorFresnelTarget)(cos_i, eta, k, n, f);
}

void DielectricFresnelBatch(const float* cos_i, const float* eta, size_t n, float* f,
                            float* cos_t) {
  HWY_DYNAMIC_DISPATCH(DielectricFresnelTarget)(cos_i, eta, n, f, cos_t);
}

void ShadeBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index, size_t n,
                const ShadeInputs& in, const ShadeOutputs& out) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(ShadeBatchTarget)(m, tag, material_index, n, in, out);
}

void ShadeHits(const MaterialTables& m, const MaterialRef* refs, size_t n, const ShadeInputs& in,
               const ShadeOutputs& out, ShadeScratch* scratch) {
  ShadeHitsWith(
      [](const MaterialTables& mt, MaterialTag tag, const uint32_t* index, size_t count,
         const ShadeInputs& bin,
         const ShadeOutputs& bout) { simd::ShadeBatch(mt, tag, index, count, bin, bout); },
      m, refs, n, in, out, scratch);
}

}  // namespace ptlab::simd
#endif  // HWY_ONCE
