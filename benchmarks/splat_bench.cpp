// Film splatting alone: the scalar oracle (FilmBlock::Splat per sample) against
// simd::SplatSamples, for the samples of a wave in the wavefront's order (row, pixel, sample),
// with Nori's default Gaussian (radius 2, σ 0.5) and a box of radius 0.5. Items are samples.
#include <benchmark/benchmark.h>

#include <vector>

#include "benchmarks/bench_target.h"
#include "engine/core/rng.h"
#include "engine/render/filter.h"
#include "engine/wavefront/splat.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/splat8.h"

namespace ptlab {
namespace {

// A 64 x 16-pixel wave at 8 samples per pixel, jittered in its pixel, and its tile's block
// (the tile plus a border of the radius).
struct Wave {
  std::vector<float> sx, sy, r, g, b;
  FilmSamples View() const {
    return {sx.data(), sy.data(), r.data(), g.data(), b.data(), sx.size()};
  }
};

constexpr int kWaveWidth = 64, kWaveHeight = 16, kSamplesPerPixel = 8;

Wave MakeWave() {
  Wave w;
  Pcg32 rng(3, 7);
  for (int y = 0; y < kWaveHeight; ++y)
    for (int x = 0; x < kWaveWidth; ++x)
      for (int s = 0; s < kSamplesPerPixel; ++s) {
        w.sx.push_back(float(x) + rng.NextFloat()), w.sy.push_back(float(y) + rng.NextFloat());
        w.r.push_back(rng.NextFloat()), w.g.push_back(rng.NextFloat());
        w.b.push_back(rng.NextFloat());
      }
  return w;
}

template <bool kSimd>
void BM_Splat_Wave(benchmark::State& state) {
  using T = FilterDesc::Type;
  const FilterDesc desc =
      state.range(0) == 0 ? FilterDesc{T::kGaussian, 2.0f, 0.5f} : FilterDesc{T::kBox, 0.5f, 0.0f};
  const PixelFilter filter(desc);
  const Wave wave = MakeWave();
  const int border = int(desc.radius) + 1;
  FilmBlock block(-border, -border, kWaveWidth + 2 * border, kWaveHeight + 2 * border);
  for (auto _ : state) {
    if (kSimd)
      simd::SplatSamples(filter, wave.View(), &block);
    else
      SplatSamples(filter, wave.View(), &block);
    benchmark::DoNotOptimize(block.sums().data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(wave.sx.size()));
  state.SetLabel(kSimd ? simd::DispatchedTargetName() : "oracle");
}

BENCHMARK_TEMPLATE(BM_Splat_Wave, false)->Arg(0)->Arg(1);
BENCHMARK_TEMPLATE(BM_Splat_Wave, true)->Arg(0)->Arg(1);

}  // namespace
}  // namespace ptlab
