// libFuzzer harness: COLLADA (.dae) scenes with the CS184 extensions.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/io/collada_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ptlab::StatusOr<ptlab::Scene> scene = ptlab::LoadColladaSceneFromString(text, "fuzz.dae");
  if (scene.ok() && scene->triangles.size() <= 100000)
    (void)ptlab::BuildBvh(scene->triangles, scene->spheres);
  return 0;
}
