#pragma once

// The grid's window on the odometry frame, and the float layers that live in it.
//
// Why a scrolling window: the extended grid lives in the odometry frame (docs/extended-grid.md,
// "what the grid holds"), not in the vehicle frame as in the paper, so that a static world
// stays still in it while the ego moves. The window follows the ego by whole cells, so no cell
// is ever resampled (resampling would blur occupancy and velocities at every step).
//
// Why a circular buffer (as grid_map): the cells of the odometry frame form one fixed global
// lattice, cell (gx, gy) covering [gx s, (gx + 1) s) x [gy s, (gy + 1) s) with s the cell size
// (the half-open convention of docs/conventions.md). The window is a width x height block of
// that lattice whose lower-left cell, window_origin, is an integer global index. A global cell
// is stored at
//     storage column = gx mod width,  storage row = gy mod height,
//     storage index  = row * width + column
// (floored modulo). A cell therefore keeps its storage slot for as long as it stays in the
// window: moving the window copies nothing, it only reports which storage rows and columns now
// hold new cells, and the layers reset those to their prior values.
//
// Index spaces, named everywhere:
//   metres  - a point in the odometry frame (Eigen::Vector2d, *_m);
//   global  - CellIndex on the odometry frame's lattice, any integer (fits int up to
//             +-2^31 cells: 3e5 km at 0.15 m);
//   local   - CellIndex relative to the window's lower-left cell, [0, width) x [0, height);
//   storage - std::size_t index into every layer's vector, [0, width * height).

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/grid/grid_options.h"

namespace lookout::grid {

// What a window move brought in: storage rows and columns whose cells are new to the window
// and must be reset to the prior. A row spans every storage column and a column every storage
// row (their crossings may be listed twice; resetting is idempotent).
struct VacatedCells {
  bool all = false;          // moved by a window size or more: every cell is new
  std::vector<int> columns;  // storage columns, in increasing global x of the new cells
  std::vector<int> rows;     // storage rows, in increasing global y of the new cells

  bool empty() const { return !all && columns.empty() && rows.empty(); }
};

// The one type that converts between metres, global cells, window-local cells and storage
// indices, and moves the window. A small value type: copy it freely (a MeasurementGrid keeps
// the copy it was computed in).
class ScrollingGridGeometry {
 public:
  // A width x height window of cells of cell_size_m whose lower-left cell is `window_origin`.
  // Preconditions (GridOptions::Validate checks them for user input): cell_size_m > 0,
  // 1 <= width, height <= kMaxGridSideCells.
  ScrollingGridGeometry(double cell_size_m, int width_cells, int height_cells,
                        CellIndex window_origin = {});
  // The window of `options` centred on `center_m` (as Recenter(center_m) would place it).
  // Validates the options (lookout::InputError).
  explicit ScrollingGridGeometry(const GridOptions& options,
                                 const Eigen::Vector2d& center_m = Eigen::Vector2d::Zero());

