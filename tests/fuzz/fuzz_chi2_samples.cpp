// libFuzzer harness: `chi2 check --samples` files, as text (2 and 3 numbers a line) and raw
// float32 (--dims 2, 3). The reader takes a path, so the input goes through a file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/chi2/check/sample_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/ptlab_fuzz_chi2_samples_" + std::to_string(::getpid());
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  std::vector<ptlab::chi2::Point> points;
  for (const bool raw : {false, true})
    for (const int dims : {2, 3}) (void)ptlab::ReadSampleFile(path, raw, dims, &points);
  return 0;
}
