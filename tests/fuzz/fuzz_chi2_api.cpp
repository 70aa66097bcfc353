// libFuzzer harness: the chi² lab's API as the Python module's entry points call it
// (tools/chi2/python/module.cpp: chi2_test with a sample array or a sample function, t_test
// one-sample and Welch), with every argument taken from the input: the domain text, the
// options (samples, res, alpha, test count, uniforms per sample, coarse blocks, power), the
// points a sampler returns and the one density the pdf returns (NaN, Inf, negative, huge and
// out-of-domain values included). Each call must return a Status (an error for bad input) and
// never crash, hang or abort. Sample counts are kept small so that an execution takes
// milliseconds; the counts' own limits are checked by the API's tests.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ptlab/chi2.h"

namespace {

namespace chi2 = ptlab::chi2;

// Reads the input front to back; past its end every read gives zeros.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  template <class T>
  T Get() {
    T v{};
    const size_t n = std::min(sizeof(T), size_ - std::min(pos_, size_));
    if (n > 0) std::memcpy(&v, data_ + pos_, n);
    pos_ += sizeof(T);
    return v;
  }
  // Text up to the next NUL (at most 64 bytes).
  std::string Text() {
    std::string s;
    while (pos_ < size_ && data_[pos_] != 0 && s.size() < 64) s += char(data_[pos_++]);
    ++pos_;
    return s;
  }
  size_t left() const { return pos_ < size_ ? size_ - pos_ : 0; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// A value a fuzzed callable returns: mostly ordinary numbers, sometimes raw bit patterns.
float FuzzFloat(Bytes& in) {
  const uint8_t kind = in.Get<uint8_t>();
  if (kind < 200) return float(in.Get<int8_t>()) / 64.0f;
  return in.Get<float>();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  const uint8_t which = in.Get<uint8_t>();
  if (which % 3 == 2) {
    // t_test(values, reference=...) or t_test(values, other=...).
    const size_t n1 = in.Get<uint8_t>() % 40, n2 = in.Get<uint8_t>() % 40;
    const double reference = in.Get<double>(), alpha = in.Get<double>();
    const int test_count = in.Get<int16_t>();
    std::vector<double> a(n1), b(n2);
    for (double& v : a) v = in.Get<uint8_t>() < 220 ? double(in.Get<int16_t>()) / 100.0 : in.Get<double>();
    for (double& v : b) v = in.Get<uint8_t>() < 220 ? double(in.Get<int16_t>()) / 100.0 : in.Get<double>();
    chi2::TTestResult r;
    (void)chi2::OneSampleTTest(a.data(), int64_t(n1), reference, alpha, test_count, &r);
    (void)chi2::WelchTTest(a.data(), int64_t(n1), b.data(), int64_t(n2), alpha, test_count, &r);
    return 0;
  }
  chi2::Domain domain;
  if (!chi2::ParseDomain(in.Text(), &domain).ok()) return 0;
  chi2::Options options;
  options.samples = int64_t(in.Get<int16_t>()) % 2048;
  options.res = int(in.Get<int16_t>()) % 96;
  options.alpha = in.Get<uint8_t>() < 128 ? 0.01 : in.Get<double>();
  options.test_count = int(in.Get<int16_t>());
  options.coarse_blocks = int(in.Get<int8_t>()) % 12;
  options.power = (in.Get<uint8_t>() & 1) != 0 && options.samples <= 256;
  const int dims = domain.dims();
  // The points a sampler returns, cycled through.
  std::vector<chi2::Point> points(1 + in.Get<uint8_t>() % 16);
  for (chi2::Point& p : points) p = {FuzzFloat(in), FuzzFloat(in), dims == 3 ? FuzzFloat(in) : 0};
  // One density for every point (NaN, Inf, negative and huge included): a pdf that is noise
  // within cells runs the integration to its 8 M-point budget, tens of seconds per input under
  // ASan, past ./lab fuzz's 10 s timeout (that budget has its own check in chi2.cpp).
  const double density = double(FuzzFloat(in));
  const chi2::PdfFn pdf = [density](const chi2::Point*, int64_t n, double* out) {
    for (int64_t i = 0; i < n; ++i) out[i] = density;
    return chi2::Status::Ok();
  };
  chi2::Result result;
  if (which % 3 == 0) {
    // chi2_test(domain, samples_array, pdf): the points drawn elsewhere.
    std::vector<chi2::Point> sample(size_t(std::max<int64_t>(options.samples, 0)));
    for (size_t i = 0; i < sample.size(); ++i) sample[i] = points[i % points.size()];
    (void)chi2::TestPoints("fuzz", domain, sample.data(), int64_t(sample.size()), pdf, options,
                           &result);
  } else {
    // chi2_test(domain, sample_fn, pdf, uniform_dims=...).
    chi2::Subject subject;
    subject.name = "fuzz";
    subject.domain = domain;
    subject.uniform_dims = int(in.Get<int8_t>()) % 10;
    size_t next_point = 0;
    subject.sample = [&](const float*, int64_t n, int, chi2::Point* out) {
      for (int64_t i = 0; i < n; ++i) out[i] = points[next_point++ % points.size()];
      return chi2::Status::Ok();
    };
    subject.pdf = pdf;
    (void)chi2::Test(subject, options, &result);
  }
  return 0;
}
