// A pdf tabulated on a grid of the domain's parameter rectangle, interpolated bilinearly.
#include "tools/chi2/check/pdf_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

namespace ptlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Grid {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  bool spherical = false;
  std::vector<double> values;  // row-major, ny rows of nx

  double At(const chi2::Point& p) const {
    double x = p.x, y = p.y;
    if (spherical) {
      x = std::atan2(double(p.y), double(p.x));
      if (x < 0) x += 2 * kPi;
      y = std::clamp(double(p.z), -1.0, 1.0);
    }
    const double fx = std::clamp((x - x0) / (x1 - x0), 0.0, 1.0) * (nx - 1);
    const double fy = std::clamp((y - y0) / (y1 - y0), 0.0, 1.0) * (ny - 1);
    const int i = std::min(int(fx), nx - 2), j = std::min(int(fy), ny - 2);
    const double tx = fx - i, ty = fy - j;
    const double* r0 = &values[size_t(j) * size_t(nx)];
    const double* r1 = r0 + nx;
    return (1 - ty) * ((1 - tx) * r0[i] + tx * r0[i + 1]) +
           ty * ((1 - tx) * r1[i] + tx * r1[i + 1]);
  }
};

}  // namespace

chi2::Status ReadPdfGrid(const std::string& path, const chi2::Domain& domain, chi2::PdfFn* pdf) {
  std::ifstream in(path);
  if (!in) return chi2::Status::Error(path + ": cannot open the pdf grid");
  auto grid = std::make_shared<Grid>();
  switch (domain.kind) {
    case chi2::DomainKind::kBox:
      grid->x0 = domain.x0, grid->y0 = domain.y0, grid->x1 = domain.x1, grid->y1 = domain.y1;
      break;
    case chi2::DomainKind::kDisk:
      grid->x0 = -1, grid->y0 = -1, grid->x1 = 1, grid->y1 = 1;
      break;
    case chi2::DomainKind::kSphere:
      grid->spherical = true, grid->x0 = 0, grid->y0 = -1, grid->x1 = 2 * kPi, grid->y1 = 1;
      break;
    case chi2::DomainKind::kHemisphere:
      grid->spherical = true, grid->x0 = 0, grid->y0 = 0, grid->x1 = 2 * kPi, grid->y1 = 1;
      break;
  }
  std::string line;
  int64_t number = 0;
  size_t want = 0;
  while (std::getline(in, line)) {
    ++number;
    for (char& c : line)
      if (c == ',') c = ' ';
    const size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size())
        return chi2::Status::Error(path + ":" + std::to_string(number) + ": \"" + token +
                                   "\" is not a number");
      if (grid->nx == 0 || grid->ny == 0) {
        if (v != std::floor(v) || v < 2 || v > 1e5)
          return chi2::Status::Error(path + ":" + std::to_string(number) +
                                     ": expected the grid size \"NX NY\" (integers >= 2) first");
        (grid->nx == 0 ? grid->nx : grid->ny) = int(v);
        if (grid->ny > 0) want = size_t(grid->nx) * size_t(grid->ny);
        continue;
      }
      if (!std::isfinite(v) || v < 0)
        return chi2::Status::Error(path + ":" + std::to_string(number) + ": density " + token +
                                   ", expected a finite number >= 0");
      if (grid->values.size() == want)
        return chi2::Status::Error(path + ":" + std::to_string(number) +
                                   ": more than NX*NY = " + std::to_string(want) + " densities");
      grid->values.push_back(v);
    }
  }
  if (want == 0)
    return chi2::Status::Error(path + ": empty, expected \"NX NY\" and NY rows of NX densities");
  if (grid->values.size() != want)
    return chi2::Status::Error(path + ": " + std::to_string(grid->values.size()) +
                               " densities, expected NX*NY = " + std::to_string(want));
  *pdf = [grid](const chi2::Point* p, int64_t n, double* densities) {
    for (int64_t i = 0; i < n; ++i) densities[i] = grid->At(p[i]);
    return chi2::Status::Ok();
  };
  return chi2::Status::Ok();
}

}  // namespace ptlab
