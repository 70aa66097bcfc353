// The public t-test API (ptlab/chi2.h): moments of the values, then Student / Welch tests.
#include <cmath>
#include <string>

#include "ptlab/chi2.h"
#include "tools/chi2/stats_math.h"

namespace ptlab::chi2 {
namespace {

Status Moments(const char* what, const double* values, int64_t n, RunningMoments* m) {
  if (n < 2)
    return Status::Error(std::string(what) + ": a t-test needs at least 2 values, got " +
                         std::to_string(n));
  for (int64_t i = 0; i < n; ++i) {
    if (!std::isfinite(values[i]))
      return Status::Error(std::string(what) + ": value " + std::to_string(i) + " is " +
                           std::to_string(values[i]) + ", expected a finite number");
    m->Add(values[i]);
  }
  return Status::Ok();
}

Status CheckLevel(double alpha, int test_count) {
  if (!(alpha > 0 && alpha < 1))
    return Status::Error("alpha must be in (0, 1), got " + std::to_string(alpha));
  if (test_count < 1)
    return Status::Error("test_count must be >= 1, got " + std::to_string(test_count));
  return Status::Ok();
}

TTestResult ToPublic(const ptlab::TTestResult& t, const RunningMoments& m) {
  TTestResult out;
  out.passed = t.pass;
  out.t = t.t;
  out.dof = t.dof;
  out.p_value = t.p_value;
  out.alpha = t.alpha;
  out.mean = m.mean;
  out.variance = m.Variance();
  out.n = m.n;
  return out;
}

}  // namespace

Status OneSampleTTest(const double* values, int64_t n, double reference, double alpha,
                      int test_count, TTestResult* result) {
  Status st = CheckLevel(alpha, test_count);
  if (!st.ok()) return st;
  if (!std::isfinite(reference))
    return Status::Error("the reference must be finite, got " + std::to_string(reference));
  RunningMoments m;
  st = Moments("values", values, n, &m);
  if (!st.ok()) return st;
  *result =
      ToPublic(ptlab::OneSampleTTest(m.mean, m.Variance(), m.n, reference, alpha, test_count), m);
  return Status::Ok();
}

Status WelchTTest(const double* values1, int64_t n1, const double* values2, int64_t n2,
                  double alpha, int test_count, TTestResult* result) {
  Status st = CheckLevel(alpha, test_count);
  if (!st.ok()) return st;
  RunningMoments m1, m2;
  st = Moments("first values", values1, n1, &m1);
  if (!st.ok()) return st;
  st = Moments("second values", values2, n2, &m2);
  if (!st.ok()) return st;
  *result = ToPublic(ptlab::WelchTTest(m1.mean, m1.Variance(), m1.n, m2.mean, m2.Variance(), m2.n,
                                       alpha, test_count),
                     m1);
  return Status::Ok();
}

}  // namespace ptlab::chi2
