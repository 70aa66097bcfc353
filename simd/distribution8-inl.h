// Per-target helper (re-included once per Highway target): inverting a piecewise-constant CDF
// (engine/sampling/distribution2d.h) for eight numbers per vector, as SamplePiecewiseConstant1D
// does for one. Used by simd/wavefront/environment8.

#if defined(PTLAB_SIMD_DISTRIBUTION8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_DISTRIBUTION8_INL_H_
#undef PTLAB_SIMD_DISTRIBUTION8_INL_H_
#else
#define PTLAB_SIMD_DISTRIBUTION8_INL_H_
#endif

#include <cstdint>

#include "engine/core/vec.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// PiecewiseConstantBin for n bins: ⌊x·n⌋ clamped to [0, n-1].
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> PiecewiseConstantBin8(D d, V x, float n) {
  const hn::RebindToSigned<D> di;
  const auto bin = hn::ConvertTo(di, hn::Mul(x, hn::Set(d, n)));
  return hn::Min(hn::Max(bin, hn::Zero(di)), hn::Set(di, int32_t(n) - 1));
}

/// SamplePiecewiseConstant1D over the CDF rows at cdf + row (per lane; row = 0 for a single
/// CDF) of n bins, which must be non-empty, with their guide tables at guide + row
/// (BuildPiecewiseConstantGuide; null: none): *x, *bin and *pdf per lane, the scalar code's float
/// operations in its order (bit-identical to it). The bin is searched between the guide's
/// entries one bucket either side of u's (which absorbs the rounding of u·n and of the guide's
/// edges), by a branchless bisection that runs while some lane's interval holds more than one
/// candidate: usually no step or one, where a search of the whole CDF takes ⌈log2(n + 1)⌉
/// dependent gathers. The rounding repair of x is a masked loop that rarely runs.
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE void SamplePiecewiseConstant8(D d, const float* cdf, const uint32_t* guide, VI row,
                                         int n, V u, V* x, VI* bin, V* pdf) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), below_one = hn::Set(d, kOneMinusEpsilon);
  const VI one_i = hn::Set(di, 1), last = hn::Set(di, n - 1);
  const int32_t* guide_i = reinterpret_cast<const int32_t*>(guide);
  // u clamped to [0, 1): also maps NaN to 0.
  u = hn::IfThenElse(hn::Ge(u, zero), hn::Min(u, below_one), zero);
  // The answer (the last i with cdf[row + i] <= u) lies in [i, i + len): with a guide,
  // guide[b - 1] is the bin of a number <= u and guide[b + 2] (clamped: bins end at n - 1) that
  // of one >= u; without one, the whole CDF (cdf[0] = 0 <= u).
  VI i = hn::Zero(di), len = hn::Set(di, n + 1);
  if (guide != nullptr) {
    const VI b = PiecewiseConstantBin8(d, u, float(n));
    const VI below = hn::Add(row, hn::Max(hn::Sub(b, one_i), hn::Zero(di)));
    const VI above = hn::Add(row, hn::Min(hn::Add(b, hn::Set(di, 2)), hn::Set(di, n)));
    i = hn::Min(hn::GatherIndex(di, guide_i, below), last);
    len = hn::Add(hn::Sub(hn::Min(hn::GatherIndex(di, guide_i, above), last), i), one_i);
  }
  while (!hn::AllTrue(di, hn::Eq(len, one_i))) {
    // Probing i + half moves i up or leaves the answer below i + half; lanes with len = 1 probe
    // i itself and stay.
    const VI half = hn::ShiftRight<1>(len);
    const VI probe = hn::Add(i, half);
    const V c = hn::GatherIndex(d, cdf, hn::Add(row, probe));
    i = hn::IfThenElse(hn::RebindMask(di, hn::Le(c, u)), probe, i);
    len = hn::Sub(len, half);
  }
  const V lo = hn::GatherIndex(d, cdf, hn::Add(row, i));
  const V hi = hn::GatherIndex(d, cdf, hn::Add(row, hn::Add(i, one_i)));
  const V width = hn::Sub(hi, lo);
  const V t = hn::Div(hn::Sub(u, lo), width);
  const V fn = hn::Set(d, float(n));
  V v = hn::Div(hn::Add(hn::ConvertTo(d, i), hn::Min(t, one)), fn);
  // Rounding may push v onto a neighbouring bin: step it back one float at a time (the bit
  // pattern of a non-negative float steps by one ulp per integer step).
  for (;;) {
    const auto down = hn::And(hn::RebindMask(di, hn::Gt(v, zero)),
                              hn::Gt(PiecewiseConstantBin8(d, v, float(n)), i));
    if (hn::AllFalse(di, down)) break;
    v = hn::BitCast(d,
                    hn::IfThenElse(down, hn::Sub(hn::BitCast(di, v), one_i), hn::BitCast(di, v)));
  }
  for (;;) {
    const auto up = hn::Lt(PiecewiseConstantBin8(d, v, float(n)), i);
    if (hn::AllFalse(di, up)) break;
    v = hn::BitCast(d, hn::IfThenElse(up, hn::Add(hn::BitCast(di, v), one_i), hn::BitCast(di, v)));
  }
  *x = hn::IfThenElse(hn::Ge(v, one), below_one, v);
  *bin = i;
  *pdf = hn::Mul(fn, width);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_DISTRIBUTION8_INL_H_
