#include "lookout/core/grid_geometry.h"

#include <cmath>

namespace lookout {

std::optional<CellIndex> GridGeometry::CellAt(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d q = (p - origin_m) / cell_size_m;
  const double fx = std::floor(q.x());
  const double fy = std::floor(q.y());
  if (fx < 0.0 || fy < 0.0 || fx >= width || fy >= height) return std::nullopt;
  return CellIndex{static_cast<int>(fx), static_cast<int>(fy)};
}

Eigen::Vector2d GridGeometry::CellCenter(const CellIndex& c) const {
  return origin_m + cell_size_m * Eigen::Vector2d(c.ix + 0.5, c.iy + 0.5);
}

}  // namespace lookout
