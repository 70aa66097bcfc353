// Film and pixel filters: splat weights, Nori's filter shapes, block merging.
#include "engine/render/film.h"

#include <cmath>

#include <gtest/gtest.h>

namespace ptlab {
namespace {

TEST(PixelFilter, NoriShapes) {
  const PixelFilter gauss(FilterDesc{FilterDesc::Type::kGaussian, 2.0f, 0.5f});
  const float tail = std::exp(-2.0f * 4.0f);
  EXPECT_FLOAT_EQ(gauss.Eval(0), 1.0f - tail);
  EXPECT_FLOAT_EQ(gauss.Eval(0.5f), std::exp(-0.5f) - tail);
  EXPECT_FLOAT_EQ(gauss.Eval(2.0f), 0.0f);
  EXPECT_FLOAT_EQ(gauss.Eval(2.5f), 0.0f);
  const PixelFilter tent(FilterDesc{FilterDesc::Type::kTent, 1.0f, 0});
  EXPECT_FLOAT_EQ(tent.Eval(0.25f), 0.75f);
  const PixelFilter box(FilterDesc{FilterDesc::Type::kBox, 0.5f, 0});
  EXPECT_FLOAT_EQ(box.Eval(0.49f), 1.0f);
  EXPECT_FLOAT_EQ(box.Eval(0.51f), 0.0f);
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

}  // namespace
}  // namespace ptlab
