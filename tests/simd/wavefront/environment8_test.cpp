// simd::SampleEnvironmentBatch against its oracle ptlab::SampleEnvironmentBatch
// (SampleEnvironment per row), on every compiled target: radiance bit-identical, wi and pdf
// within simd/wavefront/environment8.h's contract, for 10^6 random rows and the hard cases (u = 0, the
// largest float below 1, CDF entries and plateaus of black rows and columns, tiny maps, out-of-
// range numbers and NaN where the map clamps them, batch tails), and no NaN or Inf out.
#include "simd/wavefront/environment8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/core/transform.h"
#include "engine/image/image_io.h"
#include "engine/wavefront/environment.h"
#include "engine/light/environment_map.h"
#include "engine/sampling/warp.h"
#include "simd/dispatched_target.h"
#include "simd/targets.h"  // first: the same target policy as simd/
#include "tests/simd/for_each_target.h"
#include "tests/simd/sample_columns.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

// The contract of simd/wavefront/environment8.h.
constexpr float kWiTolerance = 2e-6f;   // |Δ| per component
constexpr float kPdfTolerance = 2e-6f;  // relative

using test::SampleColumns;

// `random` random rows, then the hard cases: both numbers on the ends of [0, 1) and beyond it,
// on every CDF entry of the map (marginal and conditional) and one float below it, so that
// plateaus (black rows and columns: equal entries) and bin edges are hit.
void MakeRows(const EnvironmentMapTable& table, uint32_t map, size_t random, Pcg32& rng,
              std::vector<float>* u_x, std::vector<float>* u_y) {
  for (size_t i = 0; i < random; ++i)
    u_x->push_back(rng.NextFloat()), u_y->push_back(rng.NextFloat());
  std::vector<float> edges = {0.0f, -0.0f, 0x1.fffffep-1f, 1.0f, 2.0f, -1.0f, 1e-40f, 0.5f};
  if (table.sampling[map] == EnvironmentSampling::kImportance) {
    // Importance sampling clamps its numbers to [0, 1) and NaN to 0 (uniform sampling does not).
    edges.push_back(std::numeric_limits<float>::quiet_NaN());
    const Distribution2DView d = EnvironmentDistribution(table, map);
    const size_t entries = size_t(d.nv) + 1 + size_t(d.nv) * size_t(d.nu + 1);
    const size_t step = std::max<size_t>(1, entries / 4000);  // every entry of small maps
    for (size_t k = 0; k < entries; k += step) {
      const float c = k <= size_t(d.nv) ? d.marginal_cdf[k] : d.conditional_cdf[k - d.nv - 1];
      edges.push_back(c), edges.push_back(std::nextafter(c, 0.0f));
    }
  }
  for (float a : edges) {
    u_x->push_back(a), u_y->push_back(rng.NextFloat());
    u_x->push_back(rng.NextFloat()), u_y->push_back(a);
  }
  for (float a : {0.0f, 0x1.fffffep-1f, 1.0f})
    for (float b : {0.0f, 0x1.fffffep-1f, 1.0f}) u_x->push_back(a), u_y->push_back(b);
}

void ExpectBatchMatchesOracle(const EnvironmentMapTable& guided, uint32_t map, size_t random) {
  Pcg32 rng(7, 11);
  std::vector<float> u_x, u_y;
  MakeRows(guided, map, random, rng, &u_x, &u_y);
  const size_t n = u_x.size();
  const EnvironmentBatchInputs in{u_x.data(), u_y.data()};
  SampleColumns want(n);
  SampleEnvironmentBatch(guided, map, n, in, want.Out());
  // The guide tables change how the 8-wide search finds a bin, not which: the batch is held
  // to the same contract with them and without them (a whole-CDF bisection).
  EnvironmentMapTable copy = guided;
  copy.marginal_guide.clear(), copy.conditional_guide.clear();
  const EnvironmentMapTable& unguided = copy;
  ASSERT_EQ(EnvironmentDistribution(unguided, map).marginal_guide, nullptr);
  for (const EnvironmentMapTable* table : {&guided, &unguided}) {
    test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
      // Every tail length: batches of n, and of n - 1 ... n - 7 rows.
      float seen_wi = 0, seen_pdf = 0;
      for (size_t cut = 0; cut < 8; ++cut) {
        const size_t m = n - cut;
        SampleColumns got(m);
        simd::SampleEnvironmentBatch(*table, map, m, in, got.Out());
        const test::SampleColumnsDiff diff =
            test::ExpectSampleColumnsMatch(got, want, m, kWiTolerance, kPdfTolerance);
        seen_wi = std::max(seen_wi, diff.seen_wi), seen_pdf = std::max(seen_pdf, diff.seen_pdf);
        const size_t first = diff.first;
        if (first < m) {
          ADD_FAILURE() << "row " << first << " u = (" << u_x[first] << ", " << u_y[first]
                        << "): pdf " << got.col[6][first] << " want " << want.col[6][first];
          break;
        }
      }
      std::printf("  %s: %zu rows, seen |Δwi| %.3g, pdf rel %.3g\n", target, n, double(seen_wi),
                  double(seen_pdf));
    });
  }
}

