// The `ptlab` Python module: the chi-square and t-test lab on NumPy samplers (pybind11).
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "ptlab/chi2.h"

namespace py = pybind11;
namespace chi2 = ptlab::chi2;

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

chi2::Domain ParseDomain(const std::string& text) {
  chi2::Domain d;
  const chi2::Status st = chi2::ParseDomain(text, &d);
  if (!st.ok()) throw py::value_error(st.message());
  return d;
}

std::string Shape(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    if (i > 0) s += ", ";
    s += std::to_string(a.shape(i));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// Points from an (n, dims) array-like; the error names what was expected.
chi2::Status ToPoints(const py::handle& obj, const char* what, int64_t n, int dims,
                      std::vector<chi2::Point>* points) {
  FloatArray a = FloatArray::ensure(obj);
  if (!a) {
    PyErr_Clear();
    return chi2::Status::Error(std::string(what) + " is not a float array: expected shape (" +
                               (n >= 0 ? std::to_string(n) : std::string("N")) + ", " +
                               std::to_string(dims) + ")");
  }
  if (a.ndim() != 2 || a.shape(1) != dims || (n >= 0 && a.shape(0) != n))
    return chi2::Status::Error(std::string(what) + " has shape " + Shape(a) + ", expected (" +
                               (n >= 0 ? std::to_string(n) : std::string("N")) + ", " +
                               std::to_string(dims) + ")");
  const int64_t rows = a.shape(0);
  points->resize(size_t(rows));
  const float* v = a.data();
  for (int64_t i = 0; i < rows; ++i)
    (*points)[size_t(i)] = {v[i * dims], v[i * dims + 1], dims == 3 ? v[i * dims + 2] : 0.0f};
  return chi2::Status::Ok();
}

// Holds the first Python exception a callback raised, to re-raise it unchanged.
struct PythonError {
  std::optional<py::error_already_set> error;
  chi2::Status Keep(py::error_already_set& e) {
    const std::string what = e.what();
    if (!error) error.emplace(std::move(e));
    return chi2::Status::Error(what);
  }
};

chi2::PdfFn WrapPdf(const py::function& pdf, int dims, PythonError* python_error) {
  return [pdf, dims, python_error](const chi2::Point* p, int64_t n, double* densities) {
    try {
      DoubleArray points({py::ssize_t(n), py::ssize_t(dims)});
      double* v = points.mutable_data();
      for (int64_t i = 0; i < n; ++i) {
        v[i * dims] = p[i].x, v[i * dims + 1] = p[i].y;
        if (dims == 3) v[i * dims + 2] = p[i].z;
      }
      const py::object out = pdf(points);
      DoubleArray d = DoubleArray::ensure(out);
      if (!d) {
        PyErr_Clear();
        return chi2::Status::Error("pdf(points) did not return a float array: expected shape (" +
                                   std::to_string(n) + ",)");
      }
      if (d.size() != n || d.ndim() > 2 || (d.ndim() == 2 && d.shape(1) != 1))
        return chi2::Status::Error("pdf(points) returned shape " + Shape(d) + " for " +
                                   std::to_string(n) + " points, expected (" + std::to_string(n) +
                                   ",)");
      std::copy(d.data(), d.data() + n, densities);
      return chi2::Status::Ok();
    } catch (py::error_already_set& e) {
      return python_error->Keep(e);
    }
  };
}

chi2::Result Chi2Test(const std::string& domain_text, const py::object& sample,
                      const py::function& pdf, int64_t samples, int res, double alpha,
                      std::optional<std::string> images, const std::string& name, int uniform_dims,
                      uint64_t seed, int test_count, bool power) {
  const chi2::Domain domain = ParseDomain(domain_text);
  const int dims = domain.dims();
  chi2::Options options;
  options.samples = samples;
  options.res = res;
  options.alpha = alpha;
  options.seed = seed;
  options.test_count = test_count;
  options.power = power;
  if (images) options.images_dir = *images;
  PythonError python_error;
  chi2::Result result;
  chi2::Status st;
  if (py::isinstance<py::function>(sample)) {
    chi2::Subject s;
    s.name = name;
    s.domain = domain;
    s.uniform_dims = uniform_dims;
    const py::function fn = sample;
    s.sample = [fn, dims, &python_error](const float* u, int64_t n, int k, chi2::Point* p) {
      try {
        FloatArray uniforms({py::ssize_t(n), py::ssize_t(k)});
        std::copy(u, u + n * k, uniforms.mutable_data());
        std::vector<chi2::Point> points;
        const chi2::Status st = ToPoints(fn(uniforms), "sample(u)", n, dims, &points);
        if (st.ok()) std::copy(points.begin(), points.end(), p);
        return st;
      } catch (py::error_already_set& e) {
        return python_error.Keep(e);
      }
    };
    s.pdf = WrapPdf(pdf, dims, &python_error);
    st = chi2::Test(s, options, &result);
  } else {
    // An array of points drawn elsewhere.
    std::vector<chi2::Point> points;
    st = ToPoints(sample, "the samples", -1, dims, &points);
    if (st.ok())
      st = chi2::TestPoints(name, domain, points.data(), int64_t(points.size()),
                            WrapPdf(pdf, dims, &python_error), options, &result);
  }
  if (python_error.error) throw std::move(*python_error.error);
  if (!st.ok()) throw py::value_error(st.message());
  return result;
}

chi2::TTestResult TTest(const DoubleArray& values, std::optional<double> reference,
                        std::optional<DoubleArray> other, double alpha, int test_count) {
  if (reference.has_value() == other.has_value())
    throw py::value_error("t_test needs either reference= (one-sample) or other= (Welch)");
  if (values.ndim() != 1)
    throw py::value_error("values has shape " + Shape(values) + ", expected (N,)");
  chi2::TTestResult r;
  chi2::Status st;
  if (reference) {
    st = chi2::OneSampleTTest(values.data(), values.size(), *reference, alpha, test_count, &r);
  } else {
    if (other->ndim() != 1)
      throw py::value_error("other has shape " + Shape(*other) + ", expected (N,)");
    st = chi2::WelchTTest(values.data(), values.size(), other->data(), other->size(), alpha,
                          test_count, &r);
  }
  if (!st.ok()) throw py::value_error(st.message());
  return r;
}

}  // namespace

