// Chi-square subjects of the infinite lights and of the piecewise-constant distributions.
#include "tools/chi2/light_subjects.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "engine/core/check.h"
#include "engine/core/rng.h"
#include "engine/core/transform.h"
#include "engine/image/image_io.h"
#include "engine/light/distant_disk.h"
#include "engine/wavefront/environment.h"
#include "engine/light/environment_map.h"
#include "engine/sampling/distribution2d.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/distant_disk8.h"
#include "simd/wavefront/environment8.h"

namespace ptlab {
namespace {

using EnvTable = std::shared_ptr<const EnvironmentMapTable>;

// A 16x8 map whose luminance varies smoothly down the rows and jumps between columns.
Image GradientMap() {
  Image image(16, 8);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      image.Set(i, j,
                {0.2f + float(i) / 16.0f, 0.1f + 2.0f * float(j) / 8.0f,
                 0.5f + float((i * 7 + j * 3) % 5) / 5.0f});
  return image;
}

// One hot pixel in a black 32x16 map.
Image HotPixelMap() {
  Image image(32, 16);
  image.Set(21, 5, {50.0f, 40.0f, 30.0f});
  return image;
}

// Bright rows at both poles (sinθ -> 0 there), dim elsewhere.
Image PoleRowsMap() {
  Image image(16, 8);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      image.Set(i, j,
                (j == 0 || j == 7) ? Color3f{20.0f + float(i), 10.0f, 5.0f}
                                   : Color3f{0.05f, 0.05f, 0.05f});
  return image;
}

// Box filter to out_w x out_h (each output pixel = mean of the input pixels mapped to it).
Image Downsample(const Image& in, int out_w, int out_h) {
  Image out(out_w, out_h);
  std::vector<double> sum(size_t(out_w) * out_h * 3, 0.0), count(size_t(out_w) * out_h, 0.0);
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      const size_t k = size_t(y * out_h / in.height) * out_w + size_t(x * out_w / in.width);
      const Color3f c = in.At(x, y);
      sum[3 * k] += c.r, sum[3 * k + 1] += c.g, sum[3 * k + 2] += c.b;
      count[k] += 1;
    }
  }
  for (size_t k = 0; k < count.size(); ++k)
    for (int c = 0; c < 3; ++c) out.rgb[3 * k + c] = float(sum[3 * k + c] / count[k]);
  return out;
}

// The rotation part of a transform as a Frame (columns = images of the local axes).
Frame FrameOf(const Transform& t) {
  Frame f;
  f.s = Normalize(t.ApplyVector({1, 0, 0}));
  f.t = Normalize(t.ApplyVector({0, 1, 0}));
  f.n = Normalize(t.ApplyVector({0, 0, 1}));
  return f;
}

EnvTable MakeEnv(const Image& image, EnvironmentSampling sampling, const Frame& to_world,
                 EnvironmentRows rows = EnvironmentRows::kCentred) {
  auto table = std::make_shared<EnvironmentMapTable>();
  EnvironmentMapDesc desc;
  desc.sampling = sampling;
  desc.to_world = to_world;
  desc.rows = rows;
  const StatusOr<uint32_t> row = AddEnvironmentMap(image, desc, "chi2 subject", table.get());
  PTLAB_CHECK(row.ok() && *row == 0);
  return table;
}

Chi2Subject EnvSubject(std::string name, EnvTable table, std::string params,
                       Chi2Expect expect = Chi2Expect::kPass) {
  Chi2Subject s = DirectionWarpSubject(
      std::move(name), Chi2Domain::Sphere(),
      [table](const Vec2f& u) {
        EnvironmentSample es;
        // Only a black map returns no sample; the lab would report (0, 0, 0) as outside.
        return SampleEnvironment(*table, 0, u, &es) ? es.wi : Vec3f{};
      },
      [table](const Vec3f& w) { return EnvironmentPdf(*table, 0, w); }, expect);
  s.params = std::move(params);
  return s;
}

constexpr int kRows = 1024;  // rows of one call of the SIMD batch

