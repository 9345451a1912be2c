#pragma once

// The state the extended grid's filter works on (docs/extended-grid.md steps 2-8): the named
// layers of the grid, the associations of one cycle (who may move where, with which
// probability), and the target index that turns the per-source associations into per-target
// gathers. Shared by the stage files (association_prediction.h ... class_update.h).
//
// Coordinates: sources and targets are storage indices (scrolling_grid.h); displacements are in
// cells of the odometry frame's lattice. Targets outside the window are kOutsideWindow: their
// mass leaves the grid.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/grid/filter_options.h"
#include "lookout/grid/grid_options.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

inline constexpr int kNeighbourCount = 8;
// The 8-neighbourhood in a fixed order; rigidity layer d links a cell with the cell at
// kNeighbourOffsets[d]. Opposite directions are d and (d + 4) % 8.
inline constexpr std::array<CellIndex, kNeighbourCount> kNeighbourOffsets = {
    CellIndex{1, 0}, CellIndex{1, 1}, CellIndex{0, 1}, CellIndex{-1, 1},
    CellIndex{-1, 0}, CellIndex{-1, -1}, CellIndex{0, -1}, CellIndex{1, -1}};
// The direction from the cell at kNeighbourOffsets[d] back to the cell.
constexpr std::size_t OppositeDirection(std::size_t d) {
  return (d + kNeighbourCount / 2) % kNeighbourCount;
}

// The filter's layers in a GridLayers, by name ("occupancy", "velocity_x_mps", ...).
struct FilterLayerIds {
  LayerId occupancy;            // O(x), eq. 1; reset 0.5
  LayerId velocity_x_mps;       // V(x), eq. 4 and 14; reset 0
  LayerId velocity_y_mps;
  LayerId velocity_confidence;  // in [0, 1]; reset 0
  LayerId seen;                 // S(x): P(the occupancy was carried in from the previous map)
  std::array<LayerId, kNeighbourCount> rigidity;  // D(x, x + offset[d]), eq. 15; reset 0
  std::array<LayerId, kGridClassCount> class_pmf; // C(x, c); reset uniform
  // Scans in a row the cell was hit, the scans that do not observe it skipped (cluster_motion.h:
  // a wall is hit at the same place for seconds, a body's side sliding along itself is not).
  LayerId hit_scans;  // reset 0
};

// Adds the filter's layers to `layers` (a programming error if their names exist).
FilterLayerIds AddFilterLayers(GridLayers& layers);

// Local (window) cell -> storage index in O(1) without modulo: per-column and per-row tables.
class WindowIndexer {
 public:
  explicit WindowIndexer(const ScrollingGridGeometry& geometry);
  int width() const { return width_; }
  int height() const { return height_; }
  bool Inside(int local_x, int local_y) const {
    return local_x >= 0 && local_y >= 0 && local_x < width_ && local_y < height_;
  }
  // Precondition: Inside(local_x, local_y).
  std::size_t Storage(int local_x, int local_y) const {
    return row_base_[static_cast<std::size_t>(local_y)] +
           column_[static_cast<std::size_t>(local_x)];
  }
  // Local column `local_x`'s offset within a row's storage (Storage(x, y) is RowStorage(y) plus
  // it). Precondition: 0 <= local_x < width().
  std::size_t ColumnStorage(int local_x) const {
    return column_[static_cast<std::size_t>(local_x)];
  }
  // Where local row `local_y`'s cells start in storage: whatever the scroll, a row is width()
  // consecutive storage cells from here (in storage-column order, not local x order).
  // Precondition: 0 <= local_y < height().
  std::size_t RowStorage(int local_y) const { return row_base_[static_cast<std::size_t>(local_y)]; }
  // The window-local cell stored at `storage`, the inverse of Storage: one 32-bit division and
  // two table reads, where ScrollingGridGeometry's LocalFromGlobal(GlobalFromStorage(.)) takes
  // four divisions, two of them 64-bit (for the loops that turn many storage indices into
  // cells: the sources, the clusters' cells). Precondition: storage < width() * height().
  CellIndex Local(std::size_t storage) const {
    const auto s = static_cast<std::uint32_t>(storage);
    const std::uint32_t row = s / static_cast<std::uint32_t>(width_);
    const std::uint32_t column = s - row * static_cast<std::uint32_t>(width_);
    return {local_x_of_column_[column], local_y_of_row_[row]};
  }

