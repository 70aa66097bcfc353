// Per-target kernel of simd/wavefront/area_request8.h (re-included once per Highway target):
// integrator::AreaEmitterSampleRequest's operations in its order, eight rows per vector, with
// the BSDF evaluated by the shading stage's dispatched kernel (simd::ShadeBatch, bsdf8.h) of the
// batch's material: the shading kernels have one home, bsdf8.cpp, and are not instantiated again
// here (one indirect call per chunk of 64 rows).

#if defined(PTLAB_SIMD_AREA_REQUEST8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_AREA_REQUEST8_INL_H_
#undef PTLAB_SIMD_AREA_REQUEST8_INL_H_
#else
#define PTLAB_SIMD_AREA_REQUEST8_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "engine/bsdf/bsdf.h"
#include "engine/wavefront/area_request.h"
#include "engine/render/interaction.h"
#include "engine/scene/scene.h"
#include "hwy/highway.h"
#include "simd/light_pdf8-inl.h"
#include "simd/shading_point8-inl.h"
#include "simd/wavefront/bsdf8.h"
#include "simd/wavefront/lanes8-inl.h"  // D8, V8, M8, AllFinite3

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Rows of one pass of the kernel: geometry for all of them, then the BSDF kernel as one batch
/// over those whose geometry allows a sample, then the contributions. Its columns live on the
/// stack (a few KiB).
inline constexpr size_t kAreaRequestChunk = 64;
/// Room for a full vector stored at the last compacted row.
inline constexpr size_t kAreaRequestRoom = kAreaRequestChunk + 8;

/// A chunk's columns between the passes. Per row j = row (chunk start + j) of the batch: the
/// BSDF's f and pdf (0 where the geometry allows no sample), |cos θi|'s wi_local.z, the light
/// pdf, the validity and the shadow ray. Per compacted row k (the valid rows, in order): the
/// row `row`, the BSDF kernel's inputs (material row, wo, wi_local) and outputs.
struct AreaRequestChunk {
  HWY_ALIGN float f_r[kAreaRequestChunk], f_g[kAreaRequestChunk], f_b[kAreaRequestChunk];
  HWY_ALIGN float pdf_bsdf[kAreaRequestChunk];
  HWY_ALIGN float cos_z[kAreaRequestChunk];      // wi_local.z
  HWY_ALIGN float pdf_light[kAreaRequestChunk];  // ls.pdf · pick_pmf
  HWY_ALIGN float valid[kAreaRequestChunk];      // 1: the geometry allows a sample
  HWY_ALIGN float o_x[kAreaRequestChunk], o_y[kAreaRequestChunk], o_z[kAreaRequestChunk];
  HWY_ALIGN float d_x[kAreaRequestChunk], d_y[kAreaRequestChunk], d_z[kAreaRequestChunk];
  size_t rows = 0;  // compacted rows
  HWY_ALIGN int32_t row[kAreaRequestRoom];
  HWY_ALIGN uint32_t index[kAreaRequestRoom];
  HWY_ALIGN uint32_t entry[kAreaRequestRoom];  // queue entries (a scene with textures only)
  HWY_ALIGN float wo_x[kAreaRequestRoom], wo_y[kAreaRequestRoom], wo_z[kAreaRequestRoom];
  HWY_ALIGN float wl_x[kAreaRequestRoom], wl_y[kAreaRequestRoom], wl_z[kAreaRequestRoom];
  HWY_ALIGN float e_r[kAreaRequestRoom], e_g[kAreaRequestRoom], e_b[kAreaRequestRoom];
  HWY_ALIGN float e_pdf[kAreaRequestRoom];
};

