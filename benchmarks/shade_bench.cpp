// Scalar oracle vs Highway SIMD throughput of the shading kernels, on the same fixed inputs.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "benchmarks/bench_target.h"
#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/bsdf/plastic_precompute.h"
#include "engine/wavefront/bsdf.h"
#include "engine/core/rng.h"
#include "engine/sampling/warp.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/bsdf8.h"

namespace ptlab {
namespace {

// One batch: small enough to stay in L2, large enough to amortise the call.
constexpr size_t kBatch = 4096;

const bool kContext = [] {
  benchmark::AddCustomContext("highway_target", simd::DispatchedTargetName());
  benchmark::AddCustomContext("batch", std::to_string(kBatch));
  return true;
}();

Vec3f DirectionWithCos(float c, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  return {s * std::cos(phi), s * std::sin(phi), c};
}

// Fixed inputs: α log-uniform in [1e-3, 1], wo on the upper hemisphere, wi half near-specular
// (so D is not trivially 0) and half cosine-distributed, u uniform; Fresnel inputs uniform.
struct Inputs {
  std::vector<float> alpha, wo_x, wo_y, wo_z, wi_x, wi_y, wi_z, u_lobe, u_x, u_y;
  std::vector<float> cos_i, cos_signed, eta, k, eta_d;
  std::vector<MaterialRef> mixed;
  std::vector<uint32_t> index[kMaterialTagCount];
  MaterialTables tables;

