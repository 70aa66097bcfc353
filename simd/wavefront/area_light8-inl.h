// Per-target kernel of simd/wavefront/area_light8.h (re-included once per Highway target): SampleAreaLight's
// operations in its order, eight rows per vector.

#if defined(PTLAB_SIMD_EMITTER8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_EMITTER8_INL_H_
#undef PTLAB_SIMD_EMITTER8_INL_H_
#else
#define PTLAB_SIMD_EMITTER8_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "engine/core/vec.h"
#include "engine/scene/scene.h"
#include "engine/wavefront/area_light.h"
#include "hwy/highway.h"
#include "simd/light_pdf8-inl.h"
#include "simd/transpose4-inl.h"
#include "simd/triangle_point8-inl.h"
#include "simd/wavefront/area_radiance8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

/// Per lane of one vector of rows: the picked triangle, the rescaled u_x, 1 / light area, and
/// which lanes are valid (area > 0, 1.0f) — what the vector part loads and masks with.
struct AreaLightLanes {
  alignas(64) int32_t tri[8];
  alignas(64) float u_x[8], inv_area[8], valid[8];
};

/// Lights a scene may have for the kernel to hold their per-light values in vectors (one or
/// two per value) and pick each lane's with a lane permute instead of a gather.
inline constexpr size_t kRegisterLights = 8;

/// The per-light values the triangle pick reads, for a scene of at most kRegisterLights lights,
/// as each lane needs them: a zero-area light (never sampled) reads row 0 of a one-entry CDF,
/// and 1 / area is the vector path's own quotient (both correctly rounded). Built once a call.
struct AreaLightRegisterTable {
  alignas(64) float area[kRegisterLights], inv_area[kRegisterLights];
  alignas(64) int32_t count[kRegisterLights], cdf_at[kRegisterLights];
  alignas(64) int32_t guide_at[kRegisterLights], first[kRegisterLights];

  explicit AreaLightRegisterTable(const Scene& scene) {
    const AreaLightTable& lights = scene.area_lights;
    for (size_t i = 0; i < kRegisterLights; ++i) {
      const bool valid = i < lights.size() && lights.area[i] > 0;
      area[i] = i < lights.size() ? lights.area[i] : 0.0f;
      inv_area[i] = valid ? 1.0f / area[i] : 0.0f;
      const uint32_t mesh = i < lights.size() ? lights.mesh[i] : 0;
      count[i] = valid ? int32_t(scene.meshes.triangle_count[mesh]) : 1;
      cdf_at[i] = valid ? int32_t(lights.cdf_offset[i]) : 0;
      guide_at[i] = valid ? int32_t(lights.guide_offset[i]) : 0;
      first[i] = i < lights.size() ? int32_t(scene.meshes.first_triangle[mesh]) : 0;
    }
  }
};

/// table[light] per lane for light < min(kRegisterLights, 2 lanes): one permute of the table's
/// first vector, or two and a select on targets of fewer than kRegisterLights lanes.
template <class D, class VI>
HWY_INLINE hn::Vec<D> LookupLight(D d, const hn::TFromD<D>* table, VI light) {
  const hn::RebindToSigned<D> di;
  const size_t lanes = hn::Lanes(d);
  const auto low = hn::And(light, hn::Set(di, int32_t(lanes - 1)));
  const auto first = hn::TableLookupLanes(hn::Load(d, table), hn::IndicesFromVec(d, low));
  if (lanes >= kRegisterLights) return first;
  const auto second = hn::TableLookupLanes(hn::Load(d, table + lanes), hn::IndicesFromVec(d, low));
  return hn::IfThenElse(hn::RebindMask(d, hn::Gt(light, hn::Set(di, int32_t(lanes - 1)))), second,
                        first);
}

