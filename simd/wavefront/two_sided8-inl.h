// Per-target twin of the two-sided wrapper of engine/bsdf/two_sided.h (Mitsuba `twosided`),
// included by bsdf8-inl.h. Oracle: the TwoSidedFlips blocks of BsdfEval / BsdfPdf /
// BsdfSampleDirection. The flip is a sign change of z: the rows' wo.z and wl.z are copied with
// the sign flipped where the row is two-sided and wo.z < 0, the one-sided kernel runs on the
// copies, and a sampled wi.z is flipped back; exact, so the wrapped kernel's contract is kept.

#if defined(PTLAB_SIMD_TWO_SIDED8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_TWO_SIDED8_INL_H_
#undef PTLAB_SIMD_TWO_SIDED8_INL_H_
#else
#define PTLAB_SIMD_TWO_SIDED8_INL_H_
#endif

#include "engine/wavefront/bsdf.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

inline void ShadeBatchKernelOneSided(const MaterialTables& m, MaterialTag tag,
                                     const uint32_t* material_index, size_t n,
                                     const ShadeInputs& in, const ShadeOutputs& out);

/// The shade step of a tag some of whose rows are two-sided (`flags`, `flag_count` entries),
/// in chunks of kChunk rows on stack copies of wo.z and wl.z.
inline HWY_NOINLINE void ShadeTwoSided(const MaterialTables& m, MaterialTag tag,
                                       const uint8_t* flags, size_t flag_count,
                                       const uint32_t* material_index, size_t n,
                                       const ShadeInputs& in, const ShadeOutputs& out) {
  constexpr size_t kChunk = 256;
  HWY_ALIGN float wo_z[kChunk], wl_z[kChunk];
  HWY_ALIGN uint8_t flip[kChunk];
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  for (size_t at = 0; at < n; at += kChunk) {
    const size_t c = n - at < kChunk ? n - at : kChunk;
    const uint32_t* index = material_index + at;
    for (size_t j = 0; j < c; ++j) {
      const bool two_sided = index[j] < flag_count && flags[index[j]] != 0;
      const float z = in.wo.z[at + j];
      flip[j] = two_sided && z < 0 ? 1 : 0;
      wo_z[j] = flip[j] ? -z : z;
      if (eval) wl_z[j] = flip[j] ? -in.wl.z[at + j] : in.wl.z[at + j];
    }
    ShadeInputs cin;
    cin.texture = in.texture;  // mask: the chunk's shading points (textured rows)
    if (in.texture.entry != nullptr) cin.texture.entry = in.texture.entry + at;
    cin.wo = {in.wo.x + at, in.wo.y + at, wo_z};
    if (eval) cin.wl = {in.wl.x + at, in.wl.y + at, wl_z};
    if (sample) cin.u_lobe = in.u_lobe + at, cin.u_x = in.u_x + at, cin.u_y = in.u_y + at;
    // The rows' shading points, for textured parameters (without them a textured row read its
    // constant, 0).
    cin.texture = in.texture;
    if (in.texture.textures != nullptr) cin.texture.entry = in.texture.entry + at;
    ShadeOutputs cout;
    if (eval) {
      cout.f = {out.f.r + at, out.f.g + at, out.f.b + at};
      cout.pdf_l = out.pdf_l + at;
    }
    if (sample) {
      cout.wi = {out.wi.x + at, out.wi.y + at, out.wi.z + at};
      cout.weight = {out.weight.r + at, out.weight.g + at, out.weight.b + at};
      cout.pdf = out.pdf + at, cout.eta = out.eta + at;
      if (out.delta != nullptr) cout.delta = out.delta + at;
    }
    ShadeBatchKernelOneSided(m, tag, index, c, cin, cout);
    if (!sample) continue;
    for (size_t j = 0; j < c; ++j)
      if (flip[j] && cout.pdf[j] > 0) cout.wi.z[j] = -cout.wi.z[j];
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_TWO_SIDED8_INL_H_
