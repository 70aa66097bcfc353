// libFuzzer harness: Nori XML scenes, loaded and (when small) given a BVH, as `ptlab render`
// does before the first ray. Relative file names resolve in scenes/ so seeds that reference
// meshes reach the OBJ loader too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/io/xml_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  ptlab::StatusOr<ptlab::Scene> scene =
      ptlab::LoadSceneFromString(xml, PTLAB_SOURCE_DIR "/scenes", "fuzz.xml");
  if (scene.ok() && scene->triangles.size() <= 100000) (void)ptlab::BuildBvh(scene->triangles);
  return 0;
}
