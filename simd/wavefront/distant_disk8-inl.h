// Per-target kernel of simd/wavefront/distant_disk8.h (re-included once per Highway target):
// SampleDistantDisk's uniform cone sampling, eight rows per vector.

#if defined(PTLAB_SIMD_DISTANT_DISK8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_DISTANT_DISK8_INL_H_
#undef PTLAB_SIMD_DISTANT_DISK8_INL_H_
#else
#define PTLAB_SIMD_DISTANT_DISK8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/core/vec.h"
#include "engine/wavefront/distant_disk.h"
#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

HWY_INLINE void SampleDistantDiskBatchKernel(const DistantDiskTable& table, uint32_t disk, size_t n,
                                             const EnvironmentBatchInputs& in,
                                             const EnvironmentBatchOutputs& out) {
  const hn::CappedTag<float, 8> d;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  // A black disk gives no sample: the scalar rows write its zeros.
  if (!IsBlack(table.radiance[disk])) {
    const Frame& f = table.to_world[disk];
    const Color3f& c = table.radiance[disk];
    // The scalar code's per-disk factors, rounded as it rounds them.
    const auto scale = hn::Set(d, table.solid_angle[disk] * kInv2Pi);
    const auto pdf = hn::Set(d, 1.0f / table.solid_angle[disk]);
    const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
    const auto two_pi = hn::Set(d, 2 * kPi);
    for (; i + lanes <= n; i += lanes) {
      // 1 - cosθ = s = u.x (1 - cos thetaA); sinθ = sqrt(s (2 - s)) (distant_disk.cpp).
      const auto s = hn::Mul(hn::Min(hn::LoadU(d, in.u_x + i), one), scale);
      const auto r = hn::Sqrt(hn::Max(zero, hn::Mul(s, hn::Sub(two, s))));
      const auto phi = hn::Mul(two_pi, hn::LoadU(d, in.u_y + i));
      const auto lx = hn::Mul(r, hn::Cos(d, phi)), ly = hn::Mul(r, hn::Sin(d, phi));
      const auto lz = hn::Sub(one, s);
      // Frame::ToWorld: s l.x + t l.y + n l.z.
      const auto world = [&](float fs, float ft, float fn) {
        return hn::Add(hn::Add(hn::Mul(hn::Set(d, fs), lx), hn::Mul(hn::Set(d, ft), ly)),
                       hn::Mul(hn::Set(d, fn), lz));
      };
      hn::StoreU(world(f.s.x, f.t.x, f.n.x), d, out.wi_x + i);
      hn::StoreU(world(f.s.y, f.t.y, f.n.y), d, out.wi_y + i);
      hn::StoreU(world(f.s.z, f.t.z, f.n.z), d, out.wi_z + i);
      hn::StoreU(hn::Set(d, c.r), d, out.r + i);
      hn::StoreU(hn::Set(d, c.g), d, out.g + i);
      hn::StoreU(hn::Set(d, c.b), d, out.b + i);
      hn::StoreU(pdf, d, out.pdf + i);
    }
  }
  for (; i < n; ++i) SetEnvironmentRow(out, i, SampleDistantDiskRow(table, disk, in, i));
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_DISTANT_DISK8_INL_H_
