// Ray-sdfgrid intersection: clip to the grid box, walk the cells, solve the cubic per cell.
#include "engine/bvh/sdf_grid_intersect.h"

#include <algorithm>
#include <cmath>

namespace ptlab {
namespace {

struct Vec3d {
  double x, y, z;
};

// The first root of the cubic f(s) = ((c3 s + c2) s + c1) s + c0 in [0, len], or a negative
// value when f has none there.
double FirstCubicRoot(double c3, double c2, double c1, double c0, double len) {
  const auto f = [&](double s) { return ((c3 * s + c2) * s + c1) * s + c0; };
  // The ends of the monotone pieces: 0, the roots of f' = 3 c3 s² + 2 c2 s + c1 inside (0,
  // len) in increasing order, len.
  double ends[4];
  int n = 0;
  ends[n++] = 0.0;
  const double a = 3.0 * c3, b = 2.0 * c2, c = c1;
  if (a != 0.0) {
    const double disc = b * b - 4.0 * a * c;
    if (disc > 0.0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
      if (r0 > r1) std::swap(r0, r1);
      if (r0 > 0.0 && r0 < len) ends[n++] = r0;
      if (r1 > 0.0 && r1 < len && r1 != r0) ends[n++] = r1;
    }
  } else if (b != 0.0) {
    const double r = -c / b;
    if (r > 0.0 && r < len) ends[n++] = r;
  }
  ends[n++] = len;
  double lo = ends[0], f_lo = f(lo);
  if (f_lo == 0.0) return lo;
  for (int k = 1; k < n; ++k) {
    double hi = ends[k];
    const double f_hi = f(hi);
    if (f_hi == 0.0) return hi;
    if ((f_lo < 0.0) != (f_hi < 0.0)) {
      // Bisection on a monotone bracket until the midpoint is an end (double precision).
      for (int it = 0; it < 80; ++it) {
        const double m = 0.5 * (lo + hi);
        if (!(m > lo && m < hi)) break;
        const double f_m = f(m);
        if (f_m == 0.0) return m;
        if ((f_m < 0.0) == (f_lo < 0.0))
          lo = m, f_lo = f_m;
        else
          hi = m;
      }
      return hi;
    }
    lo = hi, f_lo = f_hi;
  }
  return -1.0;
}

}  // namespace

bool IntersectSdfGrid1(const SdfGridTable& grids, uint32_t row, const Ray& ray, float t_max,
                       float* t_out) {
  if (!(ray.t_min < t_max)) return false;
  const Matrix4& w2o = grids.to_world[row].inverse_matrix();
  const uint32_t nx = grids.nx[row], ny = grids.ny[row], nz = grids.nz[row];
  const double cells[3] = {double(nx - 1), double(ny - 1), double(nz - 1)};
  // The ray in index space (t is unchanged by an affine map of o and d).
  double o[3], d[3];
  for (int r = 0; r < 3; ++r) {
    const auto& m = w2o.m[r];
    o[r] = cells[r] * (double(m[0]) * ray.o.x + double(m[1]) * ray.o.y + double(m[2]) * ray.o.z +
                       double(m[3]));
    d[r] = cells[r] * (double(m[0]) * ray.d.x + double(m[1]) * ray.d.y + double(m[2]) * ray.d.z);
  }
  // Clip to the box [0, cells]: t0 .. t1.
  double t0 = ray.t_min, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (!(o[a] >= 0.0 && o[a] <= cells[a])) return false;
      continue;
    }
    double ta = (0.0 - o[a]) / d[a], tb = (cells[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return false;
  // The first cell: the one holding the point at t0 (clamped into the grid).
  int cell[3], step[3];
  double t_next[3], t_delta[3];
  const int last[3] = {int(nx) - 2, int(ny) - 2, int(nz) - 2};
  for (int a = 0; a < 3; ++a) {
    const double p = o[a] + t0 * d[a];
    cell[a] = std::clamp(int(std::floor(p)), 0, last[a]);
    if (d[a] > 0.0) {
      step[a] = 1, t_next[a] = (double(cell[a] + 1) - o[a]) / d[a], t_delta[a] = 1.0 / d[a];
    } else if (d[a] < 0.0) {
      step[a] = -1, t_next[a] = (double(cell[a]) - o[a]) / d[a], t_delta[a] = -1.0 / d[a];
    } else {
      step[a] = 0, t_next[a] = INFINITY, t_delta[a] = INFINITY;
    }
  }
  double t_enter = t0;
  while (t_enter <= t1) {
    const int axis = t_next[0] <= t_next[1] ? (t_next[0] <= t_next[2] ? 0 : 2)
                                            : (t_next[1] <= t_next[2] ? 1 : 2);
    const double t_exit = std::min(t_next[axis], t1);
    // The cell's eight values, v[i + 2 j + 4 k] at corner (i, j, k).
    float v[8];
    bool all_pos = true, all_neg = true;
    for (int c = 0; c < 8; ++c) {
      v[c] = grids.Value(row, uint32_t(cell[0] + (c & 1)), uint32_t(cell[1] + ((c >> 1) & 1)),
                         uint32_t(cell[2] + ((c >> 2) & 1)));
      all_pos = all_pos && v[c] > 0.0f, all_neg = all_neg && v[c] < 0.0f;
    }
    const bool occupied = !all_pos && !all_neg;
    if (occupied && t_exit >= t_enter) {
      // f(x, y, z) = a0 + a1 x + a2 y + a3 z + a4 x y + a5 y z + a6 x z + a7 x y z over the
      // cell's unit cube, along x = qx + s dx (q: the point at t_enter, cell-relative), ...
      const double a0 = v[0], a1 = double(v[1]) - v[0], a2 = double(v[2]) - v[0],
                   a3 = double(v[4]) - v[0];
      const double a4 = double(v[3]) - v[1] - v[2] + v[0];
      const double a5 = double(v[6]) - v[2] - v[4] + v[0];
      const double a6 = double(v[5]) - v[1] - v[4] + v[0];
      const double a7 =
          ((double(v[7]) - v[6]) - (double(v[5]) - v[4])) - ((double(v[3]) - v[2]) - (double(v[1]) - v[0]));
      const double qx = o[0] + t_enter * d[0] - cell[0], qy = o[1] + t_enter * d[1] - cell[1],
                   qz = o[2] + t_enter * d[2] - cell[2];
      const double dx = d[0], dy = d[1], dz = d[2];
      const double c0 = a0 + a1 * qx + a2 * qy + a3 * qz + a4 * qx * qy + a5 * qy * qz +
                        a6 * qx * qz + a7 * qx * qy * qz;
      const double c1 = a1 * dx + a2 * dy + a3 * dz + a4 * (qx * dy + qy * dx) +
                        a5 * (qy * dz + qz * dy) + a6 * (qx * dz + qz * dx) +
                        a7 * (qx * qy * dz + qx * qz * dy + qy * qz * dx);
      const double c2 = a4 * dx * dy + a5 * dy * dz + a6 * dx * dz +
                        a7 * (qx * dy * dz + qy * dx * dz + qz * dx * dy);
      const double c3 = a7 * dx * dy * dz;
      const double s = FirstCubicRoot(c3, c2, c1, c0, t_exit - t_enter);
      if (s >= 0.0) {
        const float t = float(t_enter + s);
        if (t > ray.t_min && t < t_max) {
          *t_out = t;
          return true;
        }
      }
    }
    if (t_exit >= t1) break;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] > last[axis]) break;
    t_enter = t_exit;
    t_next[axis] += t_delta[axis];
  }
  return false;
}

bool IntersectSdfGrids1(const SdfGridTable& grids, const Ray& ray, float* t_max, uint32_t* prim) {
  bool found = false;
  for (uint32_t i = 0; i < grids.size(); ++i) {
    float t = 0.0f;
    if (IntersectSdfGrid1(grids, i, ray, *t_max, &t)) {
      *t_max = t;
      *prim = 0x80000000u | kSdfGridHitBit | i;
      found = true;
    }
  }
  return found;
}

bool OccludedSdfGrids1(const SdfGridTable& grids, const Ray& ray) {
  float t = 0.0f;
  for (uint32_t i = 0; i < grids.size(); ++i)
    if (IntersectSdfGrid1(grids, i, ray, ray.t_max, &t)) return true;
  return false;
}

}  // namespace ptlab
