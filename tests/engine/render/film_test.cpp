// Film and pixel filters: splat weights, Nori's filter shapes, block merging.
#include "engine/render/film.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace ptlab {
namespace {

TEST(PixelFilter, NoriShapes) {
  const PixelFilter gauss(FilterDesc{FilterDesc::Type::kGaussian, 2.0f, 0.5f});
  const float tail = std::exp(-2.0f * 4.0f);
  EXPECT_FLOAT_EQ(gauss.EvalExact(0), 1.0f - tail);
  EXPECT_FLOAT_EQ(gauss.EvalExact(0.5f), std::exp(-0.5f) - tail);
  EXPECT_FLOAT_EQ(gauss.EvalExact(2.0f), 0.0f);
  EXPECT_FLOAT_EQ(gauss.EvalExact(2.5f), 0.0f);
  const PixelFilter tent(FilterDesc{FilterDesc::Type::kTent, 1.0f, 0});
  EXPECT_FLOAT_EQ(tent.EvalExact(0.25f), 0.75f);
  const PixelFilter box(FilterDesc{FilterDesc::Type::kBox, 0.5f, 0});
  EXPECT_FLOAT_EQ(box.EvalExact(0.49f), 1.0f);
  EXPECT_FLOAT_EQ(box.EvalExact(0.51f), 0.0f);
}

// The film's table lookup against the analytic filter, densely over [-r - 0.5, r + 0.5] and at
// the table's own samples, within filter.h's bound: h²/(8σ²) for the Gaussian (linear
// interpolation of a function whose |f''| ≤ 1/σ²), rounding (1e-6) for the tent, exact for the
// box; zero beyond the radius, finite and ≥ 0 everywhere.
TEST(PixelFilter, TableMatchesAnalyticFilter) {
  struct Case {
    FilterDesc desc;
    double tol;
  };
  std::vector<Case> cases;
  for (const float radius : {0.5f, 1.0f, 2.0f, 3.0f}) {
    for (const float stddev : {0.25f, 0.5f, 1.0f}) {
      const double h = double(radius) / kFilterTableSize;
      cases.push_back({FilterDesc{FilterDesc::Type::kGaussian, radius, stddev},
                       h * h / (8.0 * stddev * stddev) + 1e-6});
    }
    cases.push_back({FilterDesc{FilterDesc::Type::kTent, radius, 0}, 1e-6});
    cases.push_back({FilterDesc{FilterDesc::Type::kBox, radius, 0}, 0.0});
  }
  for (const Case& c : cases) {
    const PixelFilter f(c.desc);
    const float r = c.desc.radius;
    SCOPED_TRACE("type " + std::to_string(int(c.desc.type)) + " radius " + std::to_string(r) +
                 " stddev " + std::to_string(c.desc.stddev));
    double worst = 0;
    constexpr int kSteps = 100000;
    for (int k = 0; k <= kSteps; ++k) {
      const float x = (r + 0.5f) * (2.0f * float(k) / kSteps - 1.0f);
      const float table = f.Eval(x), exact = f.EvalExact(x);
      ASSERT_TRUE(std::isfinite(table) && table >= 0) << x;
      if (std::fabs(x) > r) {
        ASSERT_EQ(table, 0.0f) << x;
      }
      worst = std::max(worst, std::fabs(double(table) - double(exact)));
    }
    EXPECT_LE(worst, c.tol);
  }
}

// FilterDesc::steps: Mitsuba 3's scalar staircase (ReconstructionFilter::eval_discretized): at
// offset x the value at the inner end of x's step, floor(|x| · n / r) · r / n, and 0 at the
// radius itself and beyond. Mitsuba's own numbers for its default Gaussian (stddev 0.5, 31
// steps over radius 2): the first step is exp(0) - exp(-8), the step at x = 0.5 starts at
// 7 · 2/31 = 0.4516.
TEST(PixelFilter, StaircaseIsMitsubasDiscretization) {
  for (const FilterDesc desc : {FilterDesc{FilterDesc::Type::kGaussian, 2.0f, 0.5f, 31},
                                FilterDesc{FilterDesc::Type::kGaussian, 3.0f, 0.75f, 31},
                                FilterDesc{FilterDesc::Type::kTent, 1.5f, 0, 31},
                                FilterDesc{FilterDesc::Type::kTent, 1.0f, 0, 7}}) {
    const PixelFilter f(desc);
    const float r = desc.radius, n = float(desc.steps);
    SCOPED_TRACE("type " + std::to_string(int(desc.type)) + " radius " + std::to_string(r) +
                 " steps " + std::to_string(desc.steps));
    constexpr int kSamples = 100000;
    for (int k = 0; k <= kSamples; ++k) {
      const float x = (r + 0.5f) * (2.0f * float(k) / kSamples - 1.0f);
      const float ax = std::fabs(x);
      const float t = ax * (n / r);  // the lookup's own float operations
      const float expected =
          ax > r ? 0.0f : (int(t) >= int(n) ? 0.0f : f.EvalExact(r * float(int(t)) / n));
      ASSERT_EQ(f.Eval(x), expected) << x;
    }
    EXPECT_EQ(f.Eval(r), 0.0f);
  }
  const PixelFilter mitsuba(FilterDesc{FilterDesc::Type::kGaussian, 2.0f, 0.5f, 31});
  EXPECT_FLOAT_EQ(mitsuba.Eval(0.01f), 1.0f - std::exp(-8.0f));
  EXPECT_FLOAT_EQ(mitsuba.Eval(0.5f), std::exp(-2.0f * 0.4516129f * 0.4516129f) - std::exp(-8.0f));
}

TEST(FilmBlock, BoxFilterTouchesOnlyItsPixel) {
  const PixelFilter box(FilterDesc{FilterDesc::Type::kBox, 0.5f, 0});
  FilmBlock film(0, 0, 4, 4);
  film.Splat(box, 1.3f, 2.7f, {1, 2, 3});
  const Image img = film.Resolve();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const Color3f c = img.At(x, y);
      if (x == 1 && y == 2) {
        EXPECT_FLOAT_EQ(c.g, 2.0f);
      } else {
        EXPECT_FLOAT_EQ(c.g, 0.0f);
      }
    }
}

