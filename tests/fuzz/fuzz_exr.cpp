// libFuzzer harness: OpenEXR images through ptlab's reader (header checks, then OpenEXR).
#include "tests/fuzz/fuzz_image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return FuzzImageDecoder(data, size, std::string("\x76\x2f\x31\x01", 4));
}
