// StrategyFigure: where each strategy's tile lands in Veach's layout, and what is left out.
#include "engine/render/strategy_figure.h"

#include <gtest/gtest.h>

namespace ptlab {
namespace {

StrategyImage Constant(int s, int t, int w, int h, float v) {
  StrategyImage im{s, t, Image(w, h)};
  for (float& c : im.image.rgb) c = v;
  return im;
}

TEST(StrategyFigure, RowPerPathLengthColumnPerLightVertices) {
  constexpr int kW = 3, kH = 2, kGap = kStrategyFigureGap;
  std::vector<StrategyImage> images = {
      Constant(0, 2, kW, kH, 1.0f),   // 0 bounces, camera path hits the light
      Constant(1, 2, kW, kH, 2.0f),   // 1 bounce, emitter sampling
      Constant(2, 1, kW, kH, 3.0f),   // 1 bounce, light tracing
      Constant(1, 3, kW, kH, 4.0f),   // 2 bounces
      Constant(0, 5, kW, kH, 9.0f),   // 3 bounces: beyond max_bounces 2, left out
      Constant(-1, -1, kW, kH, 9.0f),  // the summed longer paths: left out
      Constant(1, 1, kW + 1, kH, 9.0f)};  // another size: left out
  const Image f = StrategyFigure(images, kW, kH, /*max_bounces=*/2);
  ASSERT_EQ(f.width, 4 * kW + 3 * kGap);
  ASSERT_EQ(f.height, 3 * kH + 2 * kGap);
  const auto tile = [&](int s, int k, int x, int y) {
    return f.At(s * (kW + kGap) + x, k * (kH + kGap) + y).r;
  };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      EXPECT_EQ(tile(0, 0, x, y), 1.0f);
      EXPECT_EQ(tile(1, 1, x, y), 2.0f);
      EXPECT_EQ(tile(2, 1, x, y), 3.0f);
      EXPECT_EQ(tile(1, 2, x, y), 4.0f);
      EXPECT_EQ(tile(0, 1, x, y), kStrategyFigureBackground);  // no (0, 3) image given
      EXPECT_EQ(tile(1, 0, x, y), kStrategyFigureBackground);  // (1, 1): only at another size
    }
  // Every other pixel (gaps, empty cells) is the background: the four tiles are all there is.
  size_t background = 0;
  for (float v : f.rgb) background += v == kStrategyFigureBackground;
  EXPECT_EQ(background, f.rgb.size() - 4 * size_t(3 * kW * kH));
}

TEST(StrategyFigure, DegenerateSizesGiveAnEmptyImage) {
  EXPECT_EQ(StrategyFigure({}, 0, 4, 2).width, 0);
  EXPECT_EQ(StrategyFigure({}, 4, 4, -1).width, 0);
}

}  // namespace
}  // namespace ptlab
