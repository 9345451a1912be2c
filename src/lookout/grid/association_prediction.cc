#include "lookout/grid/association_prediction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

namespace lookout::grid {

double AssociationSigmaCells(const float* class_pmf, double dt_s, double cell_size_m,
                             const FilterOptions& options) {
  double variance = 0.0;
  for (std::size_t c = 0; c < kGridClassCount; ++c) {
    const double s = options.class_velocity_sigma_mps[c];
    variance += static_cast<double>(class_pmf[c]) * s * s;
  }
  return std::max(std::sqrt(variance) * dt_s / cell_size_m, options.min_sigma_cells);
}

bool IsSource(double occupancy, double seen, const FilterOptions& options) {
  return occupancy >= options.active_occupancy ||
         (seen >= options.seen_threshold && occupancy >= options.tracked_min_occupancy);
}

double PredictVelocity(double velocity_mps, double dt_s, bool observed,
                       const FilterOptions& options) {
  if (!observed && options.velocity_persists_unobserved) return velocity_mps;
  return velocity_mps * std::exp(-dt_s / options.velocity_persistence_s);
}

SearchWindow SearchWindowFor(double velocity_x_mps, double velocity_y_mps, double seen,
                             double confidence, const float* class_pmf, double dt_s,
                             double cell_size_m, const FilterOptions& options) {
  SearchWindow w;
  const double max_cells = options.max_displacement_cells;
  const bool newly_seen = seen < options.seen_threshold;
  w.mean_x_cells = std::clamp(velocity_x_mps * dt_s / cell_size_m, -max_cells, max_cells);
  w.mean_y_cells = std::clamp(velocity_y_mps * dt_s / cell_size_m, -max_cells, max_cells);
  w.center = {static_cast<int>(std::lround(w.mean_x_cells)),
              static_cast<int>(std::lround(w.mean_y_cells))};
  w.sigma_cells = AssociationSigmaCells(class_pmf, dt_s, cell_size_m, options);
  if (!newly_seen && confidence >= options.known_confidence) {
    w.half = (options.window_size_cells - 1) / 2;
    w.stride = 1;
  } else {
    w.half = (options.new_window_size_cells - 1) / 2;
    w.stride = options.new_window_stride_cells;
    w.dense_half = options.new_window_dense_half_cells;
    w.stay_weight = options.new_stay_probability;
    w.stay_sigma_cells = options.min_sigma_cells;
    w.sigma_cells = std::max(w.sigma_cells, options.new_sigma_m / cell_size_m);
  }
  return w;
}

SearchWindow MeasuredFlowWindow(const FlowMeasurement& flow, const float* class_pmf, double dt_s,
                                double cell_size_m, const FilterOptions& options) {
  SearchWindow w;
  w.mean_x_cells = flow.mean_x_cells;
  w.mean_y_cells = flow.mean_y_cells;
  w.center = {static_cast<int>(std::lround(flow.mean_x_cells)),
              static_cast<int>(std::lround(flow.mean_y_cells))};
  w.half = (options.window_size_cells - 1) / 2;
  w.stride = 1;
  w.sigma_cells = AssociationSigmaCells(class_pmf, dt_s, cell_size_m, options);
  return w;
}

namespace {

// SearchWindowFor for every source.
std::vector<SearchWindow> PredictedWindows(std::span<const float> velocity_x_mps,
                                           std::span<const float> velocity_y_mps,
                                           std::span<const float> seen,
                                           std::span<const float> confidence,
                                           std::span<const float> class_pmf, double dt_s,
                                           double cell_size_m, const FilterOptions& options) {
  std::vector<SearchWindow> windows(velocity_x_mps.size());
  ParallelForBlocks(windows.size(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      windows[s] = SearchWindowFor(static_cast<double>(velocity_x_mps[s]),
                                   static_cast<double>(velocity_y_mps[s]),
                                   static_cast<double>(seen[s]), static_cast<double>(confidence[s]),
                                   &class_pmf[s * kGridClassCount], dt_s, cell_size_m, options);
    }
  });
  return windows;
}

// MeasuredFlowWindow in place of the wide windows whose flow `flow` measures.
void ApplyMeasuredFlow(std::span<const CellIndex> locals, std::span<const float> class_pmf,
                       double dt_s, double cell_size_m, const FilterOptions& options,
                       const ScanFlow* flow, std::vector<SearchWindow>& windows) {
  if (flow == nullptr || !flow->HasPair()) return;
  std::vector<std::uint8_t> wide(windows.size());
  for (std::size_t s = 0; s < windows.size(); ++s) wide[s] = windows[s].stride != 1 ? 1 : 0;
  const std::vector<FlowMeasurement> measured = flow->MeasureCells(locals, wide);
  for (std::size_t s = 0; s < windows.size(); ++s) {
    if (measured[s].kind == FlowKind::kUnknown) continue;
    windows[s] = MeasuredFlowWindow(measured[s], &class_pmf[s * kGridClassCount], dt_s, cell_size_m,
                                    options);
  }
}

}  // namespace

