#pragma once

// A slow literal reference of the extended grid's steps 2-7 (docs/extended-grid.md), for tests
// and for measuring the fast path's speed-up (`lookout bench`), never in the pipeline: the
// equations as they read, in double precision, scatter-based (each source pushes its contributions
// into dense accumulators), no active-set bookkeeping, no target index, and the unfactorised
// rigidity term of eq. 11 (every move of every linked neighbour for every move of the cell:
// 8 M^4 products a source over the eight neighbours whose links the grid stores; the paper's
// O(M^6) links every cell of the window). It shares
// with the fast path only the window choice (SourceWindow: a design choice, not an equation),
// the stage after step 7 that measures each rigid cluster whole (cluster_motion.h: beyond the
// paper, no equation of it; run when a scan pair is given) and the options. Step 8 (classes) is
// not part of it.

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {

// Updates occupancy, seen, velocity, confidence and rigidity layers of `layers` (ids as
// AddFilterLayers made them) with `z`, as ExtendedGrid::Update does before its class step.
// `flow`: the scan pair the windows see (prepared with z: a copy of the grid's
// ExtendedGrid::scan_flow() before its Update, then ScanFlow::Prepare(z)); nullptr: none.
void ReferenceUpdate(GridLayers& layers, const FilterLayerIds& ids, const MeasurementGrid& z,
                     double dt_s, const FilterOptions& options, const ScanFlow* flow = nullptr);

}  // namespace lookout::grid