 private:
  int width_;
  int height_;
  std::vector<std::size_t> column_;
  std::vector<std::size_t> row_base_;
  std::vector<int> local_x_of_column_;  // storage column -> local x
  std::vector<int> local_y_of_row_;     // storage row -> local y
};

// Entries' targets are 32-bit: half the memory of every pass over the 50,000 entries (their
// prediction, weighting, index and constraints). A window holds at most kMaxGridSideCells^2
// cells.
using EntryTarget = std::int32_t;
inline constexpr EntryTarget kOutsideWindow = -1;
static_assert(std::int64_t{kMaxGridSideCells} * kMaxGridSideCells <= INT32_MAX,
              "a storage index fits an EntryTarget");

// One source's search window (eq. 8): candidate displacements center + stride * (u - half,
// v - half) for u, v in [0, 2 half], entry k = v * size + u (the lattice), then, when the lattice
// is coarse (stride > 1) and dense_half > 0, the dense core: the displacements center + (x, y),
// |x|, |y| <= dense_half, that the lattice does not hold, in row order (entries LatticeCount()
// on). The Gaussian of eq. 8 is centred on the exact predicted displacement `mean`, the window on
// its rounding.
struct SearchWindow {
  CellIndex center;
  int half = 0;
  int stride = 1;
  // Why a dense core: a coarse window has no sample at a walker's 0.6-0.8 cell a cycle; the core
  // gives slow motion samples of its own without the 625 entries of a dense +-12-cell window.
  int dense_half = 0;
  double mean_x_cells = 0.0;
  double mean_y_cells = 0.0;
  double sigma_cells = 1.0;
  // A coarse (wide) window mixes in a component of this weight and sigma that follows the
  // prediction exactly: for newly seen occupancy (V = 0) it stays where it was seen (most newly
  // revealed occupancy in a street is static structure). Eq. 8 becomes
  // (1 - w) g(., sigma) + w g(., stay_sigma), each part normalised over the window.
  double stay_weight = 0.0;
  double stay_sigma_cells = 1.0;
  int size() const { return 2 * half + 1; }
  std::size_t LatticeCount() const {
    return static_cast<std::size_t>(size()) * static_cast<std::size_t>(size());
  }
  bool HasDenseCore() const { return stride > 1 && dense_half > 0; }
  // The lattice column (or row) of the sample `offset` cells from the centre along one axis, or
  // -1 when no lattice sample lies there.
  int LatticeIndex(int offset) const {
    if (offset % stride != 0 || std::abs(offset) > stride * half) return -1;
    return offset / stride + half;
  }
  // Whether the offset (x, y) from the centre lies on the lattice.
  bool OnLattice(int x, int y) const { return LatticeIndex(x) >= 0 && LatticeIndex(y) >= 0; }
  std::size_t DenseCount() const {
    if (!HasDenseCore()) return 0;
    std::size_t n = 0;
    for (int y = -dense_half; y <= dense_half; ++y) {
      for (int x = -dense_half; x <= dense_half; ++x) {
        if (!OnLattice(x, y)) ++n;
      }
    }
    return n;
  }
  std::size_t EntryCount() const { return LatticeCount() + DenseCount(); }
  bool SameEntries(const SearchWindow& o) const {
    return center == o.center && stride == o.stride && half == o.half &&
           (HasDenseCore() ? dense_half : 0) == (o.HasDenseCore() ? o.dense_half : 0);
  }
  // f(k, offset from the centre) over the dense core's entries, k from LatticeCount() on.
  template <typename F>
  void ForEachDenseOffset(const F& f) const {
    if (!HasDenseCore()) return;
    std::size_t k = LatticeCount();
    for (int y = -dense_half; y <= dense_half; ++y) {
      for (int x = -dense_half; x <= dense_half; ++x) {
        if (!OnLattice(x, y)) f(k++, CellIndex{x, y});
      }
    }
  }
  CellIndex Displacement(std::size_t k) const {
    const int n = size();
    if (k >= LatticeCount()) {
      CellIndex out = center;
      ForEachDenseOffset([&](std::size_t j, const CellIndex& o) {
        if (j == k) out = {center.ix + o.ix, center.iy + o.iy};
      });
      return out;
    }
    const int u = static_cast<int>(k % static_cast<std::size_t>(n));
    const int v = static_cast<int>(k / static_cast<std::size_t>(n));
    return {center.ix + stride * (u - half), center.iy + stride * (v - half)};
  }
  // f(k, Displacement(k)) for k = 0, 1, ... in order, without Displacement's division per entry
  // (the hot loops over a window's entries).
  template <typename F>
  void ForEachDisplacement(const F& f) const {
    const int n = size();
    std::size_t k = 0;
    for (int v = 0; v < n; ++v) {
      const int dy = center.iy + stride * (v - half);
      for (int u = 0; u < n; ++u, ++k) f(k, CellIndex{center.ix + stride * (u - half), dy});
    }
    ForEachDenseOffset([&](std::size_t j, const CellIndex& o) {
      f(j, CellIndex{center.ix + o.ix, center.iy + o.iy});
    });
  }
  // The entry of displacement d, or -1 when d is not one of the window's samples.
  std::int64_t EntryOf(const CellIndex& d) const;
};

