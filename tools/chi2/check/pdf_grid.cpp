// A pdf tabulated on a grid of the domain's parameter rectangle, interpolated bilinearly.
#include "tools/chi2/check/pdf_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string_view>
#include <vector>

#include "engine/core/line_reader.h"
#include "engine/core/parse_number.h"

namespace ptlab {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Budgets of a grid file: a side, the nodes (8 bytes each: 2^26 nodes take 512 MiB) and a
// density (integrals over the grid stay finite in double).
constexpr int kMaxGridSide = 1 << 16;
constexpr size_t kMaxGridNodes = size_t(1) << 26;
constexpr double kMaxDensity = 1e300;

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
  LineReader in;
  const Status opened = in.Open(path, "the pdf grid");
  if (!opened.ok()) return chi2::Status::Error(opened.message());
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
  std::string_view line;
  size_t want = 0;
  while (in.Next(&line)) {
    const std::string where = path + ":" + std::to_string(in.line_number()) + ": ";
    const size_t start = line.find_first_not_of(" \t,");
    if (start == std::string_view::npos || line[start] == '#') continue;
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',')) ++i;
      if (i == line.size()) break;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != ',') ++j;
      const std::string_view token = line.substr(i, j - i);
      i = j;
      if (grid->nx == 0 || grid->ny == 0) {
        int size = 0;
        const std::string error = ParseNumber<int>(token, 2, kMaxGridSide, &size);
        if (!error.empty())
          return chi2::Status::Error(where + "grid size " + error +
                                     "; expected the grid size \"NX NY\" (integers) first");
        (grid->nx == 0 ? grid->nx : grid->ny) = size;
        if (grid->ny > 0) {
          want = size_t(grid->nx) * size_t(grid->ny);
          if (want > kMaxGridNodes)
            return chi2::Status::Error(where + "grid " + std::to_string(grid->nx) + " x " +
                                       std::to_string(grid->ny) + " has " +
                                       std::to_string(want) + " nodes; expected at most " +
                                       std::to_string(kMaxGridNodes));
        }
        continue;
      }
      double v = 0;
      const std::string error = ParseNumber<double>(token, 0, kMaxDensity, &v);
      if (!error.empty())
        return chi2::Status::Error(where + "density " + error);
      if (grid->values.size() == want)
        return chi2::Status::Error(where + "more than NX*NY = " + std::to_string(want) +
                                   " densities");
      grid->values.push_back(v);
    }
  }
  if (!in.status().ok()) return chi2::Status::Error(in.status().message());
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