// `s` with its samples drawn by `batch` (a SIMD batch over EnvironmentBatch columns, called
// as batch(n, in, out) with up to 1024 rows) instead of its scalar sampler; renamed `name`,
// the SIMD target in its params. The pdf stays the scalar one.
template <class Batch>
Chi2Subject DrawnByColumnBatch(Chi2Subject s, std::string name, const char* target, Batch batch) {
  s.name = std::move(name);
  s.params += std::string(" target=") + target;
  s.sample_batch = [batch](const float*, const Vec2f* u, int n, Chi2Point* p, uint8_t* ok) {
    float u_x[kRows], u_y[kRows], wi_x[kRows], wi_y[kRows], wi_z[kRows], r[kRows], g[kRows],
        b[kRows], pdf[kRows];
    for (int begin = 0; begin < n; begin += kRows) {
      const int count = std::min(kRows, n - begin);
      for (int i = 0; i < count; ++i) u_x[i] = u[begin + i].x, u_y[i] = u[begin + i].y;
      batch(size_t(count), EnvironmentBatchInputs{u_x, u_y},
            EnvironmentBatchOutputs{wi_x, wi_y, wi_z, r, g, b, pdf});
      for (int i = 0; i < count; ++i) {
        ok[begin + i] = pdf[i] > 0 ? 1 : 0;
        p[begin + i] = {wi_x[i], wi_y[i], wi_z[i]};
      }
    }
  };
  return s;
}

// `s` with its samples drawn by simd::SampleEnvironmentBatch on row 0 of `table`.
Chi2Subject DrawnBySimdBatch(Chi2Subject s, std::string name, EnvTable table) {
  return DrawnByColumnBatch(
      std::move(s), std::move(name), simd::DispatchedTargetName(),
      [table](size_t n, const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
        simd::SampleEnvironmentBatch(*table, 0, n, in, out);
      });
}

// Broken: the pdf of `table` (the gradient map under y_to_z) read half a cell off in φ (a
// rotation about the map's up axis: the mass stays 1, only the χ² statistic can see it).
Chi2Subject HalfPixelShiftSubject(std::string name, EnvTable table) {
  const float half_cell = kPi / float(table->width[0]);
  const float c = std::cos(half_cell), sn = std::sin(half_cell);
  Chi2Subject s = DirectionWarpSubject(
      std::move(name), Chi2Domain::Sphere(),
      [table](const Vec2f& u) {
        EnvironmentSample es;
        return SampleEnvironment(*table, 0, u, &es) ? es.wi : Vec3f{};
      },
      [table, c, sn](const Vec3f& w) {
        // A rotation about world z = the map's up axis under y_to_z.
        return EnvironmentPdf(*table, 0, {c * w.x - sn * w.y, sn * w.x + c * w.y, w.z});
      },
      Chi2Expect::kFail);
  s.params = "16x8 gradient, pdf turned by pi/16 about the up axis";
  return s;
}

Chi2Subject DiskSubject(std::string name, std::shared_ptr<const DistantDiskTable> table,
                        std::string params) {
  Chi2Subject s = DirectionWarpSubject(
      std::move(name), Chi2Domain::Sphere(),
      [table](const Vec2f& u) {
        EnvironmentSample es;
        return SampleDistantDisk(*table, 0, u, &es) ? es.wi : Vec3f{};
      },
      [table](const Vec3f& w) { return DistantDiskPdf(*table, 0, w); });
  s.params = std::move(params);
  return s;
}

std::shared_ptr<const DistantDiskTable> MakeDisk(float theta_a, const Frame& to_world) {
  auto table = std::make_shared<DistantDiskTable>();
  PTLAB_CHECK(AddDistantDisk({1, 1, 1}, theta_a, to_world, "chi2 subject", table.get()).ok());
  return table;
}

// Random weights in [0, 1) with every fifth one (and, in 2-D, row 2) zero.
std::vector<float> RandomWeights(int n, int zero_row_begin, int zero_row_end) {
  Pcg32 rng(7, 11);
  std::vector<float> w(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    w[size_t(k)] =
        (k % 5 == 3 || (k >= zero_row_begin && k < zero_row_end)) ? 0.0f : rng.NextFloat();
  return w;
}

}  // namespace