// Psi of eq. 8-9 over the window's entries (EntryCount() values summing to 1); with stay_share,
// also the share of each entry that the stay component holds.
void ComputePsi(const SearchWindow& window, float* psi, float* stay_share = nullptr);

// The associations of one cycle, structure of arrays. Sources are the cells IsSource selects
// (association_prediction.h), in storage order; their previous state is copied here, so the
// stages can overwrite the layers in place.
struct Associations {
  // --- per source
  std::vector<std::size_t> source;  // storage index
  std::vector<CellIndex> source_local;
  std::vector<float> occupancy;     // O_{k-1}(j)
  std::vector<float> seen;          // S_{k-1}(j)
  std::vector<float> velocity_x_mps;
  std::vector<float> velocity_y_mps;
  std::vector<float> confidence;
  std::vector<float> class_pmf;     // kGridClassCount per source
  std::vector<float> rigidity;      // kNeighbourCount per source: D_{k-1}(j, j + offset[d])
  std::vector<SearchWindow> window;
  std::vector<std::size_t> first_entry;  // SourceCount() + 1
  // --- per entry (j -> i)
  std::vector<EntryTarget> target;       // storage index of i, or kOutsideWindow
  std::vector<std::uint32_t> entry_source;
  std::vector<float> weight;             // P(j -> i), summing to 1 over each source's window
  // The share of P(j -> i) that "stays in place" holds (step 2's mixture, where the prediction
  // is no motion; eq. 10-11 scale an entry as a whole, so the share carries through). Filled
  // only when FilterOptions::moved_share_exponent > 0.
  std::vector<float> stay_share;

  std::size_t SourceCount() const { return source.size(); }
  std::size_t EntryCount() const { return target.size(); }
};

// Per target, the entries that end in it, in source order: every gather visits its
// contributions in one fixed order, so sums are identical for any thread count.
struct TargetIndex {
  std::vector<std::size_t> targets;  // storage indices, in order of first appearance
  std::vector<std::size_t> first;    // targets.size() + 1
  std::vector<std::uint32_t> entries;
};

// Scratch arrays over the whole window, kept between cycles so a steady pipeline allocates
// nothing; every user leaves them as it found them (all kNone).
struct FilterWorkspace {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> source_of_cell;  // storage index -> source id
  std::vector<std::uint32_t> slot_of_cell;    // storage index -> target slot
  void Resize(std::size_t cells);
};

TargetIndex BuildTargetIndex(const Associations& associations, FilterWorkspace& workspace);

// Sets workspace.source_of_cell for the sources (undo with ClearSourceMap).
void MapSources(const Associations& associations, FilterWorkspace& workspace);
void ClearSourceMap(const Associations& associations, FilterWorkspace& workspace);

