// Per-target kernel of simd/wavefront/emission8.h (re-included once per Highway target): the area-light
// hits' light, ptlab::AddAreaEmissions' operations in its order, eight rows per vector.

#if defined(PTLAB_SIMD_EMISSION8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_EMISSION8_INL_H_
#undef PTLAB_SIMD_EMISSION8_INL_H_
#else
#define PTLAB_SIMD_EMISSION8_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "engine/wavefront/emission.h"
#include "hwy/highway.h"
#include "simd/light_pdf8-inl.h"
#include "simd/shading_point8-inl.h"
#include "simd/wavefront/area_radiance8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// A RayPacket8 read as floats: eight columns of eight lanes, the directions' from float 24 on.
inline constexpr int32_t kRayPacketFloats = int32_t(sizeof(RayPacket8) / sizeof(float));
inline constexpr int32_t kRayDirX = int32_t(offsetof(RayPacket8, dir_x) / sizeof(float));
static_assert(kRayPacketFloats == 64 &&
              offsetof(RayPacket8, dir_y) == offsetof(RayPacket8, dir_x) + 32 &&
              offsetof(RayPacket8, dir_z) == offsetof(RayPacket8, dir_x) + 64);
inline constexpr int32_t kInteractionEmitter =
    int32_t(offsetof(SurfaceInteraction, emitter) / sizeof(float));
inline constexpr int32_t kInteractionUv = int32_t(offsetof(SurfaceInteraction, uv) / sizeof(float));
inline constexpr int32_t kInteractionPrim =
    int32_t(offsetof(SurfaceInteraction, prim) / sizeof(float));
static_assert(sizeof(EmitterRef) == sizeof(uint32_t) && sizeof(Color3f) == 3 * sizeof(float) &&
              sizeof(Vec3f) == 3 * sizeof(float));

