// The sampler alone: numbers per second of the Sobol' sampler (padded, Owen-scrambled) against
// the PCG32 stream of the independent sampler, for the pattern a path asks for (a new path
// sample, then 2-D and 1-D dimensions), single thread. And the environment map's importance
// sampling batch: the scalar oracle, and the 8-wide batch with and without the CDFs' guide
// tables.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "benchmarks/bench_target.h"
#include "engine/core/rng.h"
#include "engine/image/image.h"
#include "engine/light/environment_map.h"
#include "engine/sampling/sampler.h"
#include "engine/wavefront/camera_paths.h"
#include "engine/wavefront/environment.h"
#include "engine/wavefront/sobol.h"
#include "simd/wavefront/camera_paths8.h"
#include "simd/wavefront/environment8.h"
#include "simd/wavefront/sobol8.h"

namespace ptlab {
namespace {

// One path sample of `dims` dimensions (half 2-D, half 1-D: 1.5 numbers each on average).
template <SamplerType kType>
void BM_Sampler_PathSample(benchmark::State& state) {
  const uint32_t dims = uint32_t(state.range(0));
  uint32_t index = 0;
  float sink = 0;
  for (auto _ : state) {
    PathSampler sampler(kType, 0x1234567ull + (index >> 6), index);
    ++index;
    for (uint32_t d = 0; d < dims; d += 2) {
      const Vec2f u = sampler.Get2D(d);
      sink += u.x + u.y + sampler.Get1D(d + 1);
    }
  }
  benchmark::DoNotOptimize(sink);
  // Items are numbers drawn: 3 per pair of dimensions.
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(dims / 2 * 3));
}

BENCHMARK_TEMPLATE(BM_Sampler_PathSample, SamplerType::kIndependent)->Arg(8)->Arg(32);
BENCHMARK_TEMPLATE(BM_Sampler_PathSample, SamplerType::kSobol)->Arg(8)->Arg(32);

// The wavefront's batch draws: one 2-D dimension for 4096 paths, scalar oracle vs the 8-wide
// kernel (items: numbers, two per row).
template <bool kSimd>
void BM_Sampler_SobolBatch2D(benchmark::State& state) {
  const size_t n = 4096;
  std::vector<uint32_t> seed(n), index(n);
  for (size_t i = 0; i < n; ++i) seed[i] = Hash32(uint32_t(i)), index[i] = uint32_t(i % 64);
  std::vector<float> x(n), y(n);
  uint32_t dim = 0;
  for (auto _ : state) {
    if (kSimd)
      simd::ScrambledSobol2DBatch(seed.data(), index.data(), dim, n, x.data(), y.data());
    else
      ScrambledSobol2DBatch(seed.data(), index.data(), dim, n, x.data(), y.data());
    dim = (dim + 1) & 31;
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(2 * n));
}
BENCHMARK_TEMPLATE(BM_Sampler_SobolBatch2D, false);
BENCHMARK_TEMPLATE(BM_Sampler_SobolBatch2D, true);

// The wavefront's camera paths (the camera_paths slot): 4096 new paths of a 4 × 2-pixel packet
// layout at 16 samples per pixel, independent sampler, scalar oracle vs the SIMD twin (items:
// paths).
template <bool kSimd>
void BM_Sampler_CameraPaths(benchmark::State& state) {
  const size_t n = 4096;
  std::vector<int32_t> px(n), py(n);
  std::vector<uint32_t> sample(n);
  for (size_t i = 0; i < n; ++i) {
    px[i] = int32_t((i / 128) * 4 + i % 4), py[i] = int32_t((i / 4) % 2);
    sample[i] = uint32_t(i / 8 % 16);
  }
  std::vector<PathSampler> sampler(n);
  std::vector<float> sx(n), sy(n);
  std::vector<Vec2f> lens(n);
  const CameraPathInputs in{px.data(), py.data(), sample.data()};
  const CameraPathOutputs out{sampler.data(), sx.data(), sy.data(), lens.data()};
  uint64_t seed = 1;
  for (auto _ : state) {
    if (kSimd)
      simd::StartCameraPaths(SamplerType::kIndependent, seed, 1920, n, in, out);
    else
      StartCameraPaths(SamplerType::kIndependent, seed, 1920, n, in, out);
    ++seed;
    benchmark::DoNotOptimize(sampler.data());
    benchmark::DoNotOptimize(lens.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
}
BENCHMARK_TEMPLATE(BM_Sampler_CameraPaths, false);
BENCHMARK_TEMPLATE(BM_Sampler_CameraPaths, true);

// A 1024 × 512 sky like the demo's sunset, without reading a file: a horizon gradient and a
// small sun 500× brighter (a peaked distribution: most samples land in few bins).
EnvironmentMapTable SkyTable(bool guided) {
  Image sky(1024, 512);
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x) {
      const float up = 1.0f - float(y) / float(sky.height);
      const float dx = float(x - 700), dy = float(y - 230);
      const float sun = dx * dx + dy * dy < 36.0f ? 500.0f : 0.0f;
      sky.Set(x, y, {0.2f + up + sun, 0.3f + up + sun, 0.5f + up + 0.8f * sun});
    }
  EnvironmentMapTable table;
  (void)AddEnvironmentMap(sky, EnvironmentMapDesc{}, "sky", &table);
  if (!guided) table.marginal_guide.clear(), table.conditional_guide.clear();
  return table;
}

// Batches of 4096 environment samples (items: samples), each iteration with other numbers
// (64 batches in turn), so that the map's texels and CDFs are read as a render reads them, not
// from a cache warmed by the same rows.
template <bool kSimd, bool kGuided>
void BM_Environment_SampleBatch(benchmark::State& state) {
  static const EnvironmentMapTable table = SkyTable(kGuided);
  constexpr size_t kRows = 4096, kBatches = 64;
  std::vector<float> u_x(kRows * kBatches), u_y(kRows * kBatches), col(7 * kRows);
  Pcg32 rng(5, 7);
  for (size_t i = 0; i < u_x.size(); ++i) u_x[i] = rng.NextFloat(), u_y[i] = rng.NextFloat();
  const EnvironmentBatchOutputs out{col.data(),
                                    col.data() + kRows,
                                    col.data() + 2 * kRows,
                                    col.data() + 3 * kRows,
                                    col.data() + 4 * kRows,
                                    col.data() + 5 * kRows,
                                    col.data() + 6 * kRows};
  size_t batch = 0;
  for (auto _ : state) {
    const EnvironmentBatchInputs in{u_x.data() + batch * kRows, u_y.data() + batch * kRows};
    batch = (batch + 1) % kBatches;
    if (kSimd) {
      simd::SampleEnvironmentBatch(table, 0, kRows, in, out);
    } else {
      SampleEnvironmentBatch(table, 0, kRows, in, out);
    }
    benchmark::DoNotOptimize(col.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kRows));
}

BENCHMARK_TEMPLATE(BM_Environment_SampleBatch, false, true)
    ->Name("BM_Environment_SampleBatch/scalar");
BENCHMARK_TEMPLATE(BM_Environment_SampleBatch, true, false)
    ->Name("BM_Environment_SampleBatch/simd/binary_search");
BENCHMARK_TEMPLATE(BM_Environment_SampleBatch, true, true)
    ->Name("BM_Environment_SampleBatch/simd/guided");

}  // namespace
}  // namespace ptlab
