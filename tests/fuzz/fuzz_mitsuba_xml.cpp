// libFuzzer harness: Mitsuba scenes (<scene version=...>), preprocessed and loaded as
// `ptlab render` does, then (when small) given a BVH. Relative names resolve in
// tests/fuzz/seeds/mitsuba_xml, whose seeds include and reference each other.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/io/mitsuba_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  ptlab::LoadOptions options;
  options.defines = {"spp=2"};
  ptlab::StatusOr<ptlab::Scene> scene = ptlab::LoadMitsubaSceneFromString(
      xml, PTLAB_SOURCE_DIR "/tests/fuzz/seeds/mitsuba_xml", "fuzz.xml", options);
  if (scene.ok() && scene->triangles.size() <= 100000)
    (void)ptlab::BuildBvh(scene->triangles, scene->spheres);
  return 0;
}
