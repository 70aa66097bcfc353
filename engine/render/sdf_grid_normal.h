// The normals of an sdfgrid hit (Mitsuba 3's rules): geometric and shading, world space.
#pragma once

#include <cstdint>

#include "engine/core/vec.h"
#include "engine/scene/sdf_grid_table.h"

namespace ptlab {

/// The grid's interpolant at object point p: trilinear in the cell holding p, p clamped into
/// [0, 1]^3 first (a texture's clamp mode, which Mitsuba reads the grid with).
double SdfGridValueAt(const SdfGridTable& grids, uint32_t row, const double p[3]);

/// The gradient (object space) of the interpolant of cell (ci, cj, ck) at p, as Mitsuba forms
/// it: per axis, the difference of the interpolant (SdfGridValueAt, clamped) on the cell's two
/// faces across that axis, at p's other two coordinates, over the cell size. The cell may lie
/// outside the grid (its faces then clamp).
void SdfCellGradient(const SdfGridTable& grids, uint32_t row, const double p[3], int ci, int cj,
                     int ck, double g[3]);

/// The unit normals at world point p of grid `row`: *ng, the gradient of the cell holding p
/// (index ⌊p (n − 1)⌋ truncated, as Mitsuba) through to_world's inverse transpose; *ns, the
/// shading normal of the row's SdfNormals rule (kSmooth: the unit gradients of the 8 cells
/// around the grid point nearest p, cells with a negative index left out, blended trilinearly
/// by p's offset from that point, an axis whose one side is all left out taking the other
/// side's weight 1; then through to_world). A zero gradient (flat data) gives ng = +z; a zero
/// blend gives ns = ng.
void SdfGridNormals(const SdfGridTable& grids, uint32_t row, const Vec3f& p, Vec3f* ng,
                    Vec3f* ns);

}  // namespace ptlab