std::vector<SearchWindow> SourceWindows(
    std::span<const CellIndex> locals, std::span<const float> velocity_x_mps,
    std::span<const float> velocity_y_mps, std::span<const float> seen,
    std::span<const float> confidence, std::span<const float> class_pmf, double dt_s,
    double cell_size_m, const FilterOptions& options, const ScanFlow* flow) {
  std::vector<SearchWindow> windows = PredictedWindows(
      velocity_x_mps, velocity_y_mps, seen, confidence, class_pmf, dt_s, cell_size_m, options);
  ApplyMeasuredFlow(locals, class_pmf, dt_s, cell_size_m, options, flow, windows);
  return windows;
}

Associations CollectSources(const GridLayers& layers, const FilterLayerIds& ids,
                            const WindowIndexer& indexer, const MeasurementGrid& z, double dt_s,
                            const FilterOptions& options) {
  Associations a;
  const auto occupancy = layers.Values(ids.occupancy);
  const auto seen = layers.Values(ids.seen);
  const auto vx = layers.Values(ids.velocity_x_mps);
  const auto vy = layers.Values(ids.velocity_y_mps);
  const auto confidence = layers.Values(ids.velocity_confidence);
  const double cell_size_m = layers.geometry().cell_size_m();
  std::array<std::span<const float>, kGridClassCount> class_layers;
  for (std::size_t k = 0; k < kGridClassCount; ++k) {
    class_layers[k] = layers.Values(ids.class_pmf[k]);
  }
  std::array<std::span<const float>, kNeighbourCount> rigidity_layers;
  for (std::size_t d = 0; d < kNeighbourCount; ++d) {
    rigidity_layers[d] = layers.Values(ids.rigidity[d]);
  }

  // Sources in storage order (a fixed order for a given window: every later sum follows it).
  // One pass over two contiguous layers; the local cell is computed only for the sources.
  // IsSource in float, so that the scan of the whole window compares floats: for a float x,
  // x >= t exactly when x >= the smallest float not below t (the same decisions as IsSource).
  const auto at_least = [](double t) {
    const auto f = static_cast<float>(t);
    return static_cast<double>(f) < t ? std::nextafter(f, 2.0f) : f;
  };
  const float active = at_least(options.active_occupancy);
  const float tracked = at_least(options.tracked_min_occupancy);
  const float seen_threshold = at_least(options.seen_threshold);
  // Bitwise, not short-circuit: both layers read, no branch.
  const auto is_source = [&](std::size_t cell) {
    const float o = occupancy[cell];
    return (o >= active) | ((o >= tracked) & (seen[cell] >= seen_threshold));
  };
  // The window's 160,000 cells hold a few hundred sources: a branch per cell cost 0.2 ms a
  // cycle (ForEachWhere).
  ForEachWhere(occupancy.size(), is_source, [&](std::size_t cell) {
    a.source.push_back(cell);
    a.source_local.push_back(indexer.Local(cell));
  });
  const std::size_t sources = a.SourceCount();
  a.occupancy.resize(sources);
  a.seen.resize(sources);
  a.velocity_x_mps.resize(sources);
  a.velocity_y_mps.resize(sources);
  a.confidence.resize(sources);
  a.class_pmf.resize(sources * kGridClassCount);
  a.rigidity.resize(sources * kNeighbourCount);
  ParallelForBlocks(sources, kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      const std::size_t cell = a.source[s];
      a.occupancy[s] = occupancy[cell];
      a.seen[s] = seen[cell];
      const bool observed = Observed(z.p_occupied[cell]);
      a.velocity_x_mps[s] = static_cast<float>(
          PredictVelocity(static_cast<double>(vx[cell]), dt_s, observed, options));
      a.velocity_y_mps[s] = static_cast<float>(
          PredictVelocity(static_cast<double>(vy[cell]), dt_s, observed, options));
      a.confidence[s] = confidence[cell];
      for (std::size_t k = 0; k < kGridClassCount; ++k) {
        a.class_pmf[s * kGridClassCount + k] = class_layers[k][cell];
      }
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        a.rigidity[s * kNeighbourCount + d] = rigidity_layers[d][cell];
      }
    }
  });
  a.window = PredictedWindows(a.velocity_x_mps, a.velocity_y_mps, a.seen, a.confidence, a.class_pmf,
                              dt_s, cell_size_m, options);
  return a;
}

