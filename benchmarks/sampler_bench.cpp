// The sampler alone: numbers per second of the Sobol' sampler (padded, Owen-scrambled) against
// the PCG32 stream of the independent sampler, for the pattern a path asks for (a new path
// sample, then 2-D and 1-D dimensions), single thread.
#include <cstdint>

#include <benchmark/benchmark.h>

#include "engine/sampling/sampler.h"
#include "simd/sampler8.h"
#include <vector>

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
    if (kSimd) simd::ScrambledSobol2DBatch(seed.data(), index.data(), dim, n, x.data(), y.data());
    else ScrambledSobol2DBatch(seed.data(), index.data(), dim, n, x.data(), y.data());
    dim = (dim + 1) & 31;
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(2 * n));
}
BENCHMARK_TEMPLATE(BM_Sampler_SobolBatch2D, false);
BENCHMARK_TEMPLATE(BM_Sampler_SobolBatch2D, true);

}  // namespace
}  // namespace ptlab
