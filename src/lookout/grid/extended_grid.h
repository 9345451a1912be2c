#pragma once

// The extended occupancy grid of seed 000 (docs/extended-grid.md): per cell occupancy,
// velocity with confidence, seen probability, rigidity links and a class pmf, updated by a
// per-cell Bayesian filter without any a priori on objects.
//
// One cycle, after the caller moved the window (Recenter) and computed the measurement grid in
// the new window (ComputeInverseSensorModel):
//     grid.Recenter(ego_position_m);
//     grid.Update(ComputeInverseSensorModel(scan, sensor_pose, grid.geometry(), ism), dt_s);
// Update reads as the paper's stages, each a free function in its own file pair.
//
// Deterministic: the same inputs give the same bytes out for any number of TBB threads (every
// parallel loop writes distinct cells and gathers its sums in one fixed order).

#include <utility>
#include <vector>

#include "lookout/grid/class_update.h"
#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/hidden_bodies.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

class ExtendedGrid {
 public:
  // Validates `options` (lookout::InputError).
  ExtendedGrid(const ScrollingGridGeometry& geometry, const FilterOptions& options = {});

  const ScrollingGridGeometry& geometry() const { return layers_.geometry(); }
  const GridLayers& layers() const { return layers_; }
  // For tests and tools that seed a state; keep the layers' meaning (filter_state.h).
  GridLayers& mutable_layers() { return layers_; }
  const FilterLayerIds& ids() const { return ids_; }
  const FilterOptions& options() const { return options_; }
  // The scan pair's memory (the last Update's hits), for the reference and tests.
  const ScanFlow& scan_flow() const { return flow_; }
  // The bodies carried through a shadow (hidden_bodies.h).
  const HiddenBodies& hidden_bodies() const { return hidden_; }

  // Moves the window (new cells get the priors: O = 0.5, no velocity, uniform class).
  VacatedCells Recenter(const Eigen::Vector2d& position_m) { return layers_.Recenter(position_m); }

  // Camera objects for the next Update's class step (step 8); consumed by it.
  void SetStereoClassEvidence(std::vector<StereoClassRegion> regions) {
    stereo_ = std::move(regions);
  }

  // One cycle of steps 2-8 with measurement `z` (computed in this grid's current window) taken
  // dt_s after the previous one. Precondition: z.geometry has this grid's window, dt_s > 0.
  void Update(const MeasurementGrid& z, double dt_s);

  // What the last Update did (for benchmarks and tests).
  struct Stats {
    std::size_t sources = 0;       // active cells moved
    std::size_t associations = 0;  // window entries over all sources
    std::size_t updated_cells = 0;
    // Wall time of the cycle's parts, ms (benchmarks only: never in any output). `motion_ms` is
    // what ReferenceUpdate computes too (the scan pair's preparation, steps 2-7, the clusters'
    // stage), the part the literal reference's speed is compared with.
    double motion_ms = 0.0;
    double hidden_bodies_ms = 0.0;
    double classes_ms = 0.0;  // step 8 and the cycle's bookkeeping
  };
  const Stats& last_stats() const { return stats_; }

 private:
  FilterOptions options_;
  GridLayers layers_;
  FilterLayerIds ids_;
  FilterWorkspace workspace_;
  ScanFlow flow_;
  HiddenBodies hidden_;
  std::vector<StereoClassRegion> stereo_;
  Stats stats_;
};

}  // namespace lookout::grid