void PredictFromSources(const WindowIndexer& indexer, double dt_s, double cell_size_m,
                        const FilterOptions& options, const ScanFlow* flow, Associations& a) {
  ApplyMeasuredFlow(a.source_local, a.class_pmf, dt_s, cell_size_m, options, flow, a.window);
  const std::size_t sources = a.SourceCount();
  a.first_entry.resize(sources + 1);
  a.first_entry[0] = 0;
  for (std::size_t s = 0; s < sources; ++s) {
    a.first_entry[s + 1] = a.first_entry[s] + a.window[s].EntryCount();
  }
  const std::size_t entries = a.first_entry.back();
  a.target.resize(entries);
  a.entry_source.resize(entries);
  a.weight.resize(entries);
  const bool with_share = options.moved_share_exponent > 0.0;
  if (with_share) a.stay_share.assign(entries, 0.0f);

  ParallelForBlocks(sources, kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      const SearchWindow& w = a.window[s];
      const CellIndex from = a.source_local[s];
      const std::size_t first = a.first_entry[s];
      // The lattice row by row: a column's storage offset found once, not once an entry.
      const int n = w.size();
      std::array<EntryTarget, kMaxWindowSideCells> column;  // kOutsideWindow: off the window
      for (int u = 0; u < n; ++u) {
        const int tx = from.ix + w.center.ix + w.stride * (u - w.half);
        column[static_cast<std::size_t>(u)] =
            tx >= 0 && tx < indexer.width() ? static_cast<EntryTarget>(indexer.ColumnStorage(tx))
                                            : kOutsideWindow;
      }
      EntryTarget* target = &a.target[first];
      for (int v = 0; v < n; ++v) {
        const int ty = from.iy + w.center.iy + w.stride * (v - w.half);
        EntryTarget* row = target + static_cast<std::ptrdiff_t>(v) * n;
        if (ty < 0 || ty >= indexer.height()) {
          std::fill_n(row, n, kOutsideWindow);
          continue;
        }
        const auto base = static_cast<EntryTarget>(indexer.RowStorage(ty));
        for (int u = 0; u < n; ++u) {
          const EntryTarget c = column[static_cast<std::size_t>(u)];
          row[u] = c == kOutsideWindow ? kOutsideWindow : base + c;
        }
      }
      w.ForEachDenseOffset([&](std::size_t k, const CellIndex& o) {
        const int tx = from.ix + w.center.ix + o.ix;
        const int ty = from.iy + w.center.iy + o.iy;
        target[k] = indexer.Inside(tx, ty) ? static_cast<EntryTarget>(indexer.Storage(tx, ty))
                                           : kOutsideWindow;
      });
      std::fill_n(&a.entry_source[first], w.EntryCount(), static_cast<std::uint32_t>(s));
      // The stay component is the static hypothesis only where the prediction is no motion.
      const bool static_prediction =
          std::hypot(w.mean_x_cells, w.mean_y_cells) < 0.5 && w.stay_weight > 0.0;
      ComputePsi(w, &a.weight[first],
                 with_share && static_prediction ? &a.stay_share[first] : nullptr);
    }
  });
}

Associations PredictAssociations(const GridLayers& layers, const FilterLayerIds& ids,
                                 const WindowIndexer& indexer, const MeasurementGrid& z,
                                 double dt_s, const FilterOptions& options, const ScanFlow* flow) {
  Associations a = CollectSources(layers, ids, indexer, z, dt_s, options);
  PredictFromSources(indexer, dt_s, layers.geometry().cell_size_m(), options, flow, a);
  return a;
}

}  // namespace lookout::grid
