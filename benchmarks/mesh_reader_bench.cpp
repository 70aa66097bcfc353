// Load time of a 1,002,528-triangle mesh from a binary PLY and from a Mitsuba .serialized file.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/ply_loader.h"
#include "engine/io/serialized_loader.h"
#include "tests/engine/io/mesh_file_writers.h"

namespace ptlab {
namespace {

// The grid of 708 x 708 quads (normals and uvs), written once per process to the temp folder.
const std::string& MeshFile(const std::string& ext) {
  static const std::string dir = [] {
    const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                    ("ptlab_mesh_reader_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    const MeshData grid = test_util::GridMesh(708);
    std::ofstream(d / "grid.ply", std::ios::binary) << test_util::PlyBinaryBytes(grid, false);
    std::ofstream(d / "grid.serialized", std::ios::binary)
        << test_util::SerializedBytes({grid}, 4, false);
    return d.string();
  }();
  static const std::string ply = dir + "/grid.ply", serialized = dir + "/grid.serialized";
  return ext == "ply" ? ply : serialized;
}

void BM_MeshReader_BinaryPly1M(benchmark::State& state) {
  const std::string& path = MeshFile("ply");
  for (auto _ : state) {
    StatusOr<MeshData> m = LoadPly(path);
    if (!m.ok()) state.SkipWithError(m.status().message().c_str());
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations() * 1002528);
}
BENCHMARK(BM_MeshReader_BinaryPly1M)->Unit(benchmark::kMillisecond);

void BM_MeshReader_Serialized1M(benchmark::State& state) {
  const std::string& path = MeshFile("serialized");
  for (auto _ : state) {
    StatusOr<MeshData> m = LoadSerialized(path, 0);
    if (!m.ok()) state.SkipWithError(m.status().message().c_str());
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations() * 1002528);
}
BENCHMARK(BM_MeshReader_Serialized1M)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ptlab
