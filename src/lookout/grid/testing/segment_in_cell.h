#pragma once

// Test support: the exact answer the grid's ray traversal is checked against.

#include <Eigen/Core>
#include <algorithm>
#include <optional>
#include <utility>

#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid::testing {

// Length (m) of the part of segment [a, b] inside the closed box of global cell c
// (Liang-Barsky clipping), or nullopt when they do not meet.
inline std::optional<double> LengthInCell(const ScrollingGridGeometry& g, const CellIndex& c,
                                          const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d lo = g.CellLowerLeftM(c);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(g.cell_size_m());
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0;
  double t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return std::nullopt;
      continue;
    }
    double ta = (lo[axis] - a[axis]) / d[axis];
    double tb = (hi[axis] - a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1 + 1e-12) return std::nullopt;
  return std::max(0.0, t1 - t0) * d.norm();
}

}  // namespace lookout::grid::testing
