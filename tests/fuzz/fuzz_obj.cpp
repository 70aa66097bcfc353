// libFuzzer harness: Wavefront OBJ meshes (ptlab's line checks, then tinyobjloader).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/obj_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)ptlab::LoadObjFromString(text, "fuzz.obj");
  return 0;
}