std::string DefaultLightDataDir() {
  // The tests' rule (tests/test_data.h, docs/data.md): $PTLAB_DATA, else beside the checkout.
  if (const char* env = std::getenv("PTLAB_DATA"); env != nullptr && *env != '\0') return env;
  // This file is <source>/tools/chi2/light_subjects.cpp.
  return (std::filesystem::path(__FILE__).parent_path() / "../../../shared/data")
      .lexically_normal()
      .string();
}

void RegisterLightSubjects(Chi2Registry* r) { RegisterLightSubjects(r, DefaultLightDataDir()); }

void RegisterLightSubjects(Chi2Registry* r, const std::string& data_dir) {
  constexpr EnvironmentSampling kImportance = EnvironmentSampling::kImportance;
  const Frame identity;
  // The importance pdf grows as 1/sinθ towards the map's poles (finite mass, unbounded density).
  // The lab's Simpson rule cannot integrate such a point singularity inside the (φ, cosθ)
  // rectangle, so every map is turned to put its poles on the domain's poles (cosθ = ±1, where
  // the singularity is 1/sqrt(1 - z²) at the end of each column and integrates well), with
  // exact 0/±1 entries so that the pole itself evaluates to 0. y_to_z: up (+y) -> +z;
  // y_to_minus_z: up -> -z, and local x -> +y (φ turned by 90°).
  Frame y_to_z;
  y_to_z.s = {1, 0, 0}, y_to_z.t = {0, 0, 1}, y_to_z.n = {0, -1, 0};
  Frame y_to_minus_z;
  y_to_minus_z.s = {0, 1, 0}, y_to_minus_z.t = {0, 0, -1}, y_to_minus_z.n = {-1, 0, 0};

  // Each importance map twice: "envmap/<what>" drawn by SampleEnvironment and
  // "simd/env_<what>" drawn by simd::SampleEnvironmentBatch, against the same scalar pdf.
  const auto add_importance = [r](const std::string& what, const EnvTable& table,
                                  const std::string& params) {
    const Chi2Subject scalar = EnvSubject("envmap/" + what, table, params);
    r->Add(scalar);
    r->Add(DrawnBySimdBatch(scalar, "simd/env_" + what, table));
  };
  const EnvTable gradient = MakeEnv(GradientMap(), kImportance, y_to_z);
  add_importance("importance_gradient", gradient, "16x8 gradient, up -> +z");
  add_importance("importance_hot_pixel", MakeEnv(HotPixelMap(), kImportance, y_to_z),
                 "32x16, one hot pixel at (21, 5), up -> +z");
  add_importance("importance_pole_rows", MakeEnv(PoleRowsMap(), kImportance, y_to_z),
                 "16x8, bright rows 0 and 7 (at the poles), up -> +z");
  Image one(1, 1);
  one.Set(0, 0, {0.3f, 0.6f, 0.9f});
  add_importance("importance_1x1", MakeEnv(one, kImportance, y_to_z), "1x1, up -> +z");
  add_importance("importance_rotated_gradient", MakeEnv(GradientMap(), kImportance, y_to_minus_z),
                 "16x8 gradient, up -> -z, local x -> +y");
  // Mitsuba 3's rows (kAtPoles: pixel rows 0 and H − 1 on the poles, H − 1 cell rows).
  constexpr EnvironmentRows kAtPoles = EnvironmentRows::kAtPoles;
  add_importance("importance_at_poles_gradient",
                 MakeEnv(GradientMap(), kImportance, y_to_z, kAtPoles),
                 "16x8 gradient, rows at the poles (Mitsuba 3), up -> +z");
  add_importance("importance_at_poles_hot_pixel",
                 MakeEnv(HotPixelMap(), kImportance, y_to_z, kAtPoles),
                 "32x16, one hot pixel at (21, 5), rows at the poles (Mitsuba 3), up -> +z");
  add_importance("importance_at_poles_pole_rows",
                 MakeEnv(PoleRowsMap(), kImportance, y_to_z, kAtPoles),
                 "16x8, bright rows 0 and 7 on the poles (Mitsuba 3), up -> +z");
  // Uniform sampling has no singularity: the map keeps its default orientation.
  r->Add(EnvSubject("envmap/uniform_gradient",
                    MakeEnv(GradientMap(), EnvironmentSampling::kUniform, identity),
                    "16x8 gradient, sampling = uniform, toWorld = identity"));
  const std::string venice = data_dir + "/envmaps/venice_sunset_1k.exr";
  if (std::filesystem::exists(venice)) {
    const StatusOr<Image> image = ReadImage(venice);
    if (image.ok())
      add_importance("importance_venice_32x16",
                     MakeEnv(Downsample(*image, 32, 16), kImportance, y_to_z),
                     "venice_sunset_1k.exr box-filtered to 32x16, up -> +z");
  }

  // Each disk twice: "distantdisk/<what>" drawn by SampleDistantDisk and
  // "simd/distant_disk_<what>" drawn by simd::SampleDistantDiskBatch, against the same pdf.
  const auto add_disk = [r](const std::string& what,
                            const std::shared_ptr<const DistantDiskTable>& table,
                            const std::string& params) {
    const Chi2Subject scalar = DiskSubject("distantdisk/" + what, table, params);
    r->Add(scalar);
    r->Add(DrawnByColumnBatch(
        scalar, "simd/distant_disk_" + what, simd::DispatchedTargetName(),
        [table](size_t n, const EnvironmentBatchInputs& in, const EnvironmentBatchOutputs& out) {
          simd::SampleDistantDiskBatch(*table, 0, n, in, out);
        }));
  };
  add_disk("cone_10deg_rotated", MakeDisk(10, FrameOf(Transform::Rotate({1, 0, 0}, 45))),
           "thetaA = 10, toWorld = rotate x 45 (sphere_side)");
  add_disk("cone_90deg", MakeDisk(90, FrameOf(Transform::Rotate({0, 1, 0}, 90))),
           "thetaA = 90 around +x");
  add_disk("full_sphere", MakeDisk(180, identity), "thetaA = 180");

  {
    const std::vector<float> w = RandomWeights(12, 0, 0);
    auto d = std::make_shared<const Distribution1D>(w.data(), int(w.size()));
    Chi2Subject s = PlanarWarpSubject(
        "distribution/1d", Chi2Domain::UnitSquare(),
        [d](const Vec2f& u) {
          float x, pdf;
          return d->Sample(u.x, &x, &pdf) ? Vec2f{x, u.y} : Vec2f{-1, -1};
        },
        [d](const Vec2f& p) { return (p.y >= 0 && p.y <= 1) ? d->Pdf(p.x) : 0.0f; });
    s.params = "12 random bins, every fifth 0; y uniform";
    r->Add(std::move(s));
  }
  {
    const std::vector<float> w = RandomWeights(7 * 5, 2 * 7, 3 * 7);
    auto d = std::make_shared<const Distribution2D>(w.data(), 7, 5);
    Chi2Subject s = PlanarWarpSubject(
        "distribution/2d", Chi2Domain::UnitSquare(),
        [d](const Vec2f& u) {
          Vec2f p;
          float pdf;
          return SampleDistribution2D(d->view(), u, &p, &pdf) ? p : Vec2f{-1, -1};
        },
        [d](const Vec2f& p) { return Distribution2DPdf(d->view(), p); });
    s.params = "7x5 random cells, every fifth 0, row 2 empty";
    r->Add(std::move(s));
  }

  r->Add(HalfPixelShiftSubject("broken/envmap_pdf_half_pixel_shift", gradient));
  r->Add(DrawnBySimdBatch(HalfPixelShiftSubject("", gradient),
                          "broken/simd_env_pdf_half_pixel_shift", gradient));
  // Broken: uniform samples in a 60° cone claimed to be cosine-weighted (also mass 1).
  {
    const auto disk = MakeDisk(60, identity);
    const float cos_a = 0.5f;  // cos 60°
    r->Add(DirectionWarpSubject(
        "broken/distantdisk_pdf_cos_weighted", Chi2Domain::Sphere(),
        [disk](const Vec2f& u) {
          EnvironmentSample es;
          return SampleDistantDisk(*disk, 0, u, &es) ? es.wi : Vec3f{};
        },
        [cos_a](const Vec3f& w) {
          return w.z >= cos_a ? w.z / (kPi * (1.0f - cos_a * cos_a)) : 0.0f;
        },
        Chi2Expect::kFail));
  }
}

}  // namespace ptlab
