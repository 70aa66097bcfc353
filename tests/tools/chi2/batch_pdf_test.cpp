// A batch pdf gives exactly the one-point-at-a-time result: same cells, χ², p and evaluations.
#include <gtest/gtest.h>

#include <string>

#include "tools/chi2/chi2.h"
#include "tools/chi2/subjects.h"

namespace ptlab {
namespace {

class StatChi2BatchPdf : public ::testing::TestWithParam<std::string> {};

// Smooth (cosine), clipped to the disk's boundary, discontinuous and broken subjects.
TEST_P(StatChi2BatchPdf, EqualsScalarPdf) {
  const Chi2Registry registry = DefaultChi2Registry();
  const Chi2Subject* scalar = registry.Find(GetParam());
  ASSERT_NE(scalar, nullptr);
  Chi2Subject batch = *scalar;
  int64_t calls = 0;
  batch.pdf_batch = [&](const Chi2Point* p, int64_t n, double* density) {
    ++calls;
    for (int64_t i = 0; i < n; ++i) density[i] = scalar->pdf(p[i]);
    return true;
  };
  batch.pdf = nullptr;
  Chi2Options options;
  options.samples = 100000;
  options.res = 21;
  const Chi2Result a = RunChi2Test(*scalar, options);
  const Chi2Result b = RunChi2Test(batch, options);
  EXPECT_EQ(a.expected, b.expected);
  EXPECT_EQ(a.observed, b.observed);
  EXPECT_EQ(a.chi2, b.chi2);
  EXPECT_EQ(a.dof, b.dof);
  EXPECT_EQ(a.pdf_integral, b.pdf_integral);
  EXPECT_EQ(a.pdf_evals, b.pdf_evals);
  EXPECT_EQ(a.pass, b.pass);
  EXPECT_EQ(a.failures, b.failures);
  EXPECT_GT(calls, 1);
  // Each pass settles one more level of the deepest refinement: at most outer x inner
  // max_depth passes per integration (a discontinuity), the recheck of empty cells included.
  EXPECT_LE(calls, 2 * 16 * 18);
}

INSTANTIATE_TEST_SUITE_P(Subjects, StatChi2BatchPdf,
                         ::testing::Values("warp/cosine_hemisphere", "warp/concentric_disk",
                                           "warp/uniform_triangle",
                                           "distantdisk/cone_10deg_rotated",
                                           "broken/cosine_hemisphere_pdf_over_2pi"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (c == '/') c = '_';
                           return s;
                         });

}  // namespace
}  // namespace ptlab
