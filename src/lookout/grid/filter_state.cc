#include "lookout/grid/filter_state.h"

#include <array>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

namespace lookout::grid {

FilterLayerIds AddFilterLayers(GridLayers& layers) {
  FilterLayerIds ids;
  ids.occupancy = layers.Add("occupancy", 0.5f);
  ids.velocity_x_mps = layers.Add("velocity_x_mps", 0.0f);
  ids.velocity_y_mps = layers.Add("velocity_y_mps", 0.0f);
  ids.velocity_confidence = layers.Add("velocity_confidence", 0.0f);
  ids.seen = layers.Add("seen", 0.0f);
  for (int d = 0; d < kNeighbourCount; ++d) {
    ids.rigidity[static_cast<std::size_t>(d)] = layers.Add("rigidity_" + std::to_string(d), 0.0f);
  }
  static constexpr std::array<const char*, kGridClassCount> kNames = {
      "class_static", "class_pedestrian", "class_cyclist", "class_vehicle", "class_unknown"};
  for (int c = 0; c < kGridClassCount; ++c) {
    ids.class_pmf[static_cast<std::size_t>(c)] =
        layers.Add(kNames[static_cast<std::size_t>(c)], 1.0f / kGridClassCount);
  }
  ids.hit_scans = layers.Add("hit_scans", 0.0f);
  return ids;
}

WindowIndexer::WindowIndexer(const ScrollingGridGeometry& geometry)
    : width_(geometry.width()), height_(geometry.height()) {
  const CellIndex origin = geometry.window_origin();
  column_.resize(static_cast<std::size_t>(width_));
  row_base_.resize(static_cast<std::size_t>(height_));
  for (int x = 0; x < width_; ++x) {
    column_[static_cast<std::size_t>(x)] =
        static_cast<std::size_t>(geometry.StorageColumn(origin.ix + x));
  }
  for (int y = 0; y < height_; ++y) {
    row_base_[static_cast<std::size_t>(y)] =
        static_cast<std::size_t>(geometry.StorageRow(origin.iy + y)) *
        static_cast<std::size_t>(width_);
  }
  // Storage indices must fit Local's 32-bit arithmetic.
  assert(geometry.CellCount() <= std::size_t{0xffffffffu});
  local_x_of_column_.resize(static_cast<std::size_t>(width_));
  local_y_of_row_.resize(static_cast<std::size_t>(height_));
  for (int x = 0; x < width_; ++x) local_x_of_column_[column_[static_cast<std::size_t>(x)]] = x;
  for (int y = 0; y < height_; ++y) {
    local_y_of_row_[row_base_[static_cast<std::size_t>(y)] / static_cast<std::size_t>(width_)] = y;
  }
}

std::int64_t SearchWindow::EntryOf(const CellIndex& d) const {
  const int x = d.ix - center.ix;
  const int y = d.iy - center.iy;
  const int u = LatticeIndex(x);
  const int v = LatticeIndex(y);
  if (u >= 0 && v >= 0) return static_cast<std::int64_t>(v) * size() + u;
  if (!HasDenseCore() || std::abs(x) > dense_half || std::abs(y) > dense_half) return -1;
  std::int64_t found = -1;
  ForEachDenseOffset([&](std::size_t k, const CellIndex& o) {
    if (o.ix == x && o.iy == y) found = static_cast<std::int64_t>(k);
  });
  return found;
}

void ComputePsi(const SearchWindow& w, float* psi, float* stay_share) {
  // The isotropic Gaussian is a product of two 1-D Gaussians over the window's columns and rows:
  // 2 n exponentials instead of n^2 (per component), and the sum over the lattice is the product
  // of the two 1-D sums. The dense core's few entries are summed directly.
  const int n = w.size();
  assert(n <= kMaxWindowSideCells);
  std::array<double, kMaxWindowSideCells> gx{}, gy{}, sx{}, sy{};
  const auto gaussians = [&](double sigma, std::array<double, kMaxWindowSideCells>& x,
                             std::array<double, kMaxWindowSideCells>& y) {
    const double inv_two_var = 1.0 / (2.0 * sigma * sigma);
    double sum_x = 0.0, sum_y = 0.0;
    for (int u = 0; u < n; ++u) {
      const double ex = w.center.ix + w.stride * (u - w.half) - w.mean_x_cells;
      const double ey = w.center.iy + w.stride * (u - w.half) - w.mean_y_cells;
      x[static_cast<std::size_t>(u)] = std::exp(-ex * ex * inv_two_var);
      y[static_cast<std::size_t>(u)] = std::exp(-ey * ey * inv_two_var);
      sum_x += x[static_cast<std::size_t>(u)];
      sum_y += y[static_cast<std::size_t>(u)];
    }
    double dense_sum = 0.0;
    w.ForEachDenseOffset([&](std::size_t, const CellIndex& o) {
      const double ex = w.center.ix + o.ix - w.mean_x_cells;
      const double ey = w.center.iy + o.iy - w.mean_y_cells;
      dense_sum += std::exp(-(ex * ex + ey * ey) * inv_two_var);
    });
    // The window holds its own mean (|centre - mean| <= 0.5 cell), so the sum is > 0.
    return sum_x * sum_y + dense_sum;
  };
  const double move_scale = (1.0 - w.stay_weight) / gaussians(w.sigma_cells, gx, gy);
  const double stay_scale =
      w.stay_weight > 0.0 ? w.stay_weight / gaussians(w.stay_sigma_cells, sx, sy) : 0.0;
  for (int v = 0; v < n; ++v) {
    const auto vi = static_cast<std::size_t>(v);
    const double row = move_scale * gy[vi];
    const double stay_row = stay_scale * sy[vi];
    const std::size_t base = static_cast<std::size_t>(v) * static_cast<std::size_t>(n);
    for (int u = 0; u < n; ++u) {
      const auto ui = static_cast<std::size_t>(u);
      const double move = row * gx[ui];
      const double stay = stay_row * sx[ui];
      psi[base + ui] = static_cast<float>(move + stay);
      if (stay_share) {
        stay_share[base + ui] = move + stay > 0.0 ? static_cast<float>(stay / (move + stay)) : 0.0f;
      }
    }
  }
  if (!w.HasDenseCore()) return;
  const double inv_move = 1.0 / (2.0 * w.sigma_cells * w.sigma_cells);
  const double inv_stay = 1.0 / (2.0 * w.stay_sigma_cells * w.stay_sigma_cells);
  w.ForEachDenseOffset([&](std::size_t k, const CellIndex& o) {
    const double ex = w.center.ix + o.ix - w.mean_x_cells;
    const double ey = w.center.iy + o.iy - w.mean_y_cells;
    const double r2 = ex * ex + ey * ey;
    const double move = move_scale * std::exp(-r2 * inv_move);
    const double stay = stay_scale > 0.0 ? stay_scale * std::exp(-r2 * inv_stay) : 0.0;
    psi[k] = static_cast<float>(move + stay);
    if (stay_share) {
      stay_share[k] = move + stay > 0.0 ? static_cast<float>(stay / (move + stay)) : 0.0f;
    }
  });
}

void FilterWorkspace::Resize(std::size_t cells) {
  if (source_of_cell.size() != cells) source_of_cell.assign(cells, kNone);
  if (slot_of_cell.size() != cells) slot_of_cell.assign(cells, kNone);
}

TargetIndex BuildTargetIndex(const Associations& associations, FilterWorkspace& workspace) {
  // A counting sort by target, sequential: two passes over the entries in source order. The
  // order of first appearance and the order within a target are therefore fixed. The first pass
  // files each entry's slot, so the second reads no cell map; raw pointers, so the compiler
  // need not reload one array after each store to another (with the branch-free first pass
  // below: 0.39 -> 0.13 ms for the junction's 50,600 entries, docs/PERFORMANCE.md,
  // "Serial passes, load balance, page faults").
  TargetIndex index;
  constexpr std::uint32_t kNone = FilterWorkspace::kNone;
  const std::size_t entries = associations.EntryCount();
  const EntryTarget* const target = associations.target.data();
  std::uint32_t* const slot_of_cell = workspace.slot_of_cell.data();
  // Scratch left unzeroed (make_unique_for_overwrite): every element is written before it is
  // read, and zeroing the three (800 kB for the junction's entries) was a third of this serial
  // pass's time.
  const auto slot_of_entry = std::make_unique_for_overwrite<std::uint32_t[]>(entries);
  std::uint32_t* const entry_slot = slot_of_entry.get();
  // Room for every entry to be a new target, so that the loop has no branch on it (which
  // target is new follows no pattern the predictor learns).
  const auto targets = std::make_unique_for_overwrite<std::size_t[]>(entries);
  const auto counts = std::make_unique_for_overwrite<std::uint32_t[]>(entries);
  std::uint32_t slots_used = 0;
  for (std::size_t e = 0; e < entries; ++e) {
    const EntryTarget t = target[e];
    if (t == kOutsideWindow) {
      entry_slot[e] = kNone;
      continue;
    }
    const auto cell = static_cast<std::size_t>(t);
    const std::uint32_t known = slot_of_cell[cell];
    const bool fresh = known == kNone;
    const std::uint32_t slot = fresh ? slots_used : known;
    slot_of_cell[cell] = slot;
    targets[slots_used] = cell;  // kept only when fresh: slots_used moves on
    counts[slots_used] = 0;      // the count of the next fresh slot starts here (slots_used <= e)
    slots_used += fresh ? 1u : 0u;
    ++counts[slot];
    entry_slot[e] = slot;
  }
  index.targets.assign(targets.get(), targets.get() + slots_used);
  const std::size_t slots = index.targets.size();
  index.first.resize(slots + 1);
  index.first[0] = 0;
  for (std::size_t s = 0; s < slots; ++s) index.first[s + 1] = index.first[s] + counts[s];
  index.entries.resize(index.first.back());
  // counts becomes each slot's cursor.
  for (std::size_t s = 0; s < slots; ++s) counts[s] = static_cast<std::uint32_t>(index.first[s]);
  std::uint32_t* const cursor = counts.get();
  std::uint32_t* const out = index.entries.data();
  for (std::size_t e = 0; e < entries; ++e) {
    const std::uint32_t slot = entry_slot[e];
    if (slot != kNone) out[cursor[slot]++] = static_cast<std::uint32_t>(e);
  }
  for (const std::size_t t : index.targets) slot_of_cell[t] = kNone;
  return index;
}

std::vector<UpdateCell> BuildUpdateList(const TargetIndex& targets, const Associations& a,
                                        const MeasurementGrid& z, FilterWorkspace& workspace) {
  std::vector<UpdateCell> cells;
  cells.reserve(targets.targets.size() + a.SourceCount() + z.touched.size());
  // slot_of_cell marks the cells already listed (kListed), cleared at the end.
  constexpr std::uint32_t kListed = FilterWorkspace::kNone - 1;
  for (std::size_t t = 0; t < targets.targets.size(); ++t) {
    const std::size_t cell = targets.targets[t];
    cells.push_back({cell, static_cast<std::uint32_t>(t), workspace.source_of_cell[cell]});
    workspace.slot_of_cell[cell] = kListed;
  }
  for (std::size_t s = 0; s < a.SourceCount(); ++s) {
    const std::size_t cell = a.source[s];
    if (workspace.slot_of_cell[cell] == kListed) continue;
    cells.push_back({cell, FilterWorkspace::kNone, static_cast<std::uint32_t>(s)});
    workspace.slot_of_cell[cell] = kListed;
  }
  for (const std::size_t cell : z.touched) {
    if (workspace.slot_of_cell[cell] == kListed) continue;
    cells.push_back({cell, FilterWorkspace::kNone, workspace.source_of_cell[cell]});
    workspace.slot_of_cell[cell] = kListed;
  }
  for (const UpdateCell& u : cells) workspace.slot_of_cell[u.cell] = FilterWorkspace::kNone;
  return cells;
}

void MapSources(const Associations& associations, FilterWorkspace& workspace) {
  for (std::size_t s = 0; s < associations.SourceCount(); ++s) {
    workspace.source_of_cell[associations.source[s]] = static_cast<std::uint32_t>(s);
  }
}

void ClearSourceMap(const Associations& associations, FilterWorkspace& workspace) {
  for (const std::size_t cell : associations.source) {
    workspace.source_of_cell[cell] = FilterWorkspace::kNone;
  }
}

}  // namespace lookout::grid
