// libFuzzer harness: Nori statistical test files (<test type="ttest|chi2test">).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/nori_test_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  (void)ptlab::LoadNoriTestFileFromString(xml, PTLAB_SOURCE_DIR "/scenes", "fuzz.xml");
  return 0;
}
