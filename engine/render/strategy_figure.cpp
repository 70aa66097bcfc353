// Veach's strategy figure (strategy_figure.h).
#include "engine/render/strategy_figure.h"

#include <algorithm>

namespace ptlab {

Image StrategyFigure(const std::vector<StrategyImage>& images, int width, int height,
                     int max_bounces) {
  if (width <= 0 || height <= 0 || max_bounces < 0) return Image();
  // Row k has strategies s = 0 .. k + 1 (t = k + 2 - s >= 1): k + 2 columns at most.
  const int rows = max_bounces + 1, columns = max_bounces + 2;
  Image figure(columns * width + (columns - 1) * kStrategyFigureGap,
               rows * height + (rows - 1) * kStrategyFigureGap);
  std::fill(figure.rgb.begin(), figure.rgb.end(), kStrategyFigureBackground);
  for (const StrategyImage& im : images) {
    const int k = im.s + im.t - 2;
    if (im.s < 0 || im.t < 1 || k < 0 || k > max_bounces) continue;
    if (im.image.width != width || im.image.height != height) continue;
    const int x0 = im.s * (width + kStrategyFigureGap), y0 = k * (height + kStrategyFigureGap);
    for (int y = 0; y < height; ++y)
      std::copy_n(&im.image.rgb[size_t(y) * size_t(width) * 3], size_t(width) * 3,
                  &figure.rgb[(size_t(y0 + y) * size_t(figure.width) + size_t(x0)) * 3]);
  }
  return figure;
}

}  // namespace ptlab
