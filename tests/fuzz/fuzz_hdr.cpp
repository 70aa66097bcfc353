// libFuzzer harness: Radiance HDR (RGBE) images through ptlab's reader (body walk, then
// stb_image).
#include "tests/fuzz/fuzz_image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return FuzzImageDecoder(data, size, "#?RADIANCE\n");
}
