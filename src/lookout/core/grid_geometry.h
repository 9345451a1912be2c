#pragma once

#include <Eigen/Core>
#include <optional>

namespace lookout {

// Integer cell coordinates: ix along x, iy along y.
struct CellIndex {
  int ix = 0;
  int iy = 0;
  bool operator==(const CellIndex&) const = default;
};

// An axis-aligned grid of square cells in some frame: the one type that converts between
// metres and cell indices. Cell (0, 0) has its lower-left corner at `origin_m`; storage is
// row-major, index = iy * width + ix.
struct GridGeometry {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double cell_size_m = 0.15;
  int width = 0;   // cells along x
  int height = 0;  // cells along y

  int CellCount() const { return width * height; }
  bool Contains(const CellIndex& c) const {
    return c.ix >= 0 && c.iy >= 0 && c.ix < width && c.iy < height;
  }
  // The cell containing point p, or nullopt outside the grid.
  std::optional<CellIndex> CellAt(const Eigen::Vector2d& p) const;
  Eigen::Vector2d CellCenter(const CellIndex& c) const;
  int LinearIndex(const CellIndex& c) const { return c.iy * width + c.ix; }
  CellIndex FromLinear(int index) const { return {index % width, index / width}; }
};

}  // namespace lookout
