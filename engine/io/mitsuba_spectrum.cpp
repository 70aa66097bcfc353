// CIE 1931 integration of spectra, .spd files, named IORs.
#include "engine/io/mitsuba_spectrum.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "engine/io/text_parsing.h"

namespace ptlab {
namespace {

constexpr int kCieSamples = 95;  // 360, 365, ..., 830 nm
constexpr double kCieMin = 360.0, kCieMax = 830.0;

// The CIE 1931 2° standard observer x̄, ȳ, z̄ and the CIE D65 illuminant (1 at 560 nm) every
// 5 nm from 360 to 830 nm: CIE standard data, as Debian's colord-data package ships it
// (/usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf, /usr/share/colord/illuminant/CIE-D65.sp).
constexpr float kCieX[kCieSamples] = {
    0.0001299,    0.0002321,    0.0004149,    0.0007416,    0.001368,     0.002236,
    0.004243,     0.00765,      0.01431,      0.02319,      0.04351,      0.07763,
    0.13438,      0.21477,      0.2839,       0.3285,       0.34828,      0.34806,
    0.3362,       0.3187,       0.2908,       0.2511,       0.19536,      0.1421,
    0.09564,      0.05795001,   0.03201,      0.0147,       0.0049,       0.0024,
    0.0093,       0.0291,       0.06327,      0.1096,       0.1655,       0.2257499,
    0.2904,       0.3597,       0.4334499,    0.5120501,    0.5945,       0.6784,
    0.7621,       0.8425,       0.9163,       0.9786,       1.0263,       1.0567,
    1.0622,       1.0456,       1.0026,       0.9384,       0.8544499,    0.7514,
    0.6424,       0.5419,       0.4479,       0.3608,       0.2835,       0.2187,
    0.1649,       0.1212,       0.0874,       0.0636,       0.04677,      0.0329,
    0.0227,       0.01584,      0.01135916,   0.008110916,  0.005790346,  0.004109457,
    0.002899327,  0.00204919,   0.001439971,  0.0009999493, 0.0006900786, 0.0004760213,
    0.0003323011, 0.0002348261, 0.0001661505, 0.000117413,  8.307527e-05, 5.870652e-05,
    4.150994e-05, 2.935326e-05, 2.067383e-05, 1.455977e-05, 1.025398e-05, 7.221456e-06,
    5.085868e-06, 3.581652e-06, 2.522525e-06, 1.776509e-06, 1.251141e-06,
};
constexpr float kCieY[kCieSamples] = {
    3.917e-06,  6.965e-06,  1.239e-05,  2.202e-05,  3.9e-05,    6.4e-05,    0.00012,    0.000217,
    0.000396,   0.00064,    0.00121,    0.00218,    0.004,      0.0073,     0.0116,     0.01684,
    0.023,      0.0298,     0.038,      0.048,      0.06,       0.0739,     0.09098,    0.1126,
    0.13902,    0.1693,     0.20802,    0.2586,     0.323,      0.4073,     0.503,      0.6082,
    0.71,       0.7932,     0.862,      0.9148501,  0.954,      0.9803,     0.9949501,  1.0,
    0.995,      0.9786,     0.952,      0.9154,     0.87,       0.8163,     0.757,      0.6949,
    0.631,      0.5668,     0.503,      0.4412,     0.381,      0.321,      0.265,      0.217,
    0.175,      0.1382,     0.107,      0.0816,     0.061,      0.04458,    0.032,      0.0232,
    0.017,      0.01192,    0.00821,    0.005723,   0.004102,   0.002929,   0.002091,   0.001484,
    0.001047,   0.00074,    0.00052,    0.0003611,  0.0002492,  0.0001719,  0.00012,    8.48e-05,
    6e-05,      4.24e-05,   3e-05,      2.12e-05,   1.499e-05,  1.06e-05,   7.4657e-06, 5.2578e-06,
    3.7029e-06, 2.6078e-06, 1.8366e-06, 1.2934e-06, 9.1093e-07, 6.4153e-07, 4.5181e-07,
};
constexpr float kCieZ[kCieSamples] = {
    0.0006061,  0.001086,    0.001946, 0.003486, 0.006450001, 0.01054999, 0.02005001,   0.03621,
    0.06785001, 0.1102,      0.2074,   0.3713,   0.6456,      1.0390501,  1.3856,       1.62296,
    1.74706,    1.7826,      1.77211,  1.7441,   1.6692,      1.5281,     1.28764,      1.0419,
    0.8129501,  0.6162,      0.46518,  0.3533,   0.272,       0.2123,     0.1582,       0.1117,
    0.07824999, 0.05725001,  0.04216,  0.02984,  0.0203,      0.0134,     0.008749999,  0.005749999,
    0.0039,     0.002749999, 0.0021,   0.0018,   0.001650001, 0.0014,     0.0011,       0.001,
    0.0008,     0.0006,      0.00034,  0.00024,  0.00019,     0.0001,     4.999999e-05, 3e-05,
    2e-05,      1e-05,       0.0,      0.0,      0.0,         0.0,        0.0,          0.0,
    0.0,        0.0,         0.0,      0.0,      0.0,         0.0,        0.0,          0.0,
    0.0,        0.0,         0.0,      0.0,      0.0,         0.0,        0.0,          0.0,
    0.0,        0.0,         0.0,      0.0,      0.0,         0.0,        0.0,          0.0,
    0.0,        0.0,         0.0,      0.0,      0.0,         0.0,        0.0,
};
constexpr float kD65[kCieSamples] = {
    0.466383, 0.493637, 0.520891, 0.510323, 0.499755, 0.523118, 0.546482, 0.687015, 0.827549,
    0.871204, 0.91486,  0.924589, 0.934318, 0.90057,  0.866823, 0.957736, 1.04865,  1.10936,
    1.17008,  1.1741,   1.17812,  1.16336,  1.14861,  1.15392,  1.15923,  1.12367,  1.08811,
    1.09082,  1.09354,  1.08578,  1.07802,  1.06296,  1.0479,   1.06239,  1.07689,  1.06047,
    1.04405,  1.04225,  1.04046,  1.02023,  1.0,      0.981671, 0.963342, 0.960611, 0.95788,
    0.922368, 0.886856, 0.893459, 0.900062, 0.898026, 0.895991, 0.886489, 0.876987, 0.854936,
    0.832886, 0.834939, 0.836992, 0.81863,  0.800268, 0.801207, 0.802146, 0.812462, 0.822778,
    0.80281,  0.782842, 0.740027, 0.697213, 0.706652, 0.716091, 0.72979,  0.74349,  0.679765,
    0.61604,  0.657448, 0.698856, 0.724863, 0.75087,  0.693398, 0.635927, 0.550054, 0.464182,
    0.566118, 0.668054, 0.650941, 0.633828, 0.638434, 0.64304,  0.618779, 0.594519, 0.557054,
    0.51959,  0.546998, 0.574406, 0.588765, 0.603125,
};

// Mitsuba 3 divides D65 (scaled to 100 at 560 nm) by this constant (MI_CIE_D65_NORMALIZATION);
// the quadrature below would give 98.888, 0.11 % less. Kept so that converted reflectances match.
constexpr double kD65Normalization = 98.99741751876255 / 100.0;

double Tabulated(const float* table, double lambda) {
  const double t = (lambda - kCieMin) * ((kCieSamples - 1) / (kCieMax - kCieMin));
  const int i0 = std::clamp(int(t), 0, kCieSamples - 2);
  const double f = t - i0;
  return (1.0 - f) * table[i0] + f * table[i0 + 1];
}

constexpr int kSteps = 1000;
double Lambda(int i) { return kCieMin + (kCieMax - kCieMin) * i / double(kSteps - 1); }

double YIntegral() {
  double sum = 0;
  for (int i = 0; i < kSteps; ++i) sum += Tabulated(kCieY, Lambda(i));
  return sum * (kCieMax - kCieMin) / kSteps;
}

struct NamedIor {
  const char* name;
  float ior;
};
// Hecht, Optics (4th ed.), at about 589 nm, 0-20 °C: the names Mitsuba accepts.
constexpr NamedIor kNamedIors[] = {
    {"vacuum", 1.0f},      {"helium", 1.000036f},        {"hydrogen", 1.000132f},
    {"air", 1.000277f},    {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
    {"acetone", 1.36f},    {"ethanol", 1.361f},          {"carbon tetrachloride", 1.461f},
    {"glycerol", 1.4729f}, {"benzene", 1.501f},          {"silicone oil", 1.52045f},
    {"bromine", 1.661f},   {"water ice", 1.31f},         {"fused quartz", 1.458f},
    {"pyrex", 1.470f},     {"acrylic glass", 1.49f},     {"polypropylene", 1.49f},
    {"bk7", 1.5046f},      {"sodium chloride", 1.544f},  {"amber", 1.55f},
    {"pet", 1.5750f},      {"diamond", 2.419f},
};

}  // namespace

Color3f SpectrumToRgb(const std::vector<double>& wavelengths, const std::vector<double>& values,
                      SpectrumUse use) {
  static const double y_integral = YIntegral();
  double x = 0, y = 0, z = 0;
  const size_t n = wavelengths.size();
  for (int i = 0; i < kSteps; ++i) {
    const double lambda = Lambda(i);
    if (n < 2 || lambda < wavelengths.front() || lambda > wavelengths.back()) continue;
    // The interval [w_k, w_k+1] holding lambda (the last one for lambda == back()).
    const size_t k =
        std::min<size_t>(size_t(std::upper_bound(wavelengths.begin(), wavelengths.end(), lambda) -
                                wavelengths.begin()) -
                             1,
                         n - 2);
    const double w0 = wavelengths[k], w1 = wavelengths[k + 1];
    double v = ((lambda - w1) * values[k] + (w0 - lambda) * values[k + 1]) / (w0 - w1);
    if (use == SpectrumUse::kReflectance) v *= Tabulated(kD65, lambda) / kD65Normalization;
    x += Tabulated(kCieX, lambda) * v;
    y += Tabulated(kCieY, lambda) * v;
    z += Tabulated(kCieZ, lambda) * v;
  }
  const double scale = (kCieMax - kCieMin) / kSteps / y_integral;
  x *= scale, y *= scale, z *= scale;
  // XYZ to linear sRGB (Rec. 709 primaries, D65 white).
  double rgb[3] = {3.240479 * x - 1.537150 * y - 0.498535 * z,
                   -0.969256 * x + 1.875991 * y + 0.041556 * z,
                   0.055648 * x - 0.204043 * y + 1.057311 * z};
  for (double& c : rgb) {
    c = std::max(c, 0.0);
    if (use == SpectrumUse::kReflectance) c = std::min(c, 1.0);
  }
  return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

Status ReadSpdFile(const std::string& path, std::vector<double>* wavelengths,
                   std::vector<double>* values) {
  std::string text;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "spectrum file", &text));
  wavelengths->clear();
  values->clear();
  size_t line_no = 0, start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++line_no;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    std::vector<std::string_view> items;
    float w = 0, v = 0;
    if (!SplitList(line, &items) || (!items.empty() && items.size() != 2) ||
        (items.size() == 2 && (!ParseFloat(items[0], &w) || !ParseFloat(items[1], &v))))
      return Status::Error(path + ":" + std::to_string(line_no) +
                           ": expected 'wavelength value' (two finite numbers)");
    if (items.empty()) continue;
    if (!wavelengths->empty() && !(w > wavelengths->back()))
      return Status::Error(path + ":" + std::to_string(line_no) +
                           ": wavelengths must increase from line to line");
    wavelengths->push_back(w);
    values->push_back(v);
  }
  if (wavelengths->size() < 2)
    return Status::Error(path + ": expected at least two 'wavelength value' lines");
  return Status::Ok();
}

bool LookupNamedIor(std::string_view name, float* ior) {
  std::string lower(name);
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const NamedIor& e : kNamedIors)
    if (lower == e.name) {
      *ior = e.ior;
      return true;
    }
  return false;
}

std::string NamedIorList() {
  std::string s;
  for (const NamedIor& e : kNamedIors) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

}  // namespace ptlab
