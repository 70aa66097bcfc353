// Scalar oracle vs Highway SIMD throughput of the area-light sampling kernel
// (simd::SampleAreaLightBatch) and of the area-light requests' finish
// (simd::AreaEmitterRequestBatch) on the shared Nori scenes' lights, same fixed inputs for both.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "benchmarks/bench_target.h"
#include "engine/core/rng.h"
#include "engine/io/scene_file.h"
#include "engine/wavefront/area_light.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/area_light8.h"
#include "simd/wavefront/area_request8.h"
#include "tests/simd/area_request_rows.h"

namespace ptlab {
namespace {

// One wave's worth of area-light picks (the render's batches are of this order).
constexpr size_t kBatch = 2048;

const bool kContext = [] {
  benchmark::AddCustomContext("highway_target", simd::DispatchedTargetName());
  benchmark::AddCustomContext("batch", std::to_string(kBatch));
  return true;
}();

// A scene's lights with fixed rows: random light, reference point in the scene's box, u.
struct Batch {
  Scene scene;
  simd::TriangleRows rows = simd::BuildTriangleRows(scene);
  std::vector<uint32_t> light;
  std::vector<float> ref_x, ref_y, ref_z, u_x, u_y;
  std::vector<std::vector<float>> col = std::vector<std::vector<float>>(10);
  AreaLightBatchInputs In() const {
    return {light.data(), ref_x.data(), ref_y.data(), ref_z.data(), u_x.data(), u_y.data()};
  }
  AreaLightBatchOutputs Out() {
    for (auto& c : col) c.resize(kBatch);
    return {col[0].data(), col[1].data(), col[2].data(), col[3].data(), col[4].data(),
            col[5].data(), col[6].data(), col[7].data(), col[8].data(), col[9].data()};
  }
};

// Null when the shared data is missing.
Batch* LoadBatch(const std::string& relative) {
  const std::string path = std::string(PTLAB_SOURCE_DIR) + "/../shared/data/" + relative;
  if (!std::filesystem::exists(path)) return nullptr;
  StatusOr<Scene> loaded = LoadSceneFile(path);
  if (!loaded.ok() || loaded->area_lights.size() == 0) return nullptr;
  auto* b = new Batch{std::move(*loaded)};
  const TriangleTable& t = b->scene.triangles;
  Vec3f lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (size_t i = 0; i < t.v0_x.size(); ++i) lo = Min(lo, t.V0(i)), hi = Max(hi, t.V0(i));
  Pcg32 rng(3, 5);
  for (size_t i = 0; i < kBatch; ++i) {
    b->light.push_back(rng.NextUint() % uint32_t(b->scene.area_lights.size()));
    b->ref_x.push_back(lo.x + (hi.x - lo.x) * rng.NextFloat());
    b->ref_y.push_back(lo.y + (hi.y - lo.y) * rng.NextFloat());
    b->ref_z.push_back(lo.z + (hi.z - lo.z) * rng.NextFloat());
    b->u_x.push_back(rng.NextFloat()), b->u_y.push_back(rng.NextFloat());
  }
  return b;
}

void BM_Emitter_AreaLight(benchmark::State& state, const char* relative, bool simd) {
  static Batch* const veach = LoadBatch("nori/epfl/scenes/pa5/veach_mi/veach_mis.xml");
  static Batch* const table = LoadBatch("nori/epfl/scenes/pa5/table/table_mis.xml");
  Batch* b = std::string(relative) == "veach" ? veach : table;
  if (b == nullptr) return state.SkipWithError("shared data not found");
  const AreaLightBatchOutputs o = b->Out();
  for (auto _ : state) {
    if (simd) {
      simd::SampleAreaLightBatch(b->scene, b->rows, TriangleSampling::kArea, kBatch, b->In(), o);
    } else {
      SampleAreaLightBatch(b->scene, TriangleSampling::kArea, kBatch, b->In(), o);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations() * kBatch));
}
BENCHMARK_CAPTURE(BM_Emitter_AreaLight, oracle_veach, "veach", false);
BENCHMARK_CAPTURE(BM_Emitter_AreaLight, simd_veach, "veach", true);
BENCHMARK_CAPTURE(BM_Emitter_AreaLight, oracle_table, "table", false);
BENCHMARK_CAPTURE(BM_Emitter_AreaLight, simd_table, "table", true);

// One wave's area-light requests of one material (shading points on the scene's triangles,
// light samples drawn from them), MIS with the power heuristic as the *_mis scenes have it.
struct RequestBatch {
  Scene scene;
  test::AreaRequestRows rows;
  test::AreaRequestColumns out{kBatch};
};

RequestBatch* LoadRequestBatch(const std::string& relative, MaterialTag tag) {
  const std::string path = std::string(PTLAB_SOURCE_DIR) + "/../shared/data/" + relative;
  if (!std::filesystem::exists(path)) return nullptr;
  StatusOr<Scene> loaded = LoadSceneFile(path);
  if (!loaded.ok() || loaded->area_lights.size() == 0) return nullptr;
  auto* b = new RequestBatch{std::move(*loaded)};
  test::AddRequestMaterials(&b->scene);
  Pcg32 rng(3, 5);
  b->rows = test::MakeAreaRequestRows(b->scene, tag, kBatch, false, rng);
  return b;
}

void BM_Emitter_AreaRequest(benchmark::State& state, const char* relative, MaterialTag tag,
                            bool simd) {
  RequestBatch* b = LoadRequestBatch(std::string("nori/epfl/scenes/pa5/") + relative, tag);
  if (b == nullptr) return state.SkipWithError("shared data not found");
  const AreaRequestOutputs o = b->out.Out();
  for (auto _ : state) {
    if (simd) {
      simd::AreaEmitterRequestBatch(b->scene, tag, true, kBatch, b->rows.In(), o);
    } else {
      AreaEmitterRequestBatch(b->scene, tag, true, kBatch, b->rows.In(), o);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations() * kBatch));
  delete b;
}
BENCHMARK_CAPTURE(BM_Emitter_AreaRequest, oracle_veach_rough_plastic, "veach_mi/veach_mis.xml",
                  MaterialTag::kRoughPlastic, false);
BENCHMARK_CAPTURE(BM_Emitter_AreaRequest, simd_veach_rough_plastic, "veach_mi/veach_mis.xml",
                  MaterialTag::kRoughPlastic, true);
BENCHMARK_CAPTURE(BM_Emitter_AreaRequest, oracle_table_diffuse, "table/table_mis.xml",
                  MaterialTag::kDiffuse, false);
BENCHMARK_CAPTURE(BM_Emitter_AreaRequest, simd_table_diffuse, "table/table_mis.xml",
                  MaterialTag::kDiffuse, true);

}  // namespace
}  // namespace ptlab
