// The chi-square lab's coarse grid: marginal CDFs and equal-mass blocks of fine cells.
#include "tools/chi2/coarse_grid.h"

#include <algorithm>
#include <cmath>

#include "engine/core/check.h"

namespace ptlab {
namespace {

// Block of each of n cells along one axis: the marginal CDF at the cell's middle, times blocks.
std::vector<int> BlocksAlong(const std::vector<double>& cdf, int blocks) {
  const int n = int(cdf.size()) - 1;
  std::vector<int> block(size_t(n), 0);
  for (int i = 0; i < n; ++i) {
    const double mid = 0.5 * (cdf[size_t(i)] + cdf[size_t(i) + 1]);
    block[size_t(i)] = std::clamp(int(std::floor(mid * blocks)), 0, blocks - 1);
  }
  return block;
}

}  // namespace

std::vector<double> Chi2MarginalCdf(const std::vector<double>& expected, int xres, int yres,
                                    int axis) {
  PTLAB_CHECK(expected.size() == size_t(xres) * size_t(yres) && (axis == 0 || axis == 1));
  const int n = axis == 0 ? xres : yres;
  std::vector<double> cdf(size_t(n) + 1, 0.0);
  for (int iy = 0; iy < yres; ++iy)
    for (int ix = 0; ix < xres; ++ix)
      cdf[size_t(axis == 0 ? ix : iy) + 1] += expected[size_t(iy) * size_t(xres) + size_t(ix)];
  for (int i = 0; i < n; ++i) cdf[size_t(i) + 1] += cdf[size_t(i)];
  const double total = cdf.back();
  if (total > 0)
    for (double& c : cdf) c /= total;
  cdf.back() = total > 0 ? 1.0 : 0.0;
  return cdf;
}

Chi2CoarseGrid MakeChi2CoarseGrid(const std::vector<double>& expected, int xres, int yres,
                                  int blocks) {
  PTLAB_CHECK(blocks >= 1);
  Chi2CoarseGrid g;
  g.xblocks = g.yblocks = blocks;
  const std::vector<int> bx = BlocksAlong(Chi2MarginalCdf(expected, xres, yres, 0), blocks);
  const std::vector<int> by = BlocksAlong(Chi2MarginalCdf(expected, xres, yres, 1), blocks);
  g.block_of_cell.resize(expected.size());
  for (int iy = 0; iy < yres; ++iy)
    for (int ix = 0; ix < xres; ++ix)
      g.block_of_cell[size_t(iy) * size_t(xres) + size_t(ix)] =
          by[size_t(iy)] * blocks + bx[size_t(ix)];
  return g;
}

std::vector<double> AggregateChi2Cells(const Chi2CoarseGrid& grid,
                                       const std::vector<double>& fine) {
  PTLAB_CHECK(fine.size() == grid.block_of_cell.size());
  std::vector<double> blocks(size_t(grid.xblocks) * size_t(grid.yblocks), 0.0);
  for (size_t c = 0; c < fine.size(); ++c) blocks[size_t(grid.block_of_cell[c])] += fine[c];
  return blocks;
}

}  // namespace ptlab