  Inputs() {
    Pcg32 rng(42, 54);
    for (int i = 0; i < 64; ++i) {
      const float a = rng.NextFloat();
      tables.AddDiffuse({a, 0.5f * a, 0.25f});
      tables.AddMirror();
      tables.AddDielectric(1.3f + 0.4f * rng.NextFloat(), 1.0f);
      Color3f e, kk;
      const char* names[] = {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Si", "none"};
      LookupConductorPreset(names[i % 8], &e, &kk);
      tables.AddConductor(std::pow(10.0f, -3.0f * rng.NextFloat()), e, kk);
      tables.AddRoughPlastic(std::pow(10.0f, -3.0f * rng.NextFloat()), 1.5f, 1.0f,
                             {0.5f * a, 0.3f, 0.2f});
      // matA: GGX and Beckmann rough glass, visible normals.
      const float ad = std::pow(10.0f, -2.0f * rng.NextFloat());
      tables.AddRoughDielectric(ad, ad, uint8_t(kMicrofacetSampleVisible | (i % 2)), 1.5f, 1.0f);
    }
    // matB: 64 rows each of the smooth plastic, the thin dielectric and a blend (of a diffuse
    // and a plastic), from their own stream so the rows above stay as they were.
    Pcg32 rng_b(43, 55);
    for (int i = 0; i < 64; ++i) {
      PlasticDesc d;
      d.int_ior = 1.3f + 0.4f * rng_b.NextFloat(), d.ext_ior = 1.0f, d.nonlinear = i % 2 == 0;
      d.diffuse = {rng_b.NextFloat(), 0.3f, 0.2f};
      const MaterialRef p = tables.AddPlastic(*MakePlasticRow(d));
      tables.AddThinDielectric(1.3f + 0.4f * rng_b.NextFloat());
      tables.AddBlend(rng_b.NextFloat(), MaterialRef::Make(MaterialTag::kDiffuse, uint32_t(i)), p);
    }
    Pcg32 rng_index(44, 56);
    for (size_t i = 0; i < kBatch; ++i) {
      const float al = std::pow(10.0f, -3.0f * rng.NextFloat());
      const float c = 0.05f + 0.95f * rng.NextFloat();
      const Vec3f wo = DirectionWithCos(c, 2 * kPi * rng.NextFloat());
      const float u1 = rng.NextFloat(), u2 = rng.NextFloat();
      const Vec3f wi = i % 2 ? ReflectAbout(wo, SampleBeckmannNormal(al, {u1, u2}))
                             : SampleCosineHemisphere({u1, u2});
      alpha.push_back(al);
      wo_x.push_back(wo.x), wo_y.push_back(wo.y), wo_z.push_back(wo.z);
      wi_x.push_back(wi.x), wi_y.push_back(wi.y), wi_z.push_back(wi.z);
      u_lobe.push_back(rng.NextFloat()), u_x.push_back(rng.NextFloat());
      u_y.push_back(rng.NextFloat());
      cos_i.push_back(rng.NextFloat());
      cos_signed.push_back(2.0f * rng.NextFloat() - 1.0f);
      eta.push_back(0.05f + 3.0f * rng.NextFloat());
      k.push_back(0.5f + 7.0f * rng.NextFloat());
      eta_d.push_back(1.2f + 0.6f * rng.NextFloat());
      // The five original models (the mixed benchmark is kept as it was before matB's tags).
      const int tag = int(rng.NextFloat() * 5) % 5;
      mixed.push_back(MaterialRef::Make(static_cast<MaterialTag>(tag), i % 64));
      // Tags from 5 on draw from their own stream (the inputs of tags 0-4 stay as they were).
      for (int t = 0; t < kMaterialTagCount; ++t)
        index[t].push_back(uint32_t((t < 5 ? rng : rng_index).NextFloat() * 64) % 64);
    }
  }
  DirectionArrays Wo() const { return {wo_x.data(), wo_y.data(), wo_z.data()}; }
  DirectionArrays Wi() const { return {wi_x.data(), wi_y.data(), wi_z.data()}; }
  ShadeInputs Shade() const {
    ShadeInputs in;
    in.wo = Wo(), in.wl = Wi();
    in.u_lobe = u_lobe.data(), in.u_x = u_x.data(), in.u_y = u_y.data();
    return in;
  }
};

const Inputs& GetInputs() {
  static const Inputs* inputs = new Inputs();
  return *inputs;
}

struct Outputs {
  std::vector<float> v[12] = {};
  Outputs() {
    for (auto& c : v) c.resize(kBatch);
  }
  ShadeOutputs Shade() {
    ShadeOutputs o;
    o.f = {v[0].data(), v[1].data(), v[2].data()};
    o.pdf_l = v[3].data();
    o.wi = {v[4].data(), v[5].data(), v[6].data()};
    o.weight = {v[7].data(), v[8].data(), v[9].data()};
    o.pdf = v[10].data();
    o.eta = v[11].data();
    return o;
  }
};

template <bool kSimd>
void BM_Shade8_BeckmannEvalPdf(benchmark::State& state) {
  const Inputs& in = GetInputs();
  Outputs out;
  for (auto _ : state) {
    if (kSimd) {
      simd::BeckmannEvalPdfBatch(in.alpha.data(), in.Wo(), in.Wi(), kBatch, out.v[0].data(),
                                 out.v[1].data());
    } else {
      ptlab::BeckmannEvalPdfBatch(in.alpha.data(), in.Wo(), in.Wi(), kBatch, out.v[0].data(),
                                  out.v[1].data());
    }
    benchmark::DoNotOptimize(out.v[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

template <bool kSimd>
void BM_Shade8_BeckmannSample(benchmark::State& state) {
  const Inputs& in = GetInputs();
  Outputs out;
  const DirectionOutArrays wi{out.v[0].data(), out.v[1].data(), out.v[2].data()};
  for (auto _ : state) {
    if (kSimd) {
      simd::SampleBeckmannReflectionBatch(in.alpha.data(), in.Wo(), in.u_x.data(), in.u_y.data(),
                                          kBatch, wi, out.v[3].data());
    } else {
      ptlab::SampleBeckmannReflectionBatch(in.alpha.data(), in.Wo(), in.u_x.data(), in.u_y.data(),
                                           kBatch, wi, out.v[3].data());
    }
    benchmark::DoNotOptimize(out.v[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

template <bool kSimd>
void BM_Shade8_ConductorFresnel(benchmark::State& state) {
  const Inputs& in = GetInputs();
  Outputs out;
  for (auto _ : state) {
    if (kSimd) {
      simd::ConductorFresnelBatch(in.cos_i.data(), in.eta.data(), in.k.data(), kBatch,
                                  out.v[0].data());
    } else {
      ptlab::ConductorFresnelBatch(in.cos_i.data(), in.eta.data(), in.k.data(), kBatch,
                                   out.v[0].data());
    }
    benchmark::DoNotOptimize(out.v[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

template <bool kSimd>
void BM_Shade8_DielectricFresnel(benchmark::State& state) {
  const Inputs& in = GetInputs();
  Outputs out;
  for (auto _ : state) {
    if (kSimd) {
      simd::DielectricFresnelBatch(in.cos_signed.data(), in.eta_d.data(), kBatch, out.v[0].data(),
                                   out.v[1].data());
    } else {
      ptlab::DielectricFresnelBatch(in.cos_signed.data(), in.eta_d.data(), kBatch, out.v[0].data(),
                                    out.v[1].data());
    }
    benchmark::DoNotOptimize(out.v[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

// The full per-material shade step (eval + pdf at a light direction, and a sample) for one
// material tag (state.range(0)).
template <bool kSimd>
void BM_Shade8_ShadeBatch(benchmark::State& state) {
  const Inputs& in = GetInputs();
  const MaterialTag tag = static_cast<MaterialTag>(state.range(0));
  const char* names[] = {"diffuse", "mirror", "dielectric", "conductor", "rough_plastic",
                         "rough_dielectric",    "tag6",   "plastic",    "thin_dielectric", "blend"};
  state.SetLabel(names[state.range(0)]);
  Outputs out;
  const ShadeOutputs o = out.Shade();
  const uint32_t* index = in.index[state.range(0)].data();
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeBatch(in.tables, tag, index, kBatch, in.Shade(), o);
    } else {
      ptlab::ShadeBatch(in.tables, tag, index, kBatch, in.Shade(), o);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

// The two calls a render makes, each on its own: sampling only (the wavefront's bsdf slot:
// range(1) = 0) and evaluation only at a light direction (its area_request slot: range(1) =
// 1), for material tag range(0): plastic (7) and blend (9).
template <bool kSimd>
void BM_Shade8_RenderCall(benchmark::State& state) {
  const Inputs& in = GetInputs();
  const MaterialTag tag = static_cast<MaterialTag>(state.range(0));
  const bool sample = state.range(1) == 0;
  state.SetLabel(std::string(tag == MaterialTag::kBlend ? "blend" : "plastic") +
                 (sample ? " sample" : " eval"));
  ShadeInputs call = in.Shade();
  if (sample) {
    call.wl = {};
  } else {
    call.u_lobe = call.u_x = call.u_y = nullptr;
  }
  Outputs out;
  const ShadeOutputs o = out.Shade();
  const uint32_t* index = in.index[state.range(0)].data();
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeBatch(in.tables, tag, index, kBatch, call, o);
    } else {
      ptlab::ShadeBatch(in.tables, tag, index, kBatch, call, o);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

// The whole shading stage on hits with mixed materials: partition, per-tag batches, scatter.
template <bool kSimd>
void BM_Shade8_ShadeHitsMixed(benchmark::State& state) {
  const Inputs& in = GetInputs();
  Outputs out;
  const ShadeOutputs o = out.Shade();
  ShadeScratch scratch;
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeHits(in.tables, in.mixed.data(), kBatch, in.Shade(), o, &scratch);
    } else {
      ptlab::ShadeHits(in.tables, in.mixed.data(), kBatch, in.Shade(), o, &scratch);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

BENCHMARK_TEMPLATE(BM_Shade8_BeckmannEvalPdf, false)->Name("BM_Shade8_BeckmannEvalPdf/scalar");
BENCHMARK_TEMPLATE(BM_Shade8_BeckmannEvalPdf, true)->Name("BM_Shade8_BeckmannEvalPdf/simd");
BENCHMARK_TEMPLATE(BM_Shade8_BeckmannSample, false)->Name("BM_Shade8_BeckmannSample/scalar");
BENCHMARK_TEMPLATE(BM_Shade8_BeckmannSample, true)->Name("BM_Shade8_BeckmannSample/simd");
BENCHMARK_TEMPLATE(BM_Shade8_ConductorFresnel, false)->Name("BM_Shade8_ConductorFresnel/scalar");
BENCHMARK_TEMPLATE(BM_Shade8_ConductorFresnel, true)->Name("BM_Shade8_ConductorFresnel/simd");
BENCHMARK_TEMPLATE(BM_Shade8_DielectricFresnel, false)->Name("BM_Shade8_DielectricFresnel/scalar");
BENCHMARK_TEMPLATE(BM_Shade8_DielectricFresnel, true)->Name("BM_Shade8_DielectricFresnel/simd");
BENCHMARK_TEMPLATE(BM_Shade8_ShadeBatch, false)
    ->Name("BM_Shade8_ShadeBatch/scalar")
    ->DenseRange(0, 5);
BENCHMARK_TEMPLATE(BM_Shade8_ShadeBatch, true)->Name("BM_Shade8_ShadeBatch/simd")->DenseRange(0, 5);
// matB: plastic (7), thin dielectric (8), blend (9).
BENCHMARK_TEMPLATE(BM_Shade8_ShadeBatch, false)->Name("BM_Shade8_ShadeBatch/scalar")->DenseRange(7, 9);
BENCHMARK_TEMPLATE(BM_Shade8_ShadeBatch, true)->Name("BM_Shade8_ShadeBatch/simd")->DenseRange(7, 9);
BENCHMARK_TEMPLATE(BM_Shade8_RenderCall, false)
    ->Name("BM_Shade8_RenderCall/scalar")
    ->ArgsProduct({{7, 9}, {0, 1}});
BENCHMARK_TEMPLATE(BM_Shade8_RenderCall, true)
    ->Name("BM_Shade8_RenderCall/simd")
    ->ArgsProduct({{7, 9}, {0, 1}});
BENCHMARK_TEMPLATE(BM_Shade8_ShadeHitsMixed, false)->Name("BM_Shade8_ShadeHitsMixed/scalar");
BENCHMARK_TEMPLATE(BM_Shade8_ShadeHitsMixed, true)->Name("BM_Shade8_ShadeHitsMixed/simd");

// matA: the Mitsuba microfacet kernels per sample (eval + pdf at a light direction and a
// sample), one table per case: range 0 rough conductor Beckmann, 1 rough conductor GGX (both
// visible normals, 1 in 3 rows 10:1 anisotropic), 2 rough dielectric Beckmann, 3 rough
// dielectric GGX, 4 smooth conductor; the directions and numbers of the inputs above.
struct MicrofacetInputs {
  MaterialTables tables[5];
  std::vector<uint32_t> index;
  MicrofacetInputs() {
    Pcg32 rng(7, 77);
    const char* names[] = {"Au", "Ag", "Al", "Cu", "Fe", "Na", "Si", "none"};
    for (int i = 0; i < 64; ++i) {
      Color3f e, kk;
      LookupConductorPreset(names[i % 8], &e, &kk);
      const float a = std::pow(10.0f, -2.0f * rng.NextFloat());
      const float av = i % 3 == 0 ? 0.1f * a : a;
      tables[0].AddRoughConductor(a, av, kMicrofacetSampleVisible, e, kk, {1, 1, 1});
      tables[1].AddRoughConductor(a, av, uint8_t(kMicrofacetSampleVisible | kMicrofacetGgx), e, kk,
                                  {1, 1, 1});
      tables[2].AddRoughDielectric(a, av, kMicrofacetSampleVisible, 1.5f, 1.0f);
      tables[3].AddRoughDielectric(a, av, uint8_t(kMicrofacetSampleVisible | kMicrofacetGgx), 1.5f,
                                   1.0f);
      tables[4].AddSmoothConductor(e, kk);
    }
    for (size_t i = 0; i < kBatch; ++i) index.push_back(uint32_t(rng.NextFloat() * 64) % 64);
  }
};

const MicrofacetInputs& GetMicrofacetInputs() {
  static const MicrofacetInputs in;
  return in;
}

template <bool kSimd>
void BM_Shade8_Microfacet(benchmark::State& state) {
  const Inputs& in = GetInputs();
  const MicrofacetInputs& mf = GetMicrofacetInputs();
  const int c = int(state.range(0));
  const char* labels[] = {"rough_conductor_beckmann", "rough_conductor_ggx",
                          "rough_dielectric_beckmann", "rough_dielectric_ggx", "smooth_conductor"};
  state.SetLabel(labels[c]);
  const MaterialTag tag = c < 2   ? MaterialTag::kConductor
                          : c < 4 ? MaterialTag::kRoughDielectric
                                  : MaterialTag::kMirror;
  Outputs out;
  const ShadeOutputs o = out.Shade();
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeBatch(mf.tables[c], tag, mf.index.data(), kBatch, in.Shade(), o);
    } else {
      ptlab::ShadeBatch(mf.tables[c], tag, mf.index.data(), kBatch, in.Shade(), o);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

BENCHMARK_TEMPLATE(BM_Shade8_Microfacet, false)
    ->Name("BM_Shade8_Microfacet/scalar")
    ->DenseRange(0, 4);
BENCHMARK_TEMPLATE(BM_Shade8_Microfacet, true)->Name("BM_Shade8_Microfacet/simd")->DenseRange(0, 4);

// principled: Mitsuba's principled BSDF per sample (eval + pdf at a light direction and a
// sample), one table per case: range 0 an opaque dielectric/metal mix with clearcoat and sheen,
// 1 a rough glass (specular transmission 1), 2 every parameter random, 3 principledthin with
// every parameter random (diff_trans in [0, 2]); the directions and numbers of the inputs above.
struct PrincipledInputs {
  MaterialTables tables[4];
  std::vector<uint32_t> index;
  PrincipledInputs() {
    Pcg32 rng(8, 88);
    for (int i = 0; i < 64; ++i) {
      PrincipledRow opaque, glass, mixed;
      opaque.base_color = glass.base_color = {rng.NextFloat(), 0.5f, 0.25f};
      opaque.value[kPrincipledRoughness] = glass.value[kPrincipledRoughness] = rng.NextFloat();
      opaque.value[kPrincipledMetallic] = rng.NextFloat();
      opaque.value[kPrincipledClearcoat] = 0.5f, opaque.value[kPrincipledSheen] = 0.5f;
      opaque.value[kPrincipledSpecTint] = 0.3f;
      glass.value[kPrincipledSpecTrans] = 1.0f;
      mixed.base_color = {rng.NextFloat(), rng.NextFloat(), rng.NextFloat()};
      for (int k = 0; k < kPrincipledDiffTrans; ++k) mixed.value[k] = rng.NextFloat();
      mixed.value[kPrincipledEta] = 1.2f + 0.6f * rng.NextFloat();
      tables[0].AddPrincipled(opaque), tables[1].AddPrincipled(glass);
      tables[2].AddPrincipled(mixed);
      mixed.value[kPrincipledDiffTrans] = 2.0f * rng.NextFloat();
      tables[3].AddPrincipled(mixed, /*thin=*/true);
    }
    for (size_t i = 0; i < kBatch; ++i) index.push_back(uint32_t(rng.NextFloat() * 64) % 64);
  }
};

template <bool kSimd>
void BM_Shade8_Principled(benchmark::State& state) {
  const Inputs& in = GetInputs();
  static const PrincipledInputs pr;
  const int c = int(state.range(0));
  const char* labels[] = {"opaque", "glass", "random", "thin_random"};
  state.SetLabel(labels[c]);
  const MaterialTag tag = c < 3 ? MaterialTag::kPrincipled : MaterialTag::kPrincipledThin;
  Outputs out;
  const ShadeOutputs o = out.Shade();
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeBatch(pr.tables[c], tag, pr.index.data(), kBatch,
                       in.Shade(), o);
    } else {
      ptlab::ShadeBatch(pr.tables[c], tag, pr.index.data(), kBatch,
                        in.Shade(), o);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

BENCHMARK_TEMPLATE(BM_Shade8_Principled, false)
    ->Name("BM_Shade8_Principled/scalar")
    ->DenseRange(0, 3);
BENCHMARK_TEMPLATE(BM_Shade8_Principled, true)->Name("BM_Shade8_Principled/simd")->DenseRange(0, 3);

// plastic8: Mitsuba's roughplastic (the plastic tag's rough rows, PlasticRoughEvalPdf /
// PlasticRoughSample) per sample (eval + pdf at a light direction and a sample): range 0 64
// Beckmann rows, 1 64 GGX rows (α log-uniform in [1e-2, 1], η in [1.3, 1.7], nonlinear every
// other row); the directions and numbers of the inputs above.
struct PlasticRoughInputs {
  MaterialTables tables[2];
  std::vector<uint32_t> index;
  PlasticRoughInputs() {
    Pcg32 rng(9, 39);
    for (int i = 0; i < 64; ++i) {
      PlasticDesc d;
      d.alpha = std::pow(10.0f, -2.0f * rng.NextFloat());
      d.int_ior = 1.3f + 0.4f * rng.NextFloat(), d.ext_ior = 1.0f, d.nonlinear = i % 2 == 0;
      d.diffuse = {rng.NextFloat(), 0.3f, 0.2f};
      d.distribution = CoatingDistribution::kBeckmann;
      tables[0].AddPlastic(*MakePlasticRow(d));
      d.distribution = CoatingDistribution::kGgx;
      tables[1].AddPlastic(*MakePlasticRow(d));
    }
    for (size_t i = 0; i < kBatch; ++i) index.push_back(uint32_t(rng.NextFloat() * 64) % 64);
  }
};

template <bool kSimd>
void BM_Shade8_PlasticRough(benchmark::State& state) {
  const Inputs& in = GetInputs();
  static const PlasticRoughInputs pr;
  const int c = int(state.range(0));
  const char* labels[] = {"rough_plastic_beckmann", "rough_plastic_ggx"};
  state.SetLabel(labels[c]);
  Outputs out;
  const ShadeOutputs o = out.Shade();
  for (auto _ : state) {
    if (kSimd) {
      simd::ShadeBatch(pr.tables[c], MaterialTag::kPlastic, pr.index.data(), kBatch, in.Shade(),
                       o);
    } else {
      ptlab::ShadeBatch(pr.tables[c], MaterialTag::kPlastic, pr.index.data(), kBatch, in.Shade(),
                        o);
    }
    benchmark::DoNotOptimize(out.v[10].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

BENCHMARK_TEMPLATE(BM_Shade8_PlasticRough, false)
    ->Name("BM_Shade8_PlasticRough/scalar")
    ->DenseRange(0, 1);
BENCHMARK_TEMPLATE(BM_Shade8_PlasticRough, true)
    ->Name("BM_Shade8_PlasticRough/simd")
    ->DenseRange(0, 1);

}  // namespace
}  // namespace ptlab
