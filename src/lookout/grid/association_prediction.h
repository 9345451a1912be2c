#pragma once

// Step 2 of docs/extended-grid.md: local association prediction, the paper's eq. 8-9.
//
//   Psi(j -> i) = g(x_j + V(j) dt - x_i, sigma_C(j)) / sum_{i' in W(j)} g(...)        (eq. 8-9)
//
// with g an isotropic Gaussian, W(j) the search window of j. Beyond the paper:
//   - W(j) is centred on the predicted displacement round(V(j) dt / cell), not on x_j, so the
//     speed is not capped at (M / 2) cell / dt;
//   - newly seen occupancy (S(j) < seen_threshold: no velocity yet), or occupancy whose velocity
//     confidence is below known_confidence, gets a coarse wide window
//     (FilterOptions::new_window_*) and a wide sigma, so a 20 m/s car is found in one cycle;
//   - sigma_C(j) = sqrt(sum_c C(j, c) sigma_c^2) dt: the class pmf mixes the per-class velocity
//     noises (the variance of the mixture's velocity change, centred).
// Only sources (IsSource) move; the rest of the map stays in place.

#include <span>
#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/scan_flow.h"
#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

// The position sigma of eq. 8 for a cell of class pmf `class_pmf`, in cells.
double AssociationSigmaCells(const float* class_pmf, double dt_s, double cell_size_m,
                             const FilterOptions& options);

// Whether a cell is a source (its occupancy is moved): O >= active_occupancy, or tracked
// (S >= seen_threshold) and O >= tracked_min_occupancy. The rest of the map stays in place.
bool IsSource(double occupancy, double seen, const FilterOptions& options);

// The motion model's prediction of one velocity component over dt_s: the estimate decays by
// exp(-dt / velocity_persistence_s) where the scan observes the cell, and is carried as it is
// where it does not, with velocity_persists_unobserved (FilterOptions says why). Pure.
double PredictVelocity(double velocity_mps, double dt_s, bool observed,
                       const FilterOptions& options);

// The search window of a source with the given state (used by the fast path and the reference).
SearchWindow SearchWindowFor(double velocity_x_mps, double velocity_y_mps, double seen,
                             double confidence, const float* class_pmf, double dt_s,
                             double cell_size_m, const FilterOptions& options);

// The fine M x M window of a source that would get the wide window but whose displacement the
// scan pair measured (`flow`, scan_flow.h; kStays or kMoves): centred on that displacement, with
// the class's sigma. Used by the fast path and the reference.
SearchWindow MeasuredFlowWindow(const FlowMeasurement& flow, const float* class_pmf, double dt_s,
                                double cell_size_m, const FilterOptions& options);

// Every source's window: SearchWindowFor, then MeasuredFlowWindow for those that got the wide one
// and whose flow `flow` measures (nullptr: none). Sources as the window-local cells `locals`;
// the state arrays are per source. Used by the fast path and the reference.
std::vector<SearchWindow> SourceWindows(
    std::span<const CellIndex> locals, std::span<const float> velocity_x_mps,
    std::span<const float> velocity_y_mps, std::span<const float> seen,
    std::span<const float> confidence, std::span<const float> class_pmf, double dt_s,
    double cell_size_m, const FilterOptions& options, const ScanFlow* flow);

// Eq. 8-9 for every active cell: the sources with their state copied (the velocity predicted,
// observed or not by `z`), their windows, and the normalised Psi in Associations::weight.
// Parallel over sources; deterministic. CollectSources then PredictFromSources.
Associations PredictAssociations(const GridLayers& layers, const FilterLayerIds& ids,
                                 const WindowIndexer& indexer, const MeasurementGrid& z,
                                 double dt_s, const FilterOptions& options,
                                 const ScanFlow* flow = nullptr);

// PredictAssociations in two halves. Why: the first reads no scan pair, so the update runs it
// beside ScanFlow::Prepare (a serial pass). CollectSources: the sources, their state and the
// windows SearchWindowFor gives them (Associations::window; nothing per entry yet).
Associations CollectSources(const GridLayers& layers, const FilterLayerIds& ids,
                            const WindowIndexer& indexer, const MeasurementGrid& z, double dt_s,
                            const FilterOptions& options);
// PredictFromSources: the windows `flow` measures (as SourceWindows), then the entries' targets
// and Psi.
void PredictFromSources(const WindowIndexer& indexer, double dt_s, double cell_size_m,
                        const FilterOptions& options, const ScanFlow* flow,
                        Associations& associations);

}  // namespace lookout::grid