EnvironmentMapTable OneMap(const Image& image,
                           EnvironmentSampling sampling = EnvironmentSampling::kImportance,
                           const Frame& to_world = Frame{},
                           EnvironmentRows rows = EnvironmentRows::kCentred) {
  EnvironmentMapTable table;
  EnvironmentMapDesc desc;
  desc.sampling = sampling;
  desc.to_world = to_world;
  desc.rows = rows;
  const StatusOr<uint32_t> row = AddEnvironmentMap(image, desc, "test", &table);
  EXPECT_TRUE(row.ok() && *row == 0);
  return table;
}

// A w × h map of random colours with black rows and columns (CDF plateaus) where asked.
Image RandomMap(int w, int h, bool black_lines, Pcg32& rng) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool black = black_lines && (y % 4 == 1 || x % 5 == 2 || (y >= h / 2 && y < h / 2 + 3));
      const float s = black ? 0.0f : 10.0f * rng.NextFloat() * rng.NextFloat();
      image.Set(x, y, {s * rng.NextFloat(), s * rng.NextFloat(), s * rng.NextFloat()});
    }
  return image;
}

// A map frame turned 40° about (1, 2, 3): no axis of the map is a world axis.
Frame RotatedFrame() {
  const Transform rotate = Transform::Rotate(Normalize(Vec3f{1, 2, 3}), 40);
  Frame f;
  f.s = rotate.ApplyVector({1, 0, 0}), f.t = rotate.ApplyVector({0, 1, 0});
  f.n = rotate.ApplyVector({0, 0, 1});
  return f;
}

const std::string kEnvmaps = test_data::Path("envmaps/");

void ExpectMatchesOnFile(const std::string& file) {
  const std::string path = kEnvmaps + file;
  PTLAB_REQUIRE_DATA(path);
  const StatusOr<Image> image = ReadImage(path);
  ASSERT_TRUE(image.ok()) << image.status().message();
  ExpectBatchMatchesOracle(OneMap(*image), 0, 1000003);
}

TEST(Environment8, BatchMatchesOracleOnVenice) { ExpectMatchesOnFile("venice_sunset_1k.exr"); }

TEST(Environment8, BatchMatchesOracleOnPedestrianOverpass) {
  ExpectMatchesOnFile("pedestrian_overpass_1k.exr");
}

TEST(Environment8, BatchMatchesOracleOnBlackRowsAndColumnsRotated) {
  Pcg32 rng(3, 5);
  const Frame f = RotatedFrame();
  ExpectBatchMatchesOracle(
      OneMap(RandomMap(37, 23, true, rng), EnvironmentSampling::kImportance, f), 0, 1000003);
}

