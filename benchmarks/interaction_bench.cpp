// Scalar oracle vs Highway SIMD throughput of the wavefront's interaction slot
// (simd::MakeInteractionBatch into rows: SurfaceInteraction and wo per hit) on the shared Nori
// scenes, same fixed hits for both: random triangles, barycentrics and unit directions.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "benchmarks/bench_target.h"
#include "engine/core/rng.h"
#include "engine/io/scene_file.h"
#include "engine/wavefront/interaction.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/interaction8.h"

namespace ptlab {
namespace {

// One wave's worth of hits (a wave's queue is of this order), all lanes hitting.
constexpr size_t kPackets = 256;

const bool kContext = [] {
  benchmark::AddCustomContext("highway_target", simd::DispatchedTargetName());
  benchmark::AddCustomContext("hits", std::to_string(kPackets * kPacketWidth));
  return true;
}();

struct Batch {
  Scene scene;
  simd::TriangleRows rows = simd::BuildTriangleRows(scene);
  std::vector<RayPacket8> rays = std::vector<RayPacket8>(kPackets);
  std::vector<HitPacket8> hits = std::vector<HitPacket8>(kPackets);
  std::vector<Mask8> mask = std::vector<Mask8>(kPackets, kAllLanes);
  std::vector<SurfaceInteraction> its = std::vector<SurfaceInteraction>(kPackets * kPacketWidth);
  std::vector<Vec3f> wo = std::vector<Vec3f>(kPackets * kPacketWidth);
};

// Null when the shared data is missing.
Batch* LoadBatch(const std::string& relative) {
  const std::string path = std::string(PTLAB_SOURCE_DIR) + "/../shared/data/" + relative;
  if (!std::filesystem::exists(path)) return nullptr;
  StatusOr<Scene> loaded = LoadSceneFile(path);
  if (!loaded.ok() || loaded->triangles.size() == 0) return nullptr;
  auto* b = new Batch{std::move(*loaded)};
  const uint32_t tris = uint32_t(b->scene.triangles.size());
  Pcg32 rng(11, 13);
  for (size_t k = 0; k < kPackets; ++k) {
    for (int j = 0; j < 8; ++j) {
      Vec3f d;
      do {
        d = {rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1};
      } while (Dot(d, d) < 1e-2f || Dot(d, d) > 1);
      SetLaneRay(&b->rays[k], j, Ray{{0, 0, 0}, Normalize(d)});
      float b1 = rng.NextFloat(), b2 = rng.NextFloat();
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      SetLaneHit(&b->hits[k], j, 1.0f, b1, b2, rng.NextUint() % tris);
    }
  }
  return b;
}

void BM_Interaction_Rows(benchmark::State& state, const char* relative, bool simd) {
  static Batch* const veach = LoadBatch("nori/epfl/scenes/pa5/veach_mi/veach_mis.xml");
  static Batch* const table = LoadBatch("nori/epfl/scenes/pa5/table/table_mis.xml");
  Batch* b = std::string(relative) == "veach" ? veach : table;
  if (b == nullptr) return state.SkipWithError("shared data not found");
  const InteractionRows out{b->its.data(), b->wo.data()};
  std::vector<uint32_t> entries(kPackets * kPacketWidth), area(kPackets * kPacketWidth);
  HitLists lists{entries.data(), area.data()};
  for (auto _ : state) {
    if (simd) {
      simd::MakeInteractionBatch(b->scene, b->rows, b->rays.data(), b->hits.data(), b->mask.data(),
                                 kPackets, out, &lists);
    } else {
      MakeInteractionBatch(b->scene, b->rays.data(), b->hits.data(), b->mask.data(), kPackets, out,
                           &lists);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations() * kPackets * kPacketWidth));
}
BENCHMARK_CAPTURE(BM_Interaction_Rows, oracle_veach, "veach", false);
BENCHMARK_CAPTURE(BM_Interaction_Rows, simd_veach, "veach", true);
BENCHMARK_CAPTURE(BM_Interaction_Rows, oracle_table, "table", false);
BENCHMARK_CAPTURE(BM_Interaction_Rows, simd_table, "table", true);

}  // namespace
}  // namespace ptlab