/// Fills `l` for rows [row, row + lanes); returns whether any lane is valid. The per-light values
/// come from `table` where the scene has one (few lights), else from gathers. The triangle pick
/// (PickAreaLightTriangle) runs as vectors: the guide table's bucket of u, then a masked linear
/// scan over the bucket for the first CDF entry above u (std::upper_bound over the bucket, without
/// its unpredictable branches; its first two entries gathered together), and the same exactness
/// check; a lane whose bucket does not bracket the answer takes the scalar pick (its full binary
/// search).
template <class D>
HWY_INLINE bool PickLanes(D d, const Scene& scene, const AreaLightRegisterTable* table,
                          const AreaLightBatchInputs& in, size_t row, AreaLightLanes* l) {
  const hn::RebindToSigned<D> di;
  const size_t lanes = hn::Lanes(d);
  const AreaLightTable& lights = scene.area_lights;
  const auto zero = hn::Zero(d);
  const auto as_i = [](const uint32_t* p) { return reinterpret_cast<const int32_t*>(p); };
  const auto zero_i = hn::Zero(di), one_i = hn::Set(di, 1);
  const auto light = hn::LoadU(di, reinterpret_cast<const int32_t*>(in.light + row));
  hn::Vec<D> area, inv_area;
  hn::Vec<decltype(di)> count, cdf_at, guide_at, first;
  if (table != nullptr) {
    area = LookupLight(d, table->area, light);
    if (hn::AllFalse(d, hn::Gt(area, zero))) return false;
    inv_area = LookupLight(d, table->inv_area, light);
    count = LookupLight(di, table->count, light);
    cdf_at = LookupLight(di, table->cdf_at, light);
    guide_at = LookupLight(di, table->guide_at, light);
    first = LookupLight(di, table->first, light);
  } else {
    area = hn::GatherIndex(d, lights.area.data(), light);
    const auto valid = hn::Gt(area, zero);
    if (hn::AllFalse(d, valid)) return false;
    const auto valid_i = hn::RebindMask(di, valid);
    // Lanes of zero-area lights read row 0 of a one-entry CDF (present: a valid lane has one).
    const auto mesh = hn::GatherIndex(di, as_i(lights.mesh.data()), light);
    count = hn::IfThenElse(
        valid_i, hn::GatherIndex(di, as_i(scene.meshes.triangle_count.data()), mesh), one_i);
    cdf_at =
        hn::IfThenElseZero(valid_i, hn::GatherIndex(di, as_i(lights.cdf_offset.data()), light));
    guide_at =
        hn::IfThenElseZero(valid_i, hn::GatherIndex(di, as_i(lights.guide_offset.data()), light));
    first = hn::GatherIndex(di, as_i(scene.meshes.first_triangle.data()), mesh);
    inv_area = hn::IfThenElseZero(valid, hn::Div(hn::Set(d, 1.0f), area));
  }
  const auto valid = hn::Gt(area, zero);
  const auto valid_i = hn::RebindMask(di, valid);
  const float* cdf = lights.triangle_cdf.data();
  const int32_t* guide = as_i(lights.triangle_guide.data());
  const auto u = hn::LoadU(d, in.u_x + row);
  const auto last = hn::Sub(count, one_i);
  // GuidedUpperBound: bucket b, its range [lo, hi), the scan, the check.
  const auto b = hn::Min(last, hn::ConvertTo(di, hn::Mul(hn::Max(zero, u), hn::ConvertTo(d, count))));
  const auto lo = hn::Min(hn::GatherIndex(di, guide, hn::Add(guide_at, b)), count);
  const auto hi =
      hn::Min(count, hn::Add(hn::GatherIndex(di, guide, hn::Add(hn::Add(guide_at, b), one_i)), one_i));
  // The scan: k steps on while k < hi and cdf[k] is not above u. Its first two entries are
  // gathered together, not one after the other (a bucket rarely holds more).
  auto k = lo;
  auto scan = hn::Lt(k, hi);
  const auto step = [&](hn::Vec<D> c) {
    const auto on = hn::AndNot(hn::RebindMask(di, hn::Gt(c, u)), scan);
    k = hn::Add(k, hn::IfThenElseZero(on, one_i));
    scan = hn::And(on, hn::Lt(k, hi));
  };
  const auto c0 = hn::GatherIndex(d, cdf, hn::Add(cdf_at, hn::Min(lo, last)));
  const auto c1 = hn::GatherIndex(d, cdf, hn::Add(cdf_at, hn::Min(hn::Add(lo, one_i), last)));
  step(c0), step(c1);
  while (!hn::AllFalse(di, scan)) step(hn::GatherIndex(d, cdf, hn::Add(cdf_at, hn::Min(k, last))));
  // The CDF entries around k: at = cdf[min(k, last)], below = cdf[k - 1] (k = count: at).
  const auto k_in = hn::Min(k, last);
  const auto at = hn::GatherIndex(d, cdf, hn::Add(cdf_at, k_in));
  const auto before =
      hn::GatherIndex(d, cdf, hn::Add(cdf_at, hn::Max(hn::Sub(k_in, one_i), zero_i)));
  const auto below = hn::IfThenElse(hn::RebindMask(d, hn::Eq(k, count)), at, before);
  const auto has_below = hn::Gt(k, zero_i);
  const auto below_ok = hn::Or(hn::Not(has_below), hn::RebindMask(di, hn::Not(hn::Gt(below, u))));
  const auto at_ok = hn::Or(hn::Eq(k, count), hn::RebindMask(di, hn::Gt(at, u)));
  const auto exact = hn::And(below_ok, at_ok);
  // The chosen triangle's CDF interval and u rescaled to it.
  k = k_in;
  const auto c_lo = hn::IfThenElseZero(hn::RebindMask(d, hn::Gt(k, zero_i)), before);
  const auto width = hn::Sub(at, c_lo);
  const auto rescaled = hn::Min(hn::Div(hn::Sub(u, c_lo), width), hn::Set(d, kOneMinusEpsilon));
  const auto u_x = hn::Max(hn::IfThenElse(hn::Gt(width, zero), rescaled, hn::Set(d, 0.5f)), zero);
  const auto tri = hn::IfThenElseZero(valid_i, hn::Add(first, k));
  hn::Store(tri, di, l->tri);
  hn::Store(hn::IfThenElse(valid, u_x, hn::Set(d, 0.5f)), d, l->u_x);
  hn::Store(inv_area, d, l->inv_area);
  hn::Store(hn::IfThenElseZero(valid, hn::Set(d, 1.0f)), d, l->valid);
  // A lane whose bucket misses the answer: the scalar pick.
  const auto redo = hn::AndNot(exact, valid_i);
  if (!hn::AllFalse(di, redo)) {
    alignas(64) int32_t redo_lanes[8];
    hn::Store(hn::VecFromMask(di, redo), di, redo_lanes);
    for (size_t j = 0; j < lanes; ++j) {
      if (redo_lanes[j] == 0) continue;
      const AreaLightTrianglePick pick =
          PickAreaLightTriangle(scene, in.light[row + j], in.u_x[row + j]);
      l->tri[j] = int32_t(pick.tri), l->u_x[j] = pick.u_x;
    }
  }
  return true;
}