TEST(Environment8, BatchMatchesOracleOnTinyMaps) {
  Pcg32 rng(9, 1);
  for (const auto& [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {3, 2}, {2, 3}, {1, 7}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    ExpectBatchMatchesOracle(OneMap(RandomMap(w, h, false, rng)), 0, 100003);
  }
  // One hot pixel in black: every other cell is a plateau.
  Image hot(16, 8);
  hot.Set(11, 3, {50.0f, 40.0f, 30.0f});
  ExpectBatchMatchesOracle(OneMap(hot), 0, 100003);
}

TEST(Environment8, UniformAndBlackMapsTakeTheScalarRows) {
  Pcg32 rng(4, 4);
  ExpectBatchMatchesOracle(OneMap(RandomMap(8, 4, false, rng), EnvironmentSampling::kUniform), 0,
                           10003);
  // A black map gives no sample: every row all zero on both paths.
  const EnvironmentMapTable black = OneMap(Image(8, 4));
  ExpectBatchMatchesOracle(black, 0, 10003);
  std::vector<float> u(17, 0.25f), pdf(17, -1.0f), wi(17 * 6, -1.0f);
  simd::SampleEnvironmentBatch(black, 0, 17, {u.data(), u.data()},
                               {wi.data(), wi.data() + 17, wi.data() + 34, wi.data() + 51,
                                wi.data() + 68, wi.data() + 85, pdf.data()});
  for (float p : pdf) EXPECT_EQ(p, 0.0f);
}

// Escaping directions for the evaluation: `random` uniform ones, then the hard cases: the
// axes with ±0 components (poles, the φ seam), directions just off the poles, and the
// directions of cell edges and pixel centres of the map (where the pdf's cell and the lookup's
// pixels change), in local coordinates turned to world by the map's frame.
std::vector<Vec3f> EvalDirections(const EnvironmentMapTable& table, uint32_t map, size_t random,
                                  Pcg32& rng) {
  std::vector<Vec3f> local;
  for (size_t i = 0; i < random; ++i) {
    const float a = rng.NextFloat();
    local.push_back(SampleUniformSphere({a, rng.NextFloat()}));
  }
  for (float a : {1.0f, -1.0f})
    for (float z : {0.0f, -0.0f}) {
      local.push_back({a, z, z}), local.push_back({z, a, z}), local.push_back({z, z, a});
      local.push_back({z, a, -z}), local.push_back({-z, z, a});
    }
  for (float e : {1e-30f, 1e-12f, 1e-6f, 1e-3f})
    for (float y : {1.0f, -1.0f}) local.push_back(Normalize(Vec3f{e, y, -e}));
  // Pixel points and cell edges in v: of the pixel bands (kCentred), and of the bands
  // between pixel rows (kAtPoles: pixel rows at j/(H − 1), cells between them).
  const int w = table.width[map], h = table.height[map], nv = EnvironmentCellRows(table, map);
  const int step = std::max(1, std::max(w, h) / 200);
  for (const int rows : {h, nv}) {
    if (rows == h && rows == nv && &rows != &h) continue;  // kCentred: the grid once
    for (int j = 0; j <= 2 * rows; j += step)
      for (int i = 0; i <= 2 * w; i += step)
        local.push_back(
            EnvironmentUvToDirection({float(i) / float(2 * w), float(j) / float(2 * rows)}));
  }
  const Frame& f = table.to_world[map];
  std::vector<Vec3f> world;
  for (const Vec3f& d : local) world.push_back(f.ToWorld(d));
  return world;
}

// The largest pixel value (any channel) of the 4 × 4 pixels around (u, v): what bounds the
// change of the bilinear lookup when (u, v) moves by a few ulp.
float LargestPixelAround(const EnvironmentMapTable& table, uint32_t map, Vec2f uv) {
  const int w = table.width[map], h = table.height[map];
  const int x = int(std::floor(uv.x * float(w) - 0.5f)),
            y = int(std::floor(uv.y * float(h) - 0.5f));
  float largest = 0;
  for (int dy = -1; dy <= 2; ++dy)
    for (int dx = -1; dx <= 2; ++dx) {
      const int px = ((x + dx) % w + w) % w, py = std::clamp(y + dy, 0, h - 1);
      const float* t =
          &table.texels[(table.pixel_offset[map] + size_t(py) * size_t(w) + size_t(px)) *
                        kEnvironmentTexel];
      largest = std::max({largest, t[0], t[1], t[2]});
    }
  return largest;
}

// True when x·n lies within 1e-3 of an integer: a cell edge, where (u, v) a few ulp off may
// fall in the neighbouring cell.
bool NearCellEdge(float x, int n) {
  const float t = x * float(n);
  return std::abs(t - std::round(t)) < 1e-3f;
}

void ExpectEvalMatchesOracle(const EnvironmentMapTable& table, uint32_t map, size_t random) {
  Pcg32 rng(13, 17);
  const std::vector<Vec3f> dirs = EvalDirections(table, map, random, rng);
  const size_t n = dirs.size();
  std::vector<float> w_x(n), w_y(n), w_z(n);
  for (size_t i = 0; i < n; ++i) w_x[i] = dirs[i].x, w_y[i] = dirs[i].y, w_z[i] = dirs[i].z;
  const EnvironmentEvalInputs in{w_x.data(), w_y.data(), w_z.data()};
  std::vector<float> want(4 * n);
  EvalEnvironmentBatch(table, map, n, in,
                       {want.data(), want.data() + n, want.data() + 2 * n, want.data() + 3 * n});
  for (size_t i = 0; i < n; ++i) {  // the oracle is the two scalar functions
    ASSERT_EQ(want[i], EnvironmentRadiance(table, map, dirs[i]).r);
    ASSERT_EQ(want[3 * n + i], EnvironmentPdf(table, map, dirs[i]));
  }
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char* target) {
    std::vector<float> got(4 * n, -1.0f), no_pdf(3 * n, -1.0f);
    simd::EvalEnvironmentBatch(
        table, map, n, in, {got.data(), got.data() + n, got.data() + 2 * n, got.data() + 3 * n});
    // Without a pdf column the radiance is the same.
    simd::EvalEnvironmentBatch(table, map, n, in,
                               {no_pdf.data(), no_pdf.data() + n, no_pdf.data() + 2 * n, nullptr});
    size_t edge_pdfs = 0;
    float seen_radiance = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec2f uv = EnvironmentDirectionToUv(table.to_world[map].ToLocal(dirs[i]));
      const float scale = LargestPixelAround(table, map, uv);
      for (size_t c = 0; c < 3; ++c) {
        const float g = got[c * n + i], o = want[c * n + i];
        ASSERT_TRUE(std::isfinite(g)) << "row " << i;
        ASSERT_EQ(g, no_pdf[c * n + i]) << "row " << i;
        const float off = std::abs(g - o);
        if (scale > 0) seen_radiance = std::max(seen_radiance, off / scale);
        ASSERT_LE(off, 1e-3f * scale) << "row " << i << " channel " << c << " uv " << uv.x << ", "
                                      << uv.y << ": " << g << " want " << o;
      }
      const float g = got[3 * n + i], o = want[3 * n + i];
      ASSERT_TRUE(std::isfinite(g) && g >= 0) << "row " << i << " pdf " << g;
      if (g == o) continue;  // the same cell: the oracle's operations on the same numbers
      ASSERT_TRUE(NearCellEdge(uv.x, table.width[map]) ||
                  NearCellEdge(uv.y, EnvironmentCellRows(table, map)))
          << "row " << i << " uv " << uv.x << ", " << uv.y << ": pdf " << g << " want " << o;
      ++edge_pdfs;
    }
    std::printf(
        "  %s: %zu rows, radiance |Δ|/largest pixel %.3g, %zu pdfs of the neighbouring "
        "cell at cell edges\n",
        target, n, double(seen_radiance), edge_pdfs);
  });
}