  double cell_size_m() const { return cell_size_m_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t CellCount() const {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  }

  // --- metres <-> global cells
  // The global cell holding p (half-open cells), whether or not it is in the window.
  CellIndex GlobalCellAt(const Eigen::Vector2d& p_m) const;
  Eigen::Vector2d CellCenterM(const CellIndex& global) const;
  Eigen::Vector2d CellLowerLeftM(const CellIndex& global) const;

  // --- the window
  CellIndex window_origin() const { return origin_; }  // global index of the lower-left cell
  Eigen::Vector2d WindowLowerLeftM() const { return CellLowerLeftM(origin_); }
  Eigen::Vector2d WindowCenterM() const;
  bool Contains(const CellIndex& global) const {
    return global.ix >= origin_.ix && global.iy >= origin_.iy && global.ix - origin_.ix < width_ &&
           global.iy - origin_.iy < height_;
  }
  bool ContainsPoint(const Eigen::Vector2d& p_m) const { return Contains(GlobalCellAt(p_m)); }
  // The window as a core GridGeometry in the odometry frame, indexed by LOCAL cells (not
  // storage): for rendering and recording, where images are in window order.
  GridGeometry WindowGeometry() const;

  // --- global <-> local <-> storage
  CellIndex LocalFromGlobal(const CellIndex& global) const {
    return {global.ix - origin_.ix, global.iy - origin_.iy};
  }
  CellIndex GlobalFromLocal(const CellIndex& local) const {
    return {local.ix + origin_.ix, local.iy + origin_.iy};
  }
  int StorageColumn(int global_x) const { return FloorMod(global_x, width_); }
  int StorageRow(int global_y) const { return FloorMod(global_y, height_); }
  // Precondition: Contains(global). (Defined outside the window too, aliasing a window cell.)
  std::size_t StorageIndex(const CellIndex& global) const {
    return static_cast<std::size_t>(StorageRow(global.iy)) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(StorageColumn(global.ix));
  }
  std::size_t StorageIndexOfLocal(const CellIndex& local) const {
    return StorageIndex(GlobalFromLocal(local));
  }
  std::optional<std::size_t> StorageIndexAt(const Eigen::Vector2d& p_m) const;
  // The global cell of the window stored at `storage`. Precondition: storage < CellCount().
  CellIndex GlobalFromStorage(std::size_t storage) const;

  // --- moving the window
  // Moves the window by whole cells so that the cell holding position_m becomes the local
  // cell (width / 2, height / 2): the position is then within one cell of the window's centre.
  // Returns the storage rows and columns that now hold new cells.
  VacatedCells Recenter(const Eigen::Vector2d& position_m);
  // Moves the window so that its lower-left cell is `window_origin`.
  VacatedCells MoveWindowTo(const CellIndex& window_origin);
  // The window origin Recenter(position_m) would choose.
  CellIndex CenteredOrigin(const Eigen::Vector2d& position_m) const;

  static int FloorMod(int a, int n) {
    const int r = a % n;
    return r < 0 ? r + n : r;
  }

 private:
  double cell_size_m_;
  int width_;
  int height_;
  CellIndex origin_;
};

// Sets the vacated cells of any storage-indexed array (a layer, a byte mask, a measurement)
// to `reset_value`.
template <typename T>
void ResetVacated(const ScrollingGridGeometry& geometry, const VacatedCells& vacated,
                  std::span<T> values, const T& reset_value) {
  const auto width = static_cast<std::size_t>(geometry.width());
  const auto height = static_cast<std::size_t>(geometry.height());
  if (vacated.all) {
    std::fill(values.begin(), values.end(), reset_value);
    return;
  }
  T* const data = values.data();
  for (const int row : vacated.rows) {
    T* const row_begin = data + static_cast<std::size_t>(row) * width;
    std::fill(row_begin, row_begin + width, reset_value);
  }
  if (vacated.columns.empty()) return;
  // Window moves bring in consecutive columns (two runs at most, split by the wrap): fill each
  // row's runs as contiguous spans rather than one strided cell at a time. Any other list
  // (built by hand) takes the cell-by-cell path.
  struct Run {
    std::size_t first = 0;
    std::size_t count = 0;
  };
  Run runs[2];
  std::size_t run_count = 0;
  for (const int c : vacated.columns) {
    const auto column = static_cast<std::size_t>(c);
    if (run_count > 0 && column == runs[run_count - 1].first + runs[run_count - 1].count) {
      ++runs[run_count - 1].count;
    } else if (run_count < 2) {
      runs[run_count++] = Run{column, 1};
    } else {
      run_count = 3;  // not runs: fall back
      break;
    }
  }
  for (std::size_t row = 0; row < height; ++row) {
    T* const row_begin = data + row * width;
    if (run_count <= 2) {
      for (std::size_t r = 0; r < run_count; ++r) {
        std::fill(row_begin + runs[r].first, row_begin + runs[r].first + runs[r].count,
                  reset_value);
      }
    } else {
      for (const int c : vacated.columns) row_begin[c] = reset_value;
    }
  }
}

// A handle on one layer of a GridLayers; cheap to copy, valid for the GridLayers that made it.
struct LayerId {
  int index = -1;
  bool operator==(const LayerId&) const = default;
};

// Named float layers over one scrolling window, structure of arrays: each layer is one
// contiguous std::vector<float> in storage order, so a stage's hot loop touches only the
// layers it needs. All layers share the geometry and scroll together; a move resets each
// layer's new cells to the layer's own reset value (its prior: 0.5 for an occupancy, 0 for a
// velocity...) and copies nothing.
//
// Spans returned by Values() stay valid while the GridLayers lives (adding layers does not move
// existing data), except across SwapValues, which exchanges the buffers behind two ids.
class GridLayers {
 public:
  explicit GridLayers(const ScrollingGridGeometry& geometry) : geometry_(geometry) {}

  const ScrollingGridGeometry& geometry() const { return geometry_; }

  // A new layer filled with reset_value. Names are unique (a programming error otherwise).
  LayerId Add(std::string name, float reset_value);
  std::optional<LayerId> Find(std::string_view name) const;
  int LayerCount() const { return static_cast<int>(layers_.size()); }
  const std::string& Name(LayerId id) const { return layer(id).name; }
  float ResetValue(LayerId id) const { return layer(id).reset_value; }

  std::span<float> Values(LayerId id) { return layer(id).values; }
  std::span<const float> Values(LayerId id) const { return layer(id).values; }
  // The value at a point, or nullopt outside the window.
  std::optional<float> ValueAt(LayerId id, const Eigen::Vector2d& p_m) const;
  // The values in window order (row-major over local cells, as geometry().WindowGeometry()
  // indexes them): for images and recordings. A copy; O(cells).
  std::vector<float> CopyInWindowOrder(LayerId id) const;

  void Reset(LayerId id);
  void ResetAll();
  // Exchanges the values of two layers in O(1): double buffering for a stage that gathers
  // from the previous values into new ones. Names and reset values stay with the ids.
  void SwapValues(LayerId a, LayerId b);

  // Move the window (ScrollingGridGeometry::Recenter / MoveWindowTo) and reset the new cells
  // of every layer to its reset value. The returned cells let a caller reset its own arrays.
  VacatedCells Recenter(const Eigen::Vector2d& position_m);
  VacatedCells MoveWindowTo(const CellIndex& window_origin);

 private:
  struct Layer {
    std::string name;
    float reset_value = 0.0f;
    std::vector<float> values;
  };
  Layer& layer(LayerId id);
  const Layer& layer(LayerId id) const;
  void ResetVacatedInAll(const VacatedCells& vacated);

  ScrollingGridGeometry geometry_;
  std::vector<Layer> layers_;
};

}  // namespace lookout::grid
