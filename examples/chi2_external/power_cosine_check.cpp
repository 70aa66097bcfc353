// Tests a power-cosine sampler, and two broken variants of it, with the installed ptlab::chi2.
#include <ptlab/chi2.h>

#include <cmath>
#include <cstdio>

namespace chi2 = ptlab::chi2;

constexpr float kPi = 3.14159265f;

// The lobe p(w) = (n+1)/(2 pi) cos^n(theta) on the upper hemisphere: its sampler and pdf.
chi2::Point SamplePowerCosine(float u0, float u1, float n) {
  const float z = std::pow(u0, 1.0f / (n + 1.0f)), r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u1;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
double PowerCosinePdf(const chi2::Point& w, float n) {
  return w.z > 0 ? (n + 1.0f) / (2.0f * kPi) * std::pow(w.z, n) : 0.0f;
}

// A subject whose sampler draws exponent n_sample and whose pdf claims n_pdf, scaled by scale.
chi2::Subject PowerCosine(const char* name, float n_sample, float n_pdf, double scale) {
  chi2::Subject s;
  s.name = name;
  s.domain = chi2::Domain::Hemisphere();
  s.sample = [=](const float* u, int64_t count, int dims, chi2::Point* points) {
    for (int64_t i = 0; i < count; ++i)
      points[i] = SamplePowerCosine(u[i * dims], u[i * dims + 1], n_sample);
    return chi2::Status::Ok();
  };
  s.pdf = [=](const chi2::Point* w, int64_t count, double* density) {
    for (int64_t i = 0; i < count; ++i) density[i] = scale * PowerCosinePdf(w[i], n_pdf);
    return chi2::Status::Ok();
  };
  return s;
}

int main() {
  chi2::Options options;  // 10^6 samples, 51 x 102 cells, alpha = 0.01 over the run's 3 tests
  options.test_count = 3;
  options.images_dir = "chi2_images";
  const struct {
    chi2::Subject subject;
    bool must_pass;
  } runs[] = {
      {PowerCosine("power_cosine_n10", 10, 10, 1.0), true},
      {PowerCosine("broken_normalisation", 10, 10, 0.5), false},  // pdf off by a factor 2
      {PowerCosine("broken_exponent", 10, 11, 1.0), false},       // pdf of another lobe
  };
  int unexpected = 0;
  for (const auto& run : runs) {
    chi2::Result result;
    const chi2::Status status = chi2::Test(run.subject, options, &result);
    if (!status.ok()) {
      std::fprintf(stderr, "%s: %s\n", run.subject.name.c_str(), status.message().c_str());
      return 2;
    }
    std::printf("%s\n", chi2::FormatResult(run.subject.name, result).c_str());
    unexpected += result.passed != run.must_pass;
  }
  std::printf("%s\n", unexpected == 0 ? "as expected" : "NOT as expected");
  return unexpected == 0 ? 0 : 1;
}
