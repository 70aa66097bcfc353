// The chi-square lab's coarse grid: fine cells merged into blocks of equal marginal probability.
#pragma once

#include <vector>

namespace ptlab {

/// Fine cells (xres × yres, index iy * xres + ix) grouped into xblocks × yblocks blocks: column
/// ix joins block column ⌊xblocks · F_x(mid ix)⌋, F_x the pdf's marginal CDF along x (the same
/// along y), so each block column and row holds about 1/blocks of the mass wherever the pdf
/// lives — a narrow lobe gets its blocks as a broad one does. Built from the expected counts
/// only (never the samples), so the grid is fixed before the samples are looked at.
struct Chi2CoarseGrid {
  int xblocks = 0, yblocks = 0;
  std::vector<int> block_of_cell;  // per fine cell: by * xblocks + bx
};

/// The marginal CDF of the fine expected counts along x (axis 0) or y (axis 1) at the n + 1 cell
/// edges: F[0] = 0, F[n] = 1 (all zeros when the counts sum to 0).
std::vector<double> Chi2MarginalCdf(const std::vector<double>& expected, int xres, int yres,
                                    int axis);

/// The blocks × blocks grid of equal marginal mass over `expected` (blocks >= 1).
Chi2CoarseGrid MakeChi2CoarseGrid(const std::vector<double>& expected, int xres, int yres,
                                  int blocks);

/// Sums per-fine-cell values into the grid's blocks.
std::vector<double> AggregateChi2Cells(const Chi2CoarseGrid& grid, const std::vector<double>& fine);

}  // namespace ptlab