HWY_INLINE void SampleAreaLightBatchKernel(const Scene& scene, const TriangleRows& tri_rows,
                                           TriangleSampling mode, size_t n,
                                           const AreaLightBatchInputs& in,
                                           const AreaLightBatchOutputs& out) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  if (mode == TriangleSampling::kArea) {
    const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    // The register table only for a scene of few lights (else the per-light values are gathered).
    std::optional<AreaLightRegisterTable> table;
    if (scene.area_lights.size() <= std::min(kRegisterLights, 2 * lanes)) table.emplace(scene);
    const AreaLightRegisterTable* registers = table ? &*table : nullptr;
    // Picks for a chunk of vectors, then their points: short loops whose iterations the core
    // overlaps better than one long one with a chain of dependent gathers.
    constexpr size_t kChunk = 8;
    AreaLightLanes chunk[kChunk];
    bool picked[kChunk];
    while (i + lanes <= n) {
      const size_t m = std::min(kChunk, (n - i) / lanes);
      for (size_t j = 0; j < m; ++j)
        picked[j] = PickLanes(d, scene, registers, in, i + j * lanes, &chunk[j]);
      for (size_t j = 0; j < m; ++j, i += lanes) {
        const AreaLightLanes& l = chunk[j];
        if (!picked[j]) {
          for (float* col : {out.p_x, out.p_y, out.p_z, out.n_x, out.n_y, out.n_z, out.ng_x,
                             out.ng_y, out.ng_z, out.pdf})
            hn::StoreU(zero, d, col + i);
          if (out.le_r != nullptr)
            for (float* col : {out.le_r, out.le_g, out.le_b}) hn::StoreU(zero, d, col + i);
          continue;
        }
        const auto tri = hn::Load(di, l.tri);
        // SampleUniformTriangle, then p = V0 b0 + V1 b1 + V2 b2 with b0 = 1 - b1 - b2.
        const auto su = hn::Sqrt(hn::Load(d, l.u_x));
        const auto b1 = hn::Sub(one, su), b2 = hn::Mul(hn::LoadU(d, in.u_y + i), su);
        const auto b0 = hn::Sub(hn::Sub(one, b1), b2);
        const auto valid = hn::Gt(hn::Load(d, l.valid), zero);
        // The triangles' rows (TriangleRows), then p, the geometric normal g (+z where
        // degenerate) and ShadingNormalAt's n: the interpolated vertex normals where the mesh
        // has them.
        hn::Vec<decltype(d)> row[kTriangleRowFloats];
        LoadRowColumns<kTriangleRowFloats / 4>(d, tri_rows.triangles.data(), kTriangleRowFloats,
                                               tri, row);
        auto px = zero, py = zero, pz = zero, gx = zero, gy = zero, gz = zero;
        auto nx = zero, ny = zero, nz = zero;
        auto has_ng = hn::Gt(zero, zero);
        PointOfRows(d, tri_rows, row, valid, b0, b1, b2, px, py, pz, gx, gy, gz, nx, ny, nz,
                    has_ng);
        // ng: the unit geometric normal, or n for a degenerate triangle.
        const auto ngx = hn::IfThenElse(has_ng, gx, nx);
        const auto ngy = hn::IfThenElse(has_ng, gy, ny);
        const auto ngz = hn::IfThenElse(has_ng, gz, nz);
        // AreaToSolidAngle(1 / area, p, n, ref).
        const auto dx = hn::Sub(px, hn::LoadU(d, in.ref_x + i));
        const auto dy = hn::Sub(py, hn::LoadU(d, in.ref_y + i));
        const auto dz = hn::Sub(pz, hn::LoadU(d, in.ref_z + i));
        auto solid = hn::Gt(zero, zero);
        const auto pdf =
            AreaToSolidAngle8(d, hn::Load(d, l.inv_area), dx, dy, dz, nx, ny, nz, &solid);
        // Lanes of zero-area lights: AreaLightSample{} (all zero).
        hn::StoreU(hn::IfThenElseZero(valid, px), d, out.p_x + i);
        hn::StoreU(hn::IfThenElseZero(valid, py), d, out.p_y + i);
        hn::StoreU(hn::IfThenElseZero(valid, pz), d, out.p_z + i);
        hn::StoreU(hn::IfThenElseZero(valid, nx), d, out.n_x + i);
        hn::StoreU(hn::IfThenElseZero(valid, ny), d, out.n_y + i);
        hn::StoreU(hn::IfThenElseZero(valid, nz), d, out.n_z + i);
        hn::StoreU(hn::IfThenElseZero(valid, ngx), d, out.ng_x + i);
        hn::StoreU(hn::IfThenElseZero(valid, ngy), d, out.ng_y + i);
        hn::StoreU(hn::IfThenElseZero(valid, ngz), d, out.ng_z + i);
        hn::StoreU(hn::IfThenElseZero(hn::And(valid, solid), pdf), d, out.pdf + i);
        if (out.le_r != nullptr) {
          // The sample's radiance (textured area lights): the light's texture at the point's
          // surface uv, or its constant radiance; 0 in lanes of zero-area lights.
          auto u = zero, v = zero, le_r = zero, le_g = zero, le_b = zero;
          SurfaceUv8(scene, tri, b1, b2, valid, &u, &v);
          const auto light = hn::LoadU(di, reinterpret_cast<const int32_t*>(in.light + i));
          AreaLightRadiance8(scene, light, u, v, px, py, pz, tri, valid, &le_r, &le_g, &le_b);
          hn::StoreU(le_r, d, out.le_r + i);
          hn::StoreU(le_g, d, out.le_g + i);
          hn::StoreU(le_b, d, out.le_b + i);
        }
      }
    }
  }
  // kSolidAngle, and the rows after the last full vector: the scalar code row by row.
  for (; i < n; ++i) {
    SetAreaLightRow(out, i,
                    ptlab::SampleAreaLight(scene, in.light[i], AreaLightRowRef(in, i), mode,
                                           AreaLightRowU(in, i)));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_EMITTER8_INL_H_
