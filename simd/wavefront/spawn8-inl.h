// Per-target kernel of simd/wavefront/spawn8.h (re-included once per Highway target): SpawnRayAt's
// operations in its order, eight rows per packet.

#if defined(PTLAB_SIMD_SPAWN8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_SPAWN8_INL_H_
#undef PTLAB_SIMD_SPAWN8_INL_H_
#else
#define PTLAB_SIMD_SPAWN8_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <limits>

#include "engine/core/packet8.h"
#include "engine/render/interaction.h"
#include "engine/wavefront/spawn.h"
#include "hwy/highway.h"
#include "simd/shading_point8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

inline void SpawnRayBatchKernel(const SurfaceInteraction* its, size_t n, const SpawnInputs& in,
                                RayPacket8* out) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  const auto infinity = hn::Set(d, std::numeric_limits<float>::infinity());
  const size_t full = n / kPacketWidth;
  for (size_t k = 0; k < full; ++k) {
    RayPacket8& ray = out[k];
    for (size_t j = 0; j < kPacketWidth; j += lanes) {
      const size_t row = k * kPacketWidth + j;
      hn::Vec<decltype(d)> p[3], g[3], n[3];
      InteractionPoints(d, its, hn::LoadU(di, reinterpret_cast<const int32_t*>(in.entry + row)), p,
                        g, n);
      const auto n_x = n[0], n_y = n[1], n_z = n[2];
      // The frame as the interaction slot built it (Frame(n)): fewer gathers than reading it.
      hn::Vec<decltype(d)> s_x, s_y, s_z, b, t_y, t_z;
      FrameOfNormal(d, n_x, n_y, n_z, s_x, s_y, s_z, b, t_y, t_z);
      // ToWorld: s * wi.x + t * wi.y + n * wi.z (t_x = b).
      const auto u_x = hn::LoadU(d, in.wi_x + row), u_y = hn::LoadU(d, in.wi_y + row);
      const auto u_z = hn::LoadU(d, in.wi_z + row);
      const auto w_x = hn::Add(hn::Add(hn::Mul(s_x, u_x), hn::Mul(b, u_y)), hn::Mul(n_x, u_z));
      const auto w_y = hn::Add(hn::Add(hn::Mul(s_y, u_x), hn::Mul(t_y, u_y)), hn::Mul(n_y, u_z));
      const auto w_z = hn::Add(hn::Add(hn::Mul(s_z, u_x), hn::Mul(t_z, u_y)), hn::Mul(n_z, u_z));
      // SpawnOrigin: the geometric normal flipped to wi's side (Dot(ng, wi) >= 0 keeps it).
      auto g_x = g[0], g_y = g[1], g_z = g[2];
      const auto side = hn::Add(hn::Add(hn::Mul(g_x, w_x), hn::Mul(g_y, w_y)), hn::Mul(g_z, w_z));
      const auto keep = hn::Ge(side, zero);
      g_x = hn::IfThenElse(keep, g_x, hn::Neg(g_x));
      g_y = hn::IfThenElse(keep, g_y, hn::Neg(g_y));
      g_z = hn::IfThenElse(keep, g_z, hn::Neg(g_z));
      const auto p_x = p[0], p_y = p[1], p_z = p[2];
      hn::Store(OffsetCoordinate(d, p_x, g_x), d, ray.org_x + j);
      hn::Store(OffsetCoordinate(d, p_y, g_y), d, ray.org_y + j);
      hn::Store(OffsetCoordinate(d, p_z, g_z), d, ray.org_z + j);
      hn::Store(w_x, d, ray.dir_x + j);
      hn::Store(w_y, d, ray.dir_y + j);
      hn::Store(w_z, d, ray.dir_z + j);
      hn::Store(zero, d, ray.t_min + j);
      hn::Store(infinity, d, ray.t_max + j);
    }
  }
  // The last, partial packet: the oracle row by row (it also zeroes the lanes without a row).
  const size_t done = full * kPacketWidth;
  if (done == n) return;
  const SpawnInputs rest{in.entry + done, in.wi_x + done, in.wi_y + done, in.wi_z + done};
  ptlab::SpawnRayBatch(its, n - done, rest, out + full);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_SPAWN8_INL_H_