/// Pass 1 for rows [i, i + Lanes(d)) of the batch into rows [j, j + Lanes(d)) of the chunk: the
/// shading point's ng and n loaded (InteractionPoints) and material gathered by queue entry, wi and
/// its validity, wi in the local frame, the shadow ray's endpoints and the light pdf; f and pdf 0;
/// the valid rows appended to the compacted rows (a BSDF evaluation for the others would be thrown
/// away: on sphere lights, sampled uniformly by area, half the points face away).
HWY_INLINE void AreaRequestGeometry(const AreaRequestInputs& in, size_t i, size_t j,
                                    AreaRequestChunk* c) {
  const D8 d;
  const hn::RebindToSigned<D8> di;
  const V8 zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto entry = hn::LoadU(di, reinterpret_cast<const int32_t*>(in.entry + i));
  V8 its_p[3], its_ng[3], its_n[3];
  InteractionPoints(d, in.its, entry, its_p, its_ng, its_n);

  const V8 px = hn::LoadU(d, in.ref_x + i), py = hn::LoadU(d, in.ref_y + i),
           pz = hn::LoadU(d, in.ref_z + i);
  const V8 ngx = its_ng[0], ngy = its_ng[1], ngz = its_ng[2];
  // wi = (ls.p - its.p) / |ls.p - its.p| (Vec3f's operator/: times the reciprocal).
  const V8 lx = hn::LoadU(d, in.p_x + i), ly = hn::LoadU(d, in.p_y + i),
           lz = hn::LoadU(d, in.p_z + i);
  const V8 dx = hn::Sub(lx, px), dy = hn::Sub(ly, py), dz = hn::Sub(lz, pz);
  const V8 dist2 = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
  const V8 inv = hn::Div(one, hn::Sqrt(dist2));
  const V8 wx = hn::Mul(dx, inv), wy = hn::Mul(dy, inv), wz = hn::Mul(dz, inv);
  const V8 cos_light =
      hn::Add(hn::Add(hn::Mul(hn::LoadU(d, in.n_x + i), wx), hn::Mul(hn::LoadU(d, in.n_y + i), wy)),
              hn::Mul(hn::LoadU(d, in.n_z + i), wz));
  const V8 ls_pdf = hn::LoadU(d, in.pdf + i);
  const M8 valid =
      hn::And(hn::And(hn::Gt(ls_pdf, zero), hn::Gt(dist2, zero)), hn::Lt(cos_light, zero));
  hn::Store(hn::IfThenElseZero(valid, one), d, c->valid + j);
  hn::Store(hn::Mul(ls_pdf, hn::LoadU(d, in.pick_pmf + i)), d, c->pdf_light + j);
  for (float* col : {c->f_r, c->f_g, c->f_b, c->pdf_bsdf}) hn::Store(zero, d, col + j);
  // wi_local = frame.ToLocal(wi): Dot(wi, s), Dot(wi, t), Dot(wi, n), the frame's s and t
  // rebuilt from n as Frame(n) builds them (every SurfaceInteraction's frame is Frame(n)):
  // fewer gathers than reading them.
  const V8 nx = its_n[0], ny = its_n[1], nz = its_n[2];
  V8 sx, sy, sz, b, ty, tz;
  FrameOfNormal(d, nx, ny, nz, sx, sy, sz, b, ty, tz);
  const V8 local_x = hn::Add(hn::Add(hn::Mul(wx, sx), hn::Mul(wy, sy)), hn::Mul(wz, sz));
  const V8 local_y = hn::Add(hn::Add(hn::Mul(wx, b), hn::Mul(wy, ty)), hn::Mul(wz, tz));
  const V8 local_z = hn::Add(hn::Add(hn::Mul(wx, nx), hn::Mul(wy, ny)), hn::Mul(wz, nz));
  hn::Store(hn::IfThenElseZero(valid, local_z), d, c->cos_z + j);
  // The valid rows for the BSDF kernel: material row (MaterialRef::index(), the ref's low 28
  // bits), wo, wi_local.
  if (!hn::AllFalse(d, valid)) {
    const auto valid_i = hn::RebindMask(di, valid);
    const size_t k = c->rows;
    const auto material =
        hn::GatherIndex(di, reinterpret_cast<const int32_t*>(in.its),
                        hn::Add(InteractionFirst(entry), hn::Set(di, kInteractionMaterial)));
    hn::StoreU(hn::Compress(hn::And(material, hn::Set(di, 0x0fffffff)), valid_i), di,
               reinterpret_cast<int32_t*>(c->index + k));
    hn::StoreU(hn::Compress(hn::Add(hn::Iota(di, 0), hn::Set(di, int32_t(j))), valid_i), di,
               c->row + k);
    const auto compact = [&](V8 v, float* col)
                             HWY_ATTR { hn::StoreU(hn::Compress(v, valid), d, col + k); };
    compact(hn::LoadU(d, in.wo_x + i), c->wo_x);
    compact(hn::LoadU(d, in.wo_y + i), c->wo_y);
    compact(hn::LoadU(d, in.wo_z + i), c->wo_z);
    compact(local_x, c->wl_x), compact(local_y, c->wl_y), compact(local_z, c->wl_z);
    c->rows = k + hn::CountTrue(d, valid);
  }
  // The shadow ray: SpawnOrigin(its, wi) to OffsetRayOrigin(ls.p, ±ls.ng), each offset to the
  // side wi leaves or arrives on.
  const M8 leave_front =
      hn::Ge(hn::Add(hn::Add(hn::Mul(ngx, wx), hn::Mul(ngy, wy)), hn::Mul(ngz, wz)), zero);
  const V8 ox = OffsetCoordinate(d, px, hn::IfThenElse(leave_front, ngx, hn::Neg(ngx)));
  const V8 oy = OffsetCoordinate(d, py, hn::IfThenElse(leave_front, ngy, hn::Neg(ngy)));
  const V8 oz = OffsetCoordinate(d, pz, hn::IfThenElse(leave_front, ngz, hn::Neg(ngz)));
  const V8 lgx = hn::LoadU(d, in.ng_x + i), lgy = hn::LoadU(d, in.ng_y + i),
           lgz = hn::LoadU(d, in.ng_z + i);
  const M8 arrive_front =
      hn::Le(hn::Add(hn::Add(hn::Mul(lgx, wx), hn::Mul(lgy, wy)), hn::Mul(lgz, wz)), zero);
  const V8 to_x = OffsetCoordinate(d, lx, hn::IfThenElse(arrive_front, lgx, hn::Neg(lgx)));
  const V8 to_y = OffsetCoordinate(d, ly, hn::IfThenElse(arrive_front, lgy, hn::Neg(lgy)));
  const V8 to_z = OffsetCoordinate(d, lz, hn::IfThenElse(arrive_front, lgz, hn::Neg(lgz)));
  hn::Store(ox, d, c->o_x + j), hn::Store(oy, d, c->o_y + j), hn::Store(oz, d, c->o_z + j);
  hn::Store(hn::Sub(to_x, ox), d, c->d_x + j), hn::Store(hn::Sub(to_y, oy), d, c->d_y + j);
  hn::Store(hn::Sub(to_z, oz), d, c->d_z + j);
}