// A cell whose state this cycle may change: a target of some association (target_slot into the
// TargetIndex), a source (its mass may leave), or a cell with evidence in z. Every other cell
// keeps its state: it stays in place (inactive) and its measurement is 0.5.
struct UpdateCell {
  std::size_t cell = 0;
  std::uint32_t target_slot = FilterWorkspace::kNone;
  std::uint32_t source = FilterWorkspace::kNone;  // its source id if it is a source
};
// Targets first (in TargetIndex order), then the other sources, then the other evidence cells.
// Needs workspace.source_of_cell mapped (MapSources).
std::vector<UpdateCell> BuildUpdateList(const TargetIndex& targets,
                                        const Associations& associations, const MeasurementGrid& z,
                                        FilterWorkspace& workspace);
// The update list's targets and other sources (its first part): the cells some mass moved into
// or out of. The cells after them only have evidence: the carried attributes (velocity, links)
// leave them as they are, and their passes stop here (two thirds of the junction's cells).
inline std::span<const UpdateCell> MovedCells(const std::vector<UpdateCell>& cells) {
  const auto end = std::partition_point(cells.begin(), cells.end(), [](const UpdateCell& c) {
    return c.target_slot != FilterWorkspace::kNone || c.source != FilterWorkspace::kNone;
  });
  return {cells.data(), static_cast<std::size_t>(end - cells.begin())};
}

// The weighted mean over the contributions w_ji = P(j -> i) O(j) that one target gathers, of a
// per-source quantity: the carrying rule of every per-cell attribute (velocity, class, links).
// Returns the weight sum.
template <typename PerSource>
double GatherWeighted(const Associations& a, const TargetIndex& targets, std::uint32_t slot,
                      const PerSource& per_source) {
  double sum = 0.0;
  for (std::size_t n = targets.first[slot]; n < targets.first[slot + 1]; ++n) {
    const std::uint32_t e = targets.entries[n];
    const std::uint32_t s = a.entry_source[e];
    const double w = static_cast<double>(a.weight[e]) * static_cast<double>(a.occupancy[s]);
    per_source(e, s, w);
    sum += w;
  }
  return sum;
}

// The source linked to source s in direction d (its 8-neighbour at kNeighbourOffsets[d], when
// that cell is a source), or FilterWorkspace::kNone. Needs workspace.source_of_cell mapped.
inline std::uint32_t LinkedSource(const Associations& a, const WindowIndexer& indexer,
                                  const FilterWorkspace& workspace, std::size_t s, std::size_t d) {
  const int nx = a.source_local[s].ix + kNeighbourOffsets[d].ix;
  const int ny = a.source_local[s].iy + kNeighbourOffsets[d].iy;
  if (!indexer.Inside(nx, ny)) return FilterWorkspace::kNone;
  return workspace.source_of_cell[indexer.Storage(nx, ny)];
}

// Sources per block in the per-source parallel loops. Why so few: a wide window costs 3.5 to 6
// times a fine one and sources come in runs of one kind (a body newly seen), so blocks of 256
// (four for the junction's 824 sources) left one of two threads most of the work.
inline constexpr std::size_t kSourceBlock = 32;

// body(i) for every i in [0, n) with test(i), in order. Why blocks: where few items pass (a few
// hundred sources or hits among the window's 160,000 cells) a branch per item costs more than
// the memory; each block of 64 is counted first by a loop without a branch, which vectorises,
// and looked at item by item only where some item passes. `test` is cheap and pure.
template <typename Test, typename Body>
void ForEachWhere(std::size_t n, const Test& test, const Body& body) {
  constexpr std::size_t kBlock = 64;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t end = std::min(begin + kBlock, n);
    int passing = 0;
    for (std::size_t i = begin; i < end; ++i) passing += test(i) ? 1 : 0;
    if (passing == 0) continue;
    for (std::size_t i = begin; i < end; ++i) {
      if (test(i)) body(i);
    }
  }
}

// Runs body(begin, end) over [0, n) in blocks of at most `block` items, in parallel. Callers write
// only to items of their own block, so the result does not depend on the thread count.
template <typename Body>
void ParallelForBlocks(std::size_t n, std::size_t block, const Body& body) {
  if (n == 0) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, block),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); },
                    tbb::simple_partitioner());
}

}  // namespace lookout::grid
