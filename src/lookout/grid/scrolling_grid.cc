#include "lookout/grid/scrolling_grid.h"

#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace lookout::grid {

ScrollingGridGeometry::ScrollingGridGeometry(double cell_size_m, int width_cells, int height_cells,
                                             CellIndex window_origin)
    : cell_size_m_(cell_size_m),
      width_(width_cells),
      height_(height_cells),
      origin_(window_origin) {
  assert(cell_size_m > 0.0);
  assert(width_cells >= 1 && width_cells <= kMaxGridSideCells);
  assert(height_cells >= 1 && height_cells <= kMaxGridSideCells);
}

namespace {
GridOptions Validated(const GridOptions& options) {
  options.Validate();
  return options;
}
}  // namespace

ScrollingGridGeometry::ScrollingGridGeometry(const GridOptions& options,
                                             const Eigen::Vector2d& center_m)
    : ScrollingGridGeometry(Validated(options).cell_size_m, options.width_cells,
                            options.height_cells) {
  origin_ = CenteredOrigin(center_m);
}

CellIndex ScrollingGridGeometry::GlobalCellAt(const Eigen::Vector2d& p_m) const {
  // Division rather than multiplication by a precomputed inverse: the ray traversal uses the
  // same expression, so a point's cell is the same whichever code asks.
  const double fx = std::floor(p_m.x() / cell_size_m_);
  const double fy = std::floor(p_m.y() / cell_size_m_);
  assert(std::abs(fx) < 2.0e9 && std::abs(fy) < 2.0e9);
  return {static_cast<int>(fx), static_cast<int>(fy)};
}

Eigen::Vector2d ScrollingGridGeometry::CellLowerLeftM(const CellIndex& global) const {
  return cell_size_m_ * Eigen::Vector2d(global.ix, global.iy);
}

Eigen::Vector2d ScrollingGridGeometry::CellCenterM(const CellIndex& global) const {
  return cell_size_m_ * Eigen::Vector2d(global.ix + 0.5, global.iy + 0.5);
}

Eigen::Vector2d ScrollingGridGeometry::WindowCenterM() const {
  return WindowLowerLeftM() + 0.5 * cell_size_m_ * Eigen::Vector2d(width_, height_);
}

GridGeometry ScrollingGridGeometry::WindowGeometry() const {
  return GridGeometry{WindowLowerLeftM(), cell_size_m_, width_, height_};
}

std::optional<std::size_t> ScrollingGridGeometry::StorageIndexAt(const Eigen::Vector2d& p_m) const {
  const CellIndex c = GlobalCellAt(p_m);
  if (!Contains(c)) return std::nullopt;
  return StorageIndex(c);
}

CellIndex ScrollingGridGeometry::GlobalFromStorage(std::size_t storage) const {
  assert(storage < CellCount());
  const int column = static_cast<int>(storage % static_cast<std::size_t>(width_));
  const int row = static_cast<int>(storage / static_cast<std::size_t>(width_));
  // The window holds exactly one global column per storage column: the one whose offset from
  // the window's left edge is (column - origin) mod width.
  return {origin_.ix + FloorMod(column - StorageColumn(origin_.ix), width_),
          origin_.iy + FloorMod(row - StorageRow(origin_.iy), height_)};
}

CellIndex ScrollingGridGeometry::CenteredOrigin(const Eigen::Vector2d& position_m) const {
  const CellIndex c = GlobalCellAt(position_m);
  return {c.ix - width_ / 2, c.iy - height_ / 2};
}

VacatedCells ScrollingGridGeometry::Recenter(const Eigen::Vector2d& position_m) {
  return MoveWindowTo(CenteredOrigin(position_m));
}

namespace {

// The storage slots (mod `size`) of the global lines new to a window that moved from
// [old_origin, old_origin + size) to [new_origin, new_origin + size), |shift| < size.
void AppendNewLines(int old_origin, int new_origin, int size, std::vector<int>& out) {
  const int first = new_origin > old_origin ? old_origin + size : new_origin;
  const int last = new_origin > old_origin ? new_origin + size : old_origin;  // exclusive
  for (int g = first; g < last; ++g) out.push_back(ScrollingGridGeometry::FloorMod(g, size));
}

}  // namespace

