// Veach's figure of bidirectional path tracing's strategies (his thesis, figure 10.3), laid out
// from the per-strategy images of RenderStrategyImages (bdpt_strategies.h).
#pragma once

#include <vector>

#include "engine/image/image.h"
#include "engine/render/bdpt_strategies.h"

namespace ptlab {

/// Pixels between the tiles of StrategyFigure, and the linear grey of the gaps and of cells
/// with no strategy (sRGB 38 of 255: dark tiles stay distinct from it).
inline constexpr int kStrategyFigureGap = 4;
inline constexpr float kStrategyFigureBackground = 0.02f;

/// One tile per strategy (s, t) with s + t - 2 <= max_bounces: row k holds the paths of k
/// bounces (s + t = k + 2), column s their light-subpath length, so each row reads from pure
/// camera paths (s = 0, left) to light tracing (t = 1, right). Tiles are the images as they are
/// (linear radiance: the film's scale, so the row sums are what the camera sees of that path
/// length); cells with no strategy and the gaps are kStrategyFigureBackground. Images of another size, s < 0 (the
/// summed longer paths) or longer paths are left out.
Image StrategyFigure(const std::vector<StrategyImage>& images, int width, int height,
                     int max_bounces);

}  // namespace ptlab
