// Normals of an sdfgrid hit: cell gradients of the trilinear interpolant, smooth blend.
#include "engine/render/sdf_grid_normal.h"

#include <algorithm>
#include <cmath>

namespace ptlab {
namespace {

uint32_t Points(const SdfGridTable& g, uint32_t row, int a) {
  return a == 0 ? g.nx[row] : (a == 1 ? g.ny[row] : g.nz[row]);
}

void Normalize3(double v[3]) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (len > 0) v[0] /= len, v[1] /= len, v[2] /= len;
}

// Object-space vector n through to_world's inverse transpose, unit; false when it vanishes.
bool ToWorldNormal(const SdfGridTable& g, uint32_t row, const double n[3], Vec3f* out) {
  const Matrix4& inv = g.to_world[row].inverse_matrix();
  double w[3];
  for (int r = 0; r < 3; ++r)
    w[r] = double(inv.m[0][r]) * n[0] + double(inv.m[1][r]) * n[1] + double(inv.m[2][r]) * n[2];
  const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (!(len > 0) || !std::isfinite(len)) return false;
  *out = {float(w[0] / len), float(w[1] / len), float(w[2] / len)};
  return true;
}

}  // namespace

double SdfGridValueAt(const SdfGridTable& g, uint32_t row, const double p[3]) {
  uint32_t i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const uint32_t n = Points(g, row, a);
    const double u = std::clamp(p[a], 0.0, 1.0) * double(n - 1);
    i[a] = std::min(uint32_t(u), n - 2);
    f[a] = u - double(i[a]);
  }
  double x[4];
  for (int c = 0; c < 4; ++c) {
    const uint32_t j = i[1] + (c & 1), k = i[2] + (c >> 1);
    const double v0 = g.Value(row, i[0], j, k), v1 = g.Value(row, i[0] + 1, j, k);
    x[c] = v0 + f[0] * (v1 - v0);
  }
  const double y0 = x[0] + f[1] * (x[1] - x[0]), y1 = x[2] + f[1] * (x[3] - x[2]);
  return y0 + f[2] * (y1 - y0);
}

void SdfCellGradient(const SdfGridTable& g, uint32_t row, const double p[3], int ci, int cj,
                     int ck, double grad[3]) {
  const int cell[3] = {ci, cj, ck};
  for (int a = 0; a < 3; ++a) {
    const double size = 1.0 / double(Points(g, row, a) - 1);
    double lo[3] = {p[0], p[1], p[2]}, hi[3] = {p[0], p[1], p[2]};
    lo[a] = double(cell[a]) * size;
    hi[a] = lo[a] + size;
    grad[a] = (SdfGridValueAt(g, row, hi) - SdfGridValueAt(g, row, lo)) / size;
  }
}

void SdfGridNormals(const SdfGridTable& g, uint32_t row, const Vec3f& p_world, Vec3f* ng,
                    Vec3f* ns) {
  const Matrix4& w2o = g.to_world[row].inverse_matrix();
  double p[3], scaled[3];
  for (int r = 0; r < 3; ++r) {
    const auto& m = w2o.m[r];
    p[r] = double(m[0]) * p_world.x + double(m[1]) * p_world.y + double(m[2]) * p_world.z +
           double(m[3]);
    scaled[r] = p[r] * double(Points(g, row, r) - 1);
  }
  double grad[3];
  SdfCellGradient(g, row, p, int(scaled[0]), int(scaled[1]), int(scaled[2]), grad);
  if (!ToWorldNormal(g, row, grad, ng)) *ng = {0, 0, 1};
  if (g.normals[row] == SdfNormals::kAnalytic) {
    *ns = *ng;
    return;
  }
  // kSmooth: cells base + (a, b, c), base = round(scaled) − 1; weights from scaled − base − 0.5.
  int base[3];
  double w[3];
  for (int a = 0; a < 3; ++a) {
    base[a] = int(std::nearbyint(scaled[a])) - 1;
    w[a] = scaled[a] - double(base[a] + 1) + 0.5;
  }
  bool valid[8];
  double n[8][3];
  for (int c = 0; c < 8; ++c) {
    const int ci = base[0] + (c & 1), cj = base[1] + ((c >> 1) & 1), ck = base[2] + (c >> 2);
    valid[c] = ci >= 0 && cj >= 0 && ck >= 0;
    n[c][0] = n[c][1] = n[c][2] = 0.0;
    if (valid[c]) {
      SdfCellGradient(g, row, p, ci, cj, ck, n[c]);
      Normalize3(n[c]);
    }
  }
  // An axis whose side 0 (or 1) holds no valid cell gives all weight to the other side.
  for (int a = 0; a < 3; ++a) {
    bool any0 = false, any1 = false;
    for (int c = 0; c < 8; ++c) ((c >> a) & 1 ? any1 : any0) |= valid[c];
    if (!any0) w[a] = 1.0;
    if (!any1) w[a] = 0.0;
  }
  double blend[3] = {0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const double wc = (c & 1 ? w[0] : 1 - w[0]) * ((c >> 1) & 1 ? w[1] : 1 - w[1]) *
                      (c >> 2 ? w[2] : 1 - w[2]);
    for (int r = 0; r < 3; ++r) blend[r] += wc * n[c][r];
  }
  if (!ToWorldNormal(g, row, blend, ns)) *ns = *ng;
}

}  // namespace ptlab
