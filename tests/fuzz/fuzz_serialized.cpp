// libFuzzer harness: Mitsuba .serialized meshes (header, dictionary, zlib stream), shapes 0 and 1.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/serialized_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  (void)ptlab::LoadSerializedFromBytes(bytes, 0, "fuzz.serialized");
  (void)ptlab::LoadSerializedFromBytes(bytes, 1, "fuzz.serialized");
  return 0;
}