TEST(Environment8, EvalMatchesOracleOnVenice) {
  const std::string path = kEnvmaps + "venice_sunset_1k.exr";
  PTLAB_REQUIRE_DATA(path);
  const StatusOr<Image> image = ReadImage(path);
  ASSERT_TRUE(image.ok()) << image.status().message();
  ExpectEvalMatchesOracle(OneMap(*image), 0, 1000003);
}

TEST(Environment8, EvalMatchesOracleOnBlackRowsRotatedTinyAndUniformMaps) {
  Pcg32 rng(3, 5);
  const Frame f = RotatedFrame();
  ExpectEvalMatchesOracle(OneMap(RandomMap(37, 23, true, rng), EnvironmentSampling::kImportance, f),
                          0, 100003);
  for (const auto& [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {3, 2}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    ExpectEvalMatchesOracle(OneMap(RandomMap(w, h, false, rng)), 0, 10003);
  }
  ExpectEvalMatchesOracle(OneMap(RandomMap(8, 4, false, rng), EnvironmentSampling::kUniform), 0,
                          10003);
  ExpectEvalMatchesOracle(OneMap(Image(8, 4)), 0, 10003);  // black
}

// Mitsuba 3's rows (kAtPoles): pixel rows on the poles, H − 1 cell rows; the same contracts.
TEST(Environment8, BatchMatchesOracleOnAtPolesMaps) {
  Pcg32 rng(21, 8);
  const Frame f = RotatedFrame();
  ExpectBatchMatchesOracle(OneMap(RandomMap(37, 23, true, rng), EnvironmentSampling::kImportance,
                                  f, EnvironmentRows::kAtPoles),
                           0, 300007);
  for (const auto& [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {3, 2}, {2, 3}, {1, 7}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    ExpectBatchMatchesOracle(OneMap(RandomMap(w, h, false, rng), EnvironmentSampling::kImportance,
                                    Frame{}, EnvironmentRows::kAtPoles),
                             0, 100003);
  }
}

TEST(Environment8, EvalMatchesOracleOnAtPolesMaps) {
  Pcg32 rng(22, 9);
  const Frame f = RotatedFrame();
  ExpectEvalMatchesOracle(OneMap(RandomMap(37, 23, true, rng), EnvironmentSampling::kImportance,
                                 f, EnvironmentRows::kAtPoles),
                          0, 100003);
  for (const auto& [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {3, 2}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    ExpectEvalMatchesOracle(OneMap(RandomMap(w, h, false, rng), EnvironmentSampling::kImportance,
                                   Frame{}, EnvironmentRows::kAtPoles),
                            0, 10003);
  }
  ExpectEvalMatchesOracle(OneMap(RandomMap(8, 4, false, rng), EnvironmentSampling::kUniform,
                                 Frame{}, EnvironmentRows::kAtPoles),
                          0, 10003);
}

}  // namespace
}  // namespace ptlab