PYBIND11_MODULE(ptlab, m) {
  m.doc() = "ptlab's statistical lab: chi-square tests of samplers and t-tests";
  py::class_<chi2::Result>(m, "Chi2Result")
      .def_readonly("passed", &chi2::Result::passed)
      .def_readonly("chi2", &chi2::Result::chi2)
      .def_readonly("dof", &chi2::Result::dof)
      .def_readonly("p_value", &chi2::Result::p_value)
      .def_readonly("alpha", &chi2::Result::alpha, "Sidak-corrected per-test significance")
      .def_readonly("pdf_integral", &chi2::Result::pdf_integral)
      .def_readonly("samples", &chi2::Result::samples)
      .def_readonly("pdf_evals", &chi2::Result::pdf_evals)
      .def_readonly("failures", &chi2::Result::failures)
      .def_readonly("notes", &chi2::Result::notes)
      .def_readonly("coarse_chi2", &chi2::Result::coarse_chi2)
      .def_readonly("coarse_dof", &chi2::Result::coarse_dof)
      .def_readonly("coarse_p_value", &chi2::Result::coarse_p_value)
      .def_readonly("alpha_each", &chi2::Result::alpha_each, "level of each of the two grids")
      .def_readonly("power_epsilon", &chi2::Result::power_epsilon)
      .def_readonly("power_at_2", &chi2::Result::power_at_2)
      .def_readonly("power_samples_for_2", &chi2::Result::power_samples_for_2)
      .def_readonly("power_report", &chi2::Result::power_report)
      .def_property_readonly("observed",
                             [](const chi2::Result& r) {
                               return DoubleArray({r.yres, r.xres}, r.observed.data());
                             })
      .def_property_readonly("expected",
                             [](const chi2::Result& r) {
                               return DoubleArray({r.yres, r.xres}, r.expected.data());
                             })
      .def("__bool__", [](const chi2::Result& r) { return r.passed; })
      .def("__repr__", [](const chi2::Result& r) { return chi2::FormatResult("chi2_test", r); });
  py::class_<chi2::TTestResult>(m, "TTestResult")
      .def_readonly("passed", &chi2::TTestResult::passed)
      .def_readonly("t", &chi2::TTestResult::t)
      .def_readonly("dof", &chi2::TTestResult::dof)
      .def_readonly("p_value", &chi2::TTestResult::p_value)
      .def_readonly("alpha", &chi2::TTestResult::alpha)
      .def_readonly("mean", &chi2::TTestResult::mean)
      .def_readonly("variance", &chi2::TTestResult::variance)
      .def_readonly("n", &chi2::TTestResult::n)
      .def("__bool__", [](const chi2::TTestResult& r) { return r.passed; })
      .def("__repr__", [](const chi2::TTestResult& r) {
        return std::string(r.passed ? "PASS" : "FAIL") + " t=" + std::to_string(r.t) +
               " dof=" + std::to_string(r.dof) + " p=" + std::to_string(r.p_value) +
               " alpha'=" + std::to_string(r.alpha);
      });
  m.def("chi2_test", &Chi2Test, py::arg("domain"), py::arg("sample"), py::arg("pdf"),
        py::arg("samples") = 1000000, py::arg("res") = 51, py::arg("alpha") = 0.01,
        py::arg("images") = py::none(), py::arg("name") = "sampler", py::arg("uniform_dims") = 2,
        py::arg("seed") = chi2::kDefaultSeed, py::arg("test_count") = 1, py::arg("power") = false,
        R"(Chi-square test of a sampler against its pdf.

domain: "square", "disk", "box:x0,y0,x1,y1", "sphere" or "hemisphere".
sample: f(u) mapping an (N, uniform_dims) float32 array of uniforms to an (N, 2|3) array of
  points (2 on planar domains, 3 = unit vectors on spherical ones); or an (N, 2|3) array of
  points drawn elsewhere.
pdf: f(points) mapping an (M, 2|3) float64 array to M densities (per unit area / steradian);
  called a few times per test with every point the adaptive integration needs next.
images: a directory for <name>.png (observed | expected | residual) and <name>.csv.
power: also estimate the smallest smooth pdf error the test detects with 95 % probability
  (result.power_epsilon, power_at_2, power_samples_for_2, power_report).
Raises ValueError on bad input (shapes, NaN or out-of-domain samples); a callback's own
exception propagates unchanged.)");
  m.def("t_test", &TTest, py::arg("values"), py::arg("reference") = py::none(),
        py::arg("other") = py::none(), py::arg("alpha") = 0.01, py::arg("test_count") = 1,
        R"(Two-tailed t-test: one-sample Student (reference=, Nori's variance floor 1e-5) or
Welch's two-sample (other=), at the Sidak-corrected level alpha for test_count tests.)");
}
