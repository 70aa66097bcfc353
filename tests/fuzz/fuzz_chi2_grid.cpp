// libFuzzer harness: `chi2 check --pdf-grid` files on every domain kind; a grid that reads is
// evaluated at the corners, the centre and points outside its rectangle.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "tools/chi2/check/pdf_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/ptlab_fuzz_chi2_grid_" + std::to_string(::getpid());
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  using ptlab::chi2::Domain;
  for (const Domain& domain : {Domain::Square(), Domain::Disk(), Domain::Sphere(),
                               Domain::Hemisphere(), Domain::Box(-3, 2, 5, 2.5)}) {
    ptlab::chi2::PdfFn pdf;
    if (!ptlab::ReadPdfGrid(path, domain, &pdf).ok()) continue;
    const ptlab::chi2::Point points[] = {{0, 0, 1},   {1, 1, 0},     {-1, -1, 0}, {0.5f, 0.5f, 0},
                                         {1e30f, -1e30f, 2}, {-3, 2.5f, -1}, {0, 1, 0}};
    double densities[7];
    (void)pdf(points, 7, densities);
  }
  return 0;
}