TEST(FilmBlock, ConstantRadianceResolvesToItself) {
  const PixelFilter gauss(FilterDesc{});
  FilmBlock film(-2, -2, 12, 12);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (float j : {0.1f, 0.5f, 0.9f}) film.Splat(gauss, x + j, y + 1 - j, {0.25f, 0.5f, 2.0f});
  const Image img = film.Resolve();
  for (int y = 2; y < 10; ++y)
    for (int x = 2; x < 10; ++x) {
      EXPECT_NEAR(img.At(x, y).r, 0.25f, 1e-6);
      EXPECT_NEAR(img.At(x, y).b, 2.0f, 1e-6);
    }
}

TEST(FilmBlock, MergeAddsOverlapOnly) {
  const PixelFilter tent(FilterDesc{FilterDesc::Type::kTent, 1.0f, 0});
  FilmBlock whole(0, 0, 8, 8), a(-1, -1, 6, 10), b(3, -1, 6, 10), direct(0, 0, 8, 8);
  a.Splat(tent, 2.2f, 3.6f, {1, 1, 1});
  b.Splat(tent, 4.5f, 3.5f, {2, 2, 2});
  direct.Splat(tent, 2.2f, 3.6f, {1, 1, 1});
  direct.Splat(tent, 4.5f, 3.5f, {2, 2, 2});
  whole.Merge(a);
  whole.Merge(b);
  const Image x = whole.Resolve(), y = direct.Resolve();
  EXPECT_EQ(x.rgb, y.rgb);
}

// A block in outside storage (the render's arena) splats there, starts zeroed, owns no bytes;
// a copy owns its accumulators; a move keeps the storage.
TEST(FilmBlock, OutsideStorageCopiesAndMoves) {
  const PixelFilter box(FilterDesc{FilterDesc::Type::kBox, 0.5f, 0});
  std::vector<float> arena(2 * 3 * 4 + 4, 7.0f);
  FilmBlock block;
  block.Reset(10, 20, 2, 3, std::span<float>(arena).subspan(2, 2 * 3 * 4));
  EXPECT_EQ(block.Bytes(), 0u);
  EXPECT_EQ(block.sums().data(), arena.data() + 2);
  EXPECT_TRUE(std::all_of(arena.begin() + 2, arena.end() - 2, [](float v) { return v == 0; }));
  EXPECT_EQ(arena[1], 7.0f);  // nothing outside its span
  EXPECT_EQ(arena[arena.size() - 2], 7.0f);
  block.Splat(box, 11.5f, 21.5f, {1.0f, 2.0f, 3.0f});
  EXPECT_EQ(arena[2 + (1 * 2 + 1) * 4 + 1], 2.0f);

  const FilmBlock copy = block;
  EXPECT_NE(copy.sums().data(), block.sums().data());
  EXPECT_TRUE(std::equal(copy.sums().begin(), copy.sums().end(), block.sums().begin()));
  EXPECT_GT(copy.Bytes(), 0u);

  FilmBlock moved = std::move(block);
  EXPECT_EQ(moved.sums().data(), arena.data() + 2);
  EXPECT_EQ(moved.Resolve().At(1, 1).g, 2.0f);
  FilmBlock own(0, 0, 2, 2);
  const float* own_data = own.sums().data();
  FilmBlock moved_own = std::move(own);
  EXPECT_EQ(moved_own.sums().data(), own_data);  // its buffer moved with it
  EXPECT_TRUE(own.sums().empty());
}

}  // namespace
}  // namespace ptlab