/// Pass 3 for rows [j, j + Lanes(d)) of the chunk into rows [i, ...) of the outputs: the MIS
/// weight (LightSampleContribution's MisWeight), the contribution f·Le·(|cos θi|·w / pdf_light)
/// and the traced flag (valid, f not black, contribution finite); rows not traced are 0.
HWY_INLINE void AreaRequestFinish(const Scene& scene, bool mis, bool power,
                                  const AreaRequestInputs& in, const AreaRequestOutputs& out,
                                  size_t i, size_t j, const AreaRequestChunk& c) {
  const D8 d;
  const hn::RebindToSigned<D8> di;
  const V8 zero = hn::Zero(d);
  const V8 fr = hn::Load(d, c.f_r + j), fg = hn::Load(d, c.f_g + j), fb = hn::Load(d, c.f_b + j);
  const V8 pdf_light = hn::Load(d, c.pdf_light + j);
  const V8 weight =
      mis ? MisWeight8(d, pdf_light, hn::Load(d, c.pdf_bsdf + j), power) : hn::Set(d, 1.0f);
  const V8 z = hn::Load(d, c.cos_z + j);
  const V8 abs_cos = hn::IfThenElse(hn::Lt(z, zero), hn::Neg(z), z);  // AbsCosTheta, -0 kept
  const V8 scale = hn::Div(hn::Mul(abs_cos, weight), pdf_light);
  // Le: the sample's own radiance (le columns: textured area lights), else the light's.
  V8 le_r, le_g, le_b;
  if (in.le_r != nullptr) {
    le_r = hn::LoadU(d, in.le_r + i), le_g = hn::LoadU(d, in.le_g + i);
    le_b = hn::LoadU(d, in.le_b + i);
  } else {
    const float* radiance = reinterpret_cast<const float*>(scene.area_lights.radiance.data());
    const auto light = hn::LoadU(di, reinterpret_cast<const int32_t*>(in.light + i));
    const auto light_row = hn::Mul(light, hn::Set(di, 3));
    le_r = hn::GatherIndex(d, radiance, light_row);
    le_g = hn::GatherIndex(d, radiance, hn::Add(light_row, hn::Set(di, 1)));
    le_b = hn::GatherIndex(d, radiance, hn::Add(light_row, hn::Set(di, 2)));
  }
  const V8 cr = hn::Mul(hn::Mul(fr, le_r), scale);
  const V8 cg = hn::Mul(hn::Mul(fg, le_g), scale);
  const V8 cb = hn::Mul(hn::Mul(fb, le_b), scale);
  const M8 black = hn::And(hn::Eq(fr, zero), hn::And(hn::Eq(fg, zero), hn::Eq(fb, zero)));
  const M8 traced =
      hn::AndNot(black, hn::And(hn::Gt(hn::Load(d, c.valid + j), zero), AllFinite3(d, cr, cg, cb)));
  hn::StoreU(hn::IfThenElseZero(traced, cr), d, out.r + i);
  hn::StoreU(hn::IfThenElseZero(traced, cg), d, out.g + i);
  hn::StoreU(hn::IfThenElseZero(traced, cb), d, out.b + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.o_x + j)), d, out.o_x + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.o_y + j)), d, out.o_y + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.o_z + j)), d, out.o_z + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.d_x + j)), d, out.d_x + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.d_y + j)), d, out.d_y + i);
  hn::StoreU(hn::IfThenElseZero(traced, hn::Load(d, c.d_z + j)), d, out.d_z + i);
  uint8_t bits[8] = {};
  hn::StoreMaskBits(d, traced, bits);
  for (size_t k = 0; k < hn::Lanes(d); ++k) out.traced[i + k] = uint8_t((bits[0] >> k) & 1u);
}

