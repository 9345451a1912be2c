#include "lookout/sim/truth.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

// The range of cell indices, along one axis, whose centres may lie in [lo, hi]: one cell of
// margin each side, so that rounding here never drops a cell (Contains decides), clamped to
// [0, count - 1] in floating point before the cast so far-away shapes cannot overflow an int.
// Empty (first > last) when the interval misses the grid.
struct IndexRange {
  int first = 0;
  int last = -1;
};

IndexRange CellRange(double lo, double hi, double origin, double cell_size, int count) {
  const double first = std::floor((lo - origin) / cell_size - 0.5) - 1.0;
  const double last = std::ceil((hi - origin) / cell_size - 0.5) + 1.0;
  const double max_index = static_cast<double>(count - 1);
  if (!(last >= 0.0 && first <= max_index)) return {};
  return {static_cast<int>(std::max(first, 0.0)), static_cast<int>(std::min(last, max_index))};
}

// Marks every cell whose centre lies in `shape` as occupied by `owner`, moving with the rigid
// body (centre p, velocity v, yaw rate w): v + w x (c - p), with w x r = w (-r_y, r_x) in 2D.
// Only the cells of the shape's bounding box are visited.
void Paint(const Shape& shape, int owner, const Vector2d& p, const Vector2d& v, double w,
           TruthRaster& raster) {
  const GridGeometry& g = raster.geometry;
  const Aabb box = BoundingBox(shape);
  const IndexRange xs = CellRange(box.min.x(), box.max.x(), g.origin_m.x(), g.cell_size_m, g.width);
  const IndexRange ys =
      CellRange(box.min.y(), box.max.y(), g.origin_m.y(), g.cell_size_m, g.height);
  for (int iy = ys.first; iy <= ys.last; ++iy) {
    for (int ix = xs.first; ix <= xs.last; ++ix) {
      const CellIndex cell{ix, iy};
      const Vector2d c = g.CellCenter(cell);
      if (!Contains(shape, c)) continue;
      const Vector2d r = c - p;
      const auto i = static_cast<std::size_t>(g.LinearIndex(cell));
      raster.occupied[i] = 1;
      raster.owner[i] = owner;
      raster.velocity[i] = (v + w * Vector2d(-r.y(), r.x())).cast<float>();
    }
  }
}

}  // namespace

// Painting order decides who owns a cell covered twice: the static world first, then the
// actors in the frame's order (ascending index), each overwriting what lies under it. An
// actor standing on a static shape -- a pedestrian by a pole, a car touching a parked one --
// is what perception must find, so it wins; two actors overlapping (a collision) leave the
// later one. Cells are never blended: each reports one owner and that owner's velocity.
TruthRaster RasteriseTruth(const TruthFrame& frame, const std::vector<Shape>& static_world,
                           const GridGeometry& geometry) {
  TruthRaster raster;
  raster.geometry = geometry;
  const auto n = static_cast<std::size_t>(std::max(geometry.CellCount(), 0));
  raster.occupied.assign(n, 0);
  raster.velocity.assign(n, Eigen::Vector2f::Zero());
  raster.owner.assign(n, kFreeCell);
  if (n == 0) return raster;

  for (const Shape& s : static_world) {
    Paint(s, kStaticOwner, Vector2d::Zero(), Vector2d::Zero(), 0.0, raster);
  }
  for (const ActorTruth& a : frame.actors) {
    Paint(a.footprint, a.index, a.state.pose.translation, a.state.Velocity(),
          a.state.yaw_rate_radps, raster);
  }
  return raster;
}

}  // namespace lookout::sim
