// The sampler alone: numbers per second of the Sobol' sampler (padded, Owen-scrambled) against
// the PCG32 stream of the independent sampler, for the pattern a path asks for (a new path
// sample, then 2-D and 1-D dimensions), single thread.
#include <cstdint>

#include <benchmark/benchmark.h>

#include "engine/sampling/sampler.h"

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

}  // namespace
}  // namespace ptlab
