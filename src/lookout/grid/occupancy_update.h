#pragma once

// Step 5 of docs/extended-grid.md: the occupancy update, the paper's eq. 12-13.
//
// The form chosen (the paper leaves P(S) and Punseen vague), for each cell i of the update list:
//   carried(i) = sum_j P(j -> i) O_{k-1}(j)                     over the sources j    (eq. 13)
//   cover(i)   = sum_j P(j -> i)
//   if i is a source (its content moved out):
//     P(S=1) = cover(i), Pseen = carried(i) / cover(i)      (what the associations bring in)
//     P(S=0) = 1 - cover(i), Punseen = gamma / 2            (new space: renewed towards unknown)
//     prior  = P(S=1) Pseen + P(S=0) Punseen = carried + (1 - cover) gamma / 2          (eq. 12)
//   else (its content stays, P(S=1) = 1):
//     prior  = max(carried(i), O_{k-1}(i))
//   O_k(i) = prior m / (prior m + (1 - prior)(1 - m)),   m = P(M_k(i) = 1 | z_k),
// carried and cover capped at 1, O_k clamped to [occupancy_clamp, 1 - occupancy_clamp].
// Reading:
//   - the sensor enters once, by Bayes' rule on the prior: a proper fusion in observed cells,
//     and m = 1/2 leaves the prediction untouched in unobserved ones;
//   - gamma, the paper's renewal rate, is the occupancy prior of space no association covers,
//     as a fraction of the unknown 1/2: a cell an object left and no one observes drifts back
//     towards unknown, not towards free;
//   - carried mass is never scaled down by P(S): an occluded object's mass is kept whole while
//     it spreads (the paper's Fig. 1-3);
//   - why max and not a sum (or a union) for a cell whose own content stays: the eq. 13 sum
//     treats every term as mass, but an inactive cell's O is mostly ignorance (0.5 in shadows)
//     or free space; adding the small mass that leaks from the Gaussian of a neighbouring wall
//     into its shadow every cycle accumulated until the shadow turned "occupied" and started
//     moving (measured on the junction benchmark: 30 000 sources instead of ~350). The max is
//     the conservative union (the two being fully correlated).
// The seen layer stores the share of the prior that tracked cells carried in:
// S(i) = min(1, carried(i)) / prior(i), or O_{k-1}(i) S_{k-1}(i) / prior(i) where the cell's own
// content wins the max (what stays keeps its seen share). Newly appearing occupancy has S ~ 0; it
// gets the wide search of step 2 and zero velocity confidence (step 6).

#include <span>
#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {

// Writes O_k and S_k of the update cells into `occupancy` and `seen` (storage order). Parallel
// over the update cells (each writes its own cell); deterministic.
void UpdateOccupancy(const Associations& associations, const TargetIndex& targets,
                     const std::vector<UpdateCell>& cells, const MeasurementGrid& z,
                     const FilterOptions& options, std::span<float> occupancy,
                     std::span<float> seen);

}  // namespace lookout::grid
