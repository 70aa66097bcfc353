// Zoomed equal-area map of the sphere onto the unit disk around a lobe's axis (a χ² domain).
#include "tools/chi2/lobe_disk.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "engine/core/check.h"

namespace ptlab {

LobeDisk::LobeDisk(const Vec3f& axis, double k) : k_(k), c_(0.5 * (2.0 + k)) {
  PTLAB_CHECK(k > 0);
  const double len =
      std::sqrt(double(axis.x) * axis.x + double(axis.y) * axis.y + double(axis.z) * axis.z);
  PTLAB_CHECK(len > 0);
  const double a[3] = {axis.x / len, axis.y / len, axis.z / len};
  // s: the unit vector of the least-aligned coordinate axis, made orthogonal to a; t = a × s.
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(a[i]) < std::fabs(a[m])) m = i;
  double s[3] = {0, 0, 0};
  s[m] = 1;
  const double d = s[m] * a[m];
  for (int i = 0; i < 3; ++i) s[i] -= d * a[i];
  const double sl = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; ++i) axis_[i] = a[i], s_[i] = s[i] / sl;
  t_[0] = a[1] * s_[2] - a[2] * s_[1];
  t_[1] = a[2] * s_[0] - a[0] * s_[2];
  t_[2] = a[0] * s_[1] - a[1] * s_[0];
}

Chi2Point LobeDisk::ToDisk(const Vec3f& w) const {
  const double v[3] = {w.x, w.y, w.z};
  double x = 0, y = 0, z = 0;
  for (int i = 0; i < 3; ++i) x += v[i] * s_[i], y += v[i] * t_[i], z += v[i] * axis_[i];
  const double q = std::hypot(x, y);
  if (!(q > 0)) return {0.0f, 0.0f, 0.0f};  // on the axis (or the antipode: one point)
  // γ from atan2 rather than acos(z): accurate for the tiny angles of sharp lobes.
  const double rho = 2.0 * std::sin(0.5 * std::atan2(q, z));
  const double r = c_ * rho / (rho + k_);
  return {float(r * x / q), float(r * y / q), 0.0f};
}

Vec3f LobeDisk::FromDisk(const Chi2Point& p, double* domega_da) const {
  const double px = p.x, py = p.y;
  const double r = std::min(std::hypot(px, py), 1.0);
  const double rho = std::min(r * k_ / (c_ - r), 2.0);
  *domega_da = (rho + k_) * (rho + k_) * (rho + k_) / (c_ * c_ * k_);
  // sinγ = ρ √(1 − ρ²/4) and ρ / r = k / (c − r): no 0/0 at the centre.
  const double sin_over_r = k_ / (c_ - r) * std::sqrt(std::max(0.0, 1.0 - 0.25 * rho * rho));
  const double x = sin_over_r * px, y = sin_over_r * py, z = 1.0 - 0.5 * rho * rho;
  double w[3];
  for (int i = 0; i < 3; ++i) w[i] = x * s_[i] + y * t_[i] + z * axis_[i];
  return {float(w[0]), float(w[1]), float(w[2])};
}

Chi2Subject OnLobeDisk(Chi2Subject subject, const LobeDisk& zoom) {
  PTLAB_CHECK(subject.domain.spherical());
  const Chi2Domain inner = subject.domain;
  // Where a direction outside the inner domain goes: outside the disk, so the lab reports it.
  auto map = [inner, zoom](Chi2Point* p) {
    if (!std::isfinite(p->x) || !std::isfinite(p->y) || !std::isfinite(p->z)) return;
    *p = Chi2Contains(inner, *p) ? zoom.ToDisk(*p) : Chi2Point{2.0f, 2.0f, 0.0f};
  };
  if (subject.sample) {
    subject.sample = [sample = std::move(subject.sample), map](float u1, const Vec2f& u2,
                                                               Chi2Point* p) {
      if (!sample(u1, u2, p)) return false;
      map(p);
      return true;
    };
  }
  if (subject.sample_batch) {
    subject.sample_batch = [batch = std::move(subject.sample_batch), map](
                               const float* u1, const Vec2f* u2, int n, Chi2Point* p, uint8_t* ok) {
      batch(u1, u2, n, p, ok);
      for (int i = 0; i < n; ++i)
        if (ok[i]) map(&p[i]);
    };
  }
  subject.pdf = [pdf = std::move(subject.pdf), zoom](const Chi2Point& p) {
    double domega_da;
    const Vec3f w = zoom.FromDisk(p, &domega_da);
    return pdf(w) * domega_da;
  };
  subject.domain = Chi2Domain::Disk();
  char buf[64];
  std::snprintf(buf, sizeof(buf), "zoom k=%g", zoom.k());
  subject.params += subject.params.empty() ? buf : std::string(" ") + buf;
  return subject;
}

Chi2PdfFn FlushLobeTail(Chi2PdfFn pdf, double peak) {
  PTLAB_CHECK(peak > 0 && std::isfinite(peak));
  const double floor = kChi2LobeTailFloor * peak;
  return [pdf = std::move(pdf), floor](const Chi2Point& p) {
    const double v = pdf(p);
    return (v >= 0 && v < floor) ? 0.0 : v;  // negative and NaN values stay: the lab reports them
  };
}

}  // namespace ptlab