inline void AddAreaEmissionsKernel(const Scene& scene, const EmissionBatchRules& rules, size_t n,
                                   const EmissionBatchInputs& in, const EmissionBatchPaths& paths) {
  const AreaLightTable& lights = scene.area_lights;
  // The solid-angle triangle sampling's density (SolidAngleSampled) stays with the oracle, as
  // does a scene without area lights (no row can then be an area hit; the gathers below read
  // light 0 in every lane that is not one).
  if (lights.radiance.empty() ||
      (rules.nee && rules.mis &&
       scene.integrator.triangle_sampling == TriangleSampling::kSolidAngle)) {
    ptlab::AddAreaEmissions(scene, rules, n, in, paths);
    return;
  }
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t lanes = hn::Lanes(d);
  const auto as_f = [](const auto* p) { return reinterpret_cast<const float*>(p); };
  const auto as_i = [](const auto* p) { return reinterpret_cast<const int32_t*>(p); };
  const float* const rays = as_f(in.rays);
  const float* const radiance = as_f(lights.radiance.data());
  const float* const throughput = as_f(paths.throughput);
  float* const L = reinterpret_cast<float*>(paths.L);
  const bool power = scene.integrator.power_heuristic;
  const bool textured = !lights.texture.empty();
  const size_t emitters = scene.emitters.size();
  const bool uniform = scene.integrator.light_selection == LightSelection::kUniform;
  const EmitterSelectionTable& selection = scene.emitter_selection;
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto zero_i = hn::Zero(di), one_i = hn::Set(di, 1), two_i = hn::Set(di, 2);
  const auto three_i = hn::Set(di, 3);
  size_t k = 0;
  for (; k + lanes <= n; k += lanes) {
    const auto entry = hn::LoadU(di, as_i(in.entry + k));
    const auto path = hn::GatherIndex(di, as_i(in.owner), entry);
    // The ray of entry q: lane q % 8 of packet q / 8.
    const auto ray = hn::Add(hn::Mul(hn::ShiftRight<3>(entry), hn::Set(di, kRayPacketFloats)),
                             hn::Add(hn::And(entry, hn::Set(di, 7)), hn::Set(di, kRayDirX)));
    const auto dx = hn::GatherIndex(d, rays, ray);
    const auto dy = hn::GatherIndex(d, rays, hn::Add(ray, hn::Set(di, 8)));
    const auto dz = hn::GatherIndex(d, rays, hn::Add(ray, hn::Set(di, 16)));
    // w = -d / Length(d): Vec3f's division is a product with 1 / s.
    const auto inv_length =
        hn::Div(one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz))));
    const auto wx = hn::Mul(hn::Neg(dx), inv_length);
    const auto wy = hn::Mul(hn::Neg(dy), inv_length);
    const auto wz = hn::Mul(hn::Neg(dz), inv_length);
    // Emitted: an area light (tag kArea = 0 in the top 4 bits; EmitterRef::None's is 15) whose
    // shading normal faces w (AreaLightRadiance).
    const auto first = InteractionFirst(entry);
    const auto emitter =
        hn::GatherIndex(di, as_i(in.its), hn::Add(first, hn::Set(di, kInteractionEmitter)));
    const auto area_i = hn::Eq(hn::And(emitter, hn::Set(di, int32_t(0xf0000000u))), zero_i);
    const auto light = hn::IfThenElseZero(area_i, hn::And(emitter, hn::Set(di, 0x0fffffff)));
    const auto nx = InteractionField(d, in.its, first, kInteractionN);
    const auto ny = InteractionField(d, in.its, first, kInteractionN + 1);
    const auto nz = InteractionField(d, in.its, first, kInteractionN + 2);
    const auto cos_w = hn::Add(hn::Add(hn::Mul(nx, wx), hn::Mul(ny, wy)), hn::Mul(nz, wz));
    const auto emits = hn::And(hn::RebindMask(d, area_i), hn::Gt(cos_w, zero));
    const auto light_row = hn::Mul(light, three_i);
    auto le_r = hn::IfThenElseZero(emits, hn::GatherIndex(d, radiance, light_row));
    auto le_g = hn::IfThenElseZero(emits, hn::GatherIndex(d, radiance, hn::Add(light_row, one_i)));
    auto le_b = hn::IfThenElseZero(emits, hn::GatherIndex(d, radiance, hn::Add(light_row, two_i)));
    if (textured) {
      // AreaLightRadianceAt at the hit's uv, p and prim (Emitted): the texture where the light
      // has one.
      const auto u = InteractionField(d, in.its, first, kInteractionUv);
      const auto v = InteractionField(d, in.its, first, kInteractionUv + 1);
      const auto px = InteractionField(d, in.its, first, kInteractionP);
      const auto py = InteractionField(d, in.its, first, kInteractionP + 1);
      const auto pz = InteractionField(d, in.its, first, kInteractionP + 2);
      const auto prim =
          hn::GatherIndex(di, as_i(in.its), hn::Add(first, hn::Set(di, kInteractionPrim)));
      AreaLightRadiance8(scene, light, u, v, px, py, pz, prim, emits, &le_r, &le_g, &le_b);
    }
    // IsBlack(Le): nothing is added.
    const auto add =
        hn::Not(hn::And(hn::Eq(le_r, zero), hn::And(hn::Eq(le_g, zero), hn::Eq(le_b, zero))));
    if (hn::AllFalse(d, add)) continue;
    // The path's rows of the Vec3f / Color3f columns (prev_p, throughput, L).
    const auto path_row = hn::Mul(path, three_i);
    const auto rows_g = hn::Add(path_row, one_i), rows_b = hn::Add(path_row, two_i);
    auto w = one;
    if (rules.nee) {
      const auto weighed =
          hn::RebindMask(d, hn::Eq(hn::GatherIndex(di, as_i(paths.specular), path), zero_i));
      if (!rules.mis) {
        w = hn::IfThenElse(weighed, zero, one);
      } else {
        // EmitterPdf: EmitterSelectionPmf times AreaLightPdf (triangles sampled by area:
        // AreaToSolidAngle(1 / area, p, n, prev_p)).
        auto pmf = zero;
        if (emitters != 0) {
          pmf = uniform
                    ? hn::Set(d, 1.0f / float(emitters))
                    : hn::GatherIndex(d, selection.pmf.data(),
                                      hn::GatherIndex(di, as_i(selection.slot_area.data()), light));
        }
        const auto area = hn::GatherIndex(d, lights.area.data(), light);
        const float* const prev_p = as_f(paths.prev_p);
        const auto ex = hn::Sub(InteractionField(d, in.its, first, kInteractionP),
                                hn::GatherIndex(d, prev_p, path_row));
        const auto ey = hn::Sub(InteractionField(d, in.its, first, kInteractionP + 1),
                                hn::GatherIndex(d, prev_p, rows_g));
        const auto ez = hn::Sub(InteractionField(d, in.its, first, kInteractionP + 2),
                                hn::GatherIndex(d, prev_p, rows_b));
        auto solid = hn::Gt(zero, zero);
        const auto to_solid =
            AreaToSolidAngle8(d, hn::Div(one, area), ex, ey, ez, nx, ny, nz, &solid);
        const auto area_pdf = hn::IfThenElseZero(hn::And(hn::Gt(area, zero), solid), to_solid);
        const auto prev_pdf = hn::GatherIndex(d, paths.prev_pdf, path);
        w = hn::IfThenElse(weighed, MisWeight8(d, prev_pdf, hn::Mul(pmf, area_pdf), power), one);
      }
    }
    // L += throughput · Le · w, written back in every lane (each row's path is its own).
    const auto l_r = hn::GatherIndex(d, L, path_row);
    const auto l_g = hn::GatherIndex(d, L, rows_g);
    const auto l_b = hn::GatherIndex(d, L, rows_b);
    const auto c_r = hn::Mul(hn::Mul(hn::GatherIndex(d, throughput, path_row), le_r), w);
    const auto c_g = hn::Mul(hn::Mul(hn::GatherIndex(d, throughput, rows_g), le_g), w);
    const auto c_b = hn::Mul(hn::Mul(hn::GatherIndex(d, throughput, rows_b), le_b), w);
    hn::ScatterIndex(hn::IfThenElse(add, hn::Add(l_r, c_r), l_r), d, L, path_row);
    hn::ScatterIndex(hn::IfThenElse(add, hn::Add(l_g, c_g), l_g), d, L, rows_g);
    hn::ScatterIndex(hn::IfThenElse(add, hn::Add(l_b, c_b), l_b), d, L, rows_b);
  }
  // The rows after the last whole vector: the oracle.
  if (k == n) return;
  EmissionBatchInputs rest = in;
  rest.entry = in.entry + k;
  ptlab::AddAreaEmissions(scene, rules, n - k, rest, paths);
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_EMISSION8_INL_H_
