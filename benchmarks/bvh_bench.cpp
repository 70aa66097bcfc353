// BVH build time on a ~1M-triangle mesh and single-ray traversal throughput (rays/s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/bvh/bvh.h"
#include "engine/bvh/intersect1.h"
#include "engine/core/ray.h"
#include "engine/core/rng.h"
#include "engine/core/vec.h"
#include "engine/scene/geometry_tables.h"

namespace ptlab {
namespace {

// A bumpy torus (major radius 1, minor 0.35) of 2 * n * n triangles with shared vertices;
// n = 708 gives 1,002,528 triangles.
TriangleTable MakeBumpyTorus(int n) {
  std::vector<Vec3f> v(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float u = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
      const float w = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(n);
      const float r = 0.35f * (1.0f + 0.08f * std::sin(23.0f * u) * std::sin(17.0f * w));
      v[static_cast<size_t>(j) * n + i] = {(1.0f + r * std::cos(w)) * std::cos(u),
                                           (1.0f + r * std::cos(w)) * std::sin(u), r * std::sin(w)};
    }
  }
  TriangleTable t;
  auto at = [&](int i, int j) { return v[static_cast<size_t>(j % n) * n + (i % n)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      t.Append(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      t.Append(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return t;
}

const TriangleTable& BenchMesh() {
  static const TriangleTable mesh = MakeBumpyTorus(708);
  return mesh;
}

const Bvh& BenchBvh() {
  static const Bvh bvh = BuildBvh(BenchMesh());
  return bvh;
}

// Pinhole camera rays, 512 x 512, looking at the torus from above and to the side.
std::vector<Ray> CoherentRays() {
  constexpr int kRes = 512;
  const Vec3f eye{0.0f, -3.0f, 2.0f};
  const Vec3f forward = Normalize(Vec3f{0, 0, 0} - eye);
  const Vec3f right = Normalize(Cross(forward, {0, 0, 1}));
  const Vec3f up = Cross(right, forward);
  std::vector<Ray> rays;
  rays.reserve(kRes * kRes);
  for (int y = 0; y < kRes; ++y) {
    for (int x = 0; x < kRes; ++x) {
      const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / kRes - 1.0f) * 0.45f;
      const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / kRes) * 0.45f;
      rays.push_back({eye, Normalize(forward + right * sx + up * sy)});
    }
  }
  return rays;
}

// Bounce-like rays: origins on the torus' bounding region, uniform random directions.
std::vector<Ray> IncoherentRays() {
  Pcg32 rng(42, 1);
  std::vector<Ray> rays(1 << 18);
  for (Ray& r : rays) {
    r.o = {2.7f * rng.NextFloat() - 1.35f, 2.7f * rng.NextFloat() - 1.35f,
           0.8f * rng.NextFloat() - 0.4f};
    const float z = 1.0f - 2.0f * rng.NextFloat();
    const float s = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * rng.NextFloat();
    r.d = {s * std::cos(phi), s * std::sin(phi), z};
  }
  return rays;
}

void BM_Bvh_Build(benchmark::State& state) {
  const TriangleTable& mesh = BenchMesh();
  for (auto _ : state) {
    Bvh bvh = BuildBvh(mesh);
    benchmark::DoNotOptimize(bvh.nodes.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.size()));
  state.counters["triangles"] = static_cast<double>(mesh.size());
  state.counters["nodes"] = static_cast<double>(BenchBvh().nodes.size());
}
BENCHMARK(BM_Bvh_Build)->Unit(benchmark::kMillisecond);

void RunIntersect1(benchmark::State& state, const std::vector<Ray>& rays) {
  const Bvh& bvh = BenchBvh();
  int64_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : rays) {
      Hit hit;
      hits += Intersect1(bvh, r, &hit);
      benchmark::DoNotOptimize(hit);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rays.size()));
  state.counters["hit_fraction"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations() * rays.size());
}

void BM_Bvh_Intersect1(benchmark::State& state) {
  static const std::vector<Ray> rays = CoherentRays();
  RunIntersect1(state, rays);
}
BENCHMARK(BM_Bvh_Intersect1)->Unit(benchmark::kMillisecond);

void BM_Bvh_Intersect1_Incoherent(benchmark::State& state) {
  static const std::vector<Ray> rays = IncoherentRays();
  RunIntersect1(state, rays);
}
BENCHMARK(BM_Bvh_Intersect1_Incoherent)->Unit(benchmark::kMillisecond);

void BM_Bvh_Occluded1_Incoherent(benchmark::State& state) {
  static const std::vector<Ray> rays = IncoherentRays();
  const Bvh& bvh = BenchBvh();
  for (auto _ : state) {
    for (const Ray& r : rays) benchmark::DoNotOptimize(Occluded1(bvh, r));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rays.size()));
}
BENCHMARK(BM_Bvh_Occluded1_Incoherent)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ptlab
