// libFuzzer harness: Stanford PLY meshes (header, ASCII and binary bodies, attributes).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/ply_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  (void)ptlab::LoadPlyFromBytes(bytes, "fuzz.ply");
  return 0;
}
