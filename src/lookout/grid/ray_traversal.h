#pragma once

// Exact grid traversal of a segment (Amanatides & Woo, "A fast voxel traversal algorithm for
// ray tracing", Eurographics 1987) over a scrolling window: every window cell the segment
// passes through, in order from the start, each once, with constant work per cell.
//
// Exactness and its one tolerance. The cells visited are those whose half-open square the
// segment [start, end] meets, walked on the odometry frame's global lattice. Where the segment
// passes exactly through a cell corner, it only touches the two cells diagonal to its path at
// a point; the walk steps along y first at such a tie, so it visits one of them (a cell the
// segment meets in a single point). Cells met along a positive length are never missed.
//
// Termination does not rely on floating-point crossings: the walk takes exactly
// |end.x - start.x| steps in x and |end.y - start.y| in y (cell indices, from
// GlobalCellAt), so it always ends on the end cell, whatever the rounding of the crossing
// parameters near a corner.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>

#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

// Calls visit(std::size_t storage_index, bool is_end_cell) for each cell of the window that
// the segment from start_m to end_m (odometry frame) passes through, in order from start_m.
// is_end_cell is true for the cell holding end_m, which is visited last (if in the window).
// Cells outside the window are skipped; the walk stops where the segment leaves the window.
template <typename Visitor>
void TraverseSegment(const ScrollingGridGeometry& geometry, const Eigen::Vector2d& start_m,
                     const Eigen::Vector2d& end_m, Visitor&& visit) {
  const CellIndex start = geometry.GlobalCellAt(start_m);
  const CellIndex end = geometry.GlobalCellAt(end_m);
  const CellIndex origin = geometry.window_origin();
  const int width = geometry.width();
  const int height = geometry.height();

  // Quick rejection: the segment's bounding box of cells misses the window.
  if (std::max(start.ix, end.ix) < origin.ix || std::min(start.ix, end.ix) >= origin.ix + width ||
      std::max(start.iy, end.iy) < origin.iy || std::min(start.iy, end.iy) >= origin.iy + height) {
    return;
  }

  // Crossing parameters in units of the segment (t in [0, 1]), in cell coordinates.
  const double s = geometry.cell_size_m();
  const double qx = start_m.x() / s;
  const double qy = start_m.y() / s;
  const double dx = end_m.x() / s - qx;
  const double dy = end_m.y() / s - qy;
  constexpr double kNever = std::numeric_limits<double>::infinity();

  const int step_x = end.ix > start.ix ? 1 : (end.ix < start.ix ? -1 : 0);
  const int step_y = end.iy > start.iy ? 1 : (end.iy < start.iy ? -1 : 0);
  int remaining_x = std::abs(end.ix - start.ix);
  int remaining_y = std::abs(end.iy - start.iy);
  // A step is taken only when the end cell differs along that axis, so dx (dy) is non-zero
  // whenever its parameters are used.
  const double t_delta_x = step_x != 0 ? 1.0 / std::abs(dx) : kNever;
  const double t_delta_y = step_y != 0 ? 1.0 / std::abs(dy) : kNever;
  double t_max_x = step_x > 0   ? (start.ix + 1 - qx) / dx
                   : step_x < 0 ? (qx - start.ix) / -dx
                                : kNever;
  double t_max_y = step_y > 0   ? (start.iy + 1 - qy) / dy
                   : step_y < 0 ? (qy - start.iy) / -dy
                                : kNever;

  int local_x = start.ix - origin.ix;
  int local_y = start.iy - origin.iy;
  int column = geometry.StorageColumn(start.ix);
  int row = geometry.StorageRow(start.iy);
  const auto width_u = static_cast<std::size_t>(width);
  bool entered = false;
  for (;;) {
    const bool inside = static_cast<unsigned>(local_x) < static_cast<unsigned>(width) &&
                        static_cast<unsigned>(local_y) < static_cast<unsigned>(height);
    const bool at_end = remaining_x == 0 && remaining_y == 0;
    if (inside) {
      entered = true;
      visit(static_cast<std::size_t>(row) * width_u + static_cast<std::size_t>(column), at_end);
    } else if (entered) {
      return;  // the window is convex: once out, the segment never comes back
    }
    if (at_end) return;
    if (remaining_y == 0 || (remaining_x != 0 && t_max_x < t_max_y)) {
      local_x += step_x;
      column += step_x;
      if (column == width) column = 0;
      if (column < 0) column = width - 1;
      t_max_x += t_delta_x;
      --remaining_x;
    } else {
      local_y += step_y;
      row += step_y;
      if (row == height) row = 0;
      if (row < 0) row = height - 1;
      t_max_y += t_delta_y;
      --remaining_y;
    }
  }
}

}  // namespace lookout::grid
