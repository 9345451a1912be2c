#pragma once

// Step 7 of docs/extended-grid.md: the rigidity links, the paper's eq. 15.
//
//   D_k(x, y) = sum_a P(x moves by a) P(y moves by a)                                  (eq. 15)
//
// over the 8-neighbours y of each tracked cell x, with P the associations of eq. 11. Two cells
// whose move pmfs agree (and are sharp) are likely one rigid body. The links are computed at the
// sources and carried to the targets like every other attribute (w_ji-weighted mean), so at time
// k they sit where the occupancy went. Cells with no tracked neighbour, and new cells, have no
// link (0).

#include <array>
#include <span>
#include <vector>

#include "lookout/grid/filter_state.h"

namespace lookout::grid {

// D_k(j, j + offset[d]) for every source j, kNeighbourCount per source. Needs
// workspace.source_of_cell mapped. Parallel over sources; deterministic.
std::vector<float> ComputeRigidityLinks(const Associations& associations,
                                        const WindowIndexer& indexer,
                                        const FilterWorkspace& workspace);

// Computes the links and carries them to the update cells of `rigidity` (one layer per
// direction). A source that received nothing loses its links. `cells`: the update list, or its
// MovedCells (the others keep their links).
void UpdateRigidity(const Associations& associations, const TargetIndex& targets,
                    std::span<const UpdateCell> cells, const WindowIndexer& indexer,
                    const FilterWorkspace& workspace,
                    const std::array<std::span<float>, kNeighbourCount>& rigidity);

}  // namespace lookout::grid