inline void AreaEmitterRequestBatchKernel(const Scene& scene, MaterialTag tag, bool mis, size_t n,
                                          const AreaRequestInputs& in,
                                          const AreaRequestOutputs& out) {
  const D8 d;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  // Delta materials: f = 0 for every direction, no row traces (the oracle's BsdfEval).
  if (IsDeltaMaterial(tag)) {
    const V8 zero = hn::Zero(d);
    for (; i + lanes <= n; i += lanes) {
      for (float* col : {out.o_x, out.o_y, out.o_z, out.d_x, out.d_y, out.d_z, out.r, out.g, out.b})
        hn::StoreU(zero, d, col + i);
      for (size_t k = 0; k < lanes; ++k) out.traced[i + k] = 0;
    }
  }
  const bool power = scene.integrator.power_heuristic;
  AreaRequestChunk c;
  while (i + lanes <= n) {
    const size_t rows = std::min(kAreaRequestChunk, (n - i) / lanes * lanes);
    c.rows = 0;
    for (size_t j = 0; j < rows; j += lanes) AreaRequestGeometry(in, i + j, j, &c);
    // The BSDF at (wo, wi_local) of the valid rows, evaluation only: f, and its pdf for the MIS
    // weight; then back to their rows.
    if (c.rows > 0) {
      ShadeInputs bsdf_in;
      bsdf_in.wo = {c.wo_x, c.wo_y, c.wo_z};
      bsdf_in.wl = {c.wl_x, c.wl_y, c.wl_z};
      // Textured parameters read the compacted rows' shading points.
      if (!scene.textures.empty()) {
        for (size_t k = 0; k < c.rows; ++k) c.entry[k] = in.entry[i + size_t(c.row[k])];
        bsdf_in.texture = {&scene.textures, in.its, c.entry};
      }
      ShadeOutputs bsdf_out;
      bsdf_out.f = {c.e_r, c.e_g, c.e_b};
      bsdf_out.pdf_l = c.e_pdf;
      simd::ShadeBatch(scene.materials, tag, c.index, c.rows, bsdf_in, bsdf_out);
      for (size_t k = 0; k < c.rows; ++k) {
        const int32_t j = c.row[k];
        c.f_r[j] = c.e_r[k], c.f_g[j] = c.e_g[k], c.f_b[j] = c.e_b[k];
        c.pdf_bsdf[j] = c.e_pdf[k];
      }
    }
    for (size_t j = 0; j < rows; j += lanes)
      AreaRequestFinish(scene, mis, power, in, out, i + j, j, c);
    i += rows;
  }
  // The rows after the last full vector: the oracle row by row, then, as above, no row with a
  // contribution that is not finite.
  if (i == n) return;
  ptlab::AreaEmitterRequestBatch(scene, tag, mis, n - i, in.From(i), out.From(i));
  for (; i < n; ++i) {
    if (std::isfinite(out.r[i]) && std::isfinite(out.g[i]) && std::isfinite(out.b[i])) continue;
    SetAreaRequestRow(out, i, integrator::EmitterSampleRequest{});
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_AREA_REQUEST8_INL_H_