VacatedCells ScrollingGridGeometry::MoveWindowTo(const CellIndex& window_origin) {
  VacatedCells vacated;
  const std::int64_t shift_x = std::int64_t{window_origin.ix} - origin_.ix;
  const std::int64_t shift_y = std::int64_t{window_origin.iy} - origin_.iy;
  if (std::abs(shift_x) >= width_ || std::abs(shift_y) >= height_) {
    vacated.all = true;
  } else {
    AppendNewLines(origin_.ix, window_origin.ix, width_, vacated.columns);
    AppendNewLines(origin_.iy, window_origin.iy, height_, vacated.rows);
  }
  origin_ = window_origin;
  return vacated;
}

LayerId GridLayers::Add(std::string name, float reset_value) {
  assert(!Find(name).has_value() && "layer names are unique");
  layers_.push_back(
      Layer{std::move(name), reset_value, std::vector<float>(geometry_.CellCount(), reset_value)});
  return LayerId{static_cast<int>(layers_.size()) - 1};
}

std::optional<LayerId> GridLayers::Find(std::string_view name) const {
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    if (layers_[i].name == name) return LayerId{static_cast<int>(i)};
  }
  return std::nullopt;
}

GridLayers::Layer& GridLayers::layer(LayerId id) {
  assert(id.index >= 0 && id.index < LayerCount());
  return layers_[static_cast<std::size_t>(id.index)];
}

const GridLayers::Layer& GridLayers::layer(LayerId id) const {
  assert(id.index >= 0 && id.index < LayerCount());
  return layers_[static_cast<std::size_t>(id.index)];
}

std::optional<float> GridLayers::ValueAt(LayerId id, const Eigen::Vector2d& p_m) const {
  const std::optional<std::size_t> i = geometry_.StorageIndexAt(p_m);
  if (!i) return std::nullopt;
  return layer(id).values[*i];
}

std::vector<float> GridLayers::CopyInWindowOrder(LayerId id) const {
  const std::vector<float>& values = layer(id).values;
  std::vector<float> out;
  out.reserve(values.size());
  const auto width = static_cast<std::size_t>(geometry_.width());
  const CellIndex origin = geometry_.window_origin();
  const auto first_column = static_cast<std::size_t>(geometry_.StorageColumn(origin.ix));
  for (int local_y = 0; local_y < geometry_.height(); ++local_y) {
    // A window row is the storage row from the origin's column to the end, then the wrap.
    const auto row = static_cast<std::size_t>(geometry_.StorageRow(origin.iy + local_y));
    const auto begin = values.begin() + static_cast<std::ptrdiff_t>(row * width);
    const auto split = begin + static_cast<std::ptrdiff_t>(first_column);
    out.insert(out.end(), split, begin + static_cast<std::ptrdiff_t>(width));
    out.insert(out.end(), begin, split);
  }
  return out;
}

void GridLayers::Reset(LayerId id) {
  Layer& l = layer(id);
  std::fill(l.values.begin(), l.values.end(), l.reset_value);
}

void GridLayers::ResetAll() {
  for (Layer& l : layers_) std::fill(l.values.begin(), l.values.end(), l.reset_value);
}

void GridLayers::SwapValues(LayerId a, LayerId b) { layer(a).values.swap(layer(b).values); }

void GridLayers::ResetVacatedInAll(const VacatedCells& vacated) {
  if (vacated.empty()) return;
  for (Layer& l : layers_) {
    ResetVacated(geometry_, vacated, std::span<float>(l.values), l.reset_value);
  }
}

VacatedCells GridLayers::Recenter(const Eigen::Vector2d& position_m) {
  VacatedCells vacated = geometry_.Recenter(position_m);
  ResetVacatedInAll(vacated);
  return vacated;
}

VacatedCells GridLayers::MoveWindowTo(const CellIndex& window_origin) {
  VacatedCells vacated = geometry_.MoveWindowTo(window_origin);
  ResetVacatedInAll(vacated);
  return vacated;
}

}  // namespace lookout::grid
