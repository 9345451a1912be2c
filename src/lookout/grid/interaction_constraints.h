#pragma once

// Step 4 of docs/extended-grid.md: the interaction constraints, the paper's eq. 11, in a
// factorised form.
//
//   P(j -> i) = Pw(j -> i) NC(j -> i) R(j -> i) / sum over W(j)                            (eq. 11)
//
// No convergence: with In(i) = sum_j' Pw(j' -> i) O(j') the occupancy mass poured into i,
//   NC(j -> i) = exp(-e^2 / (2 sigma_nc^2)),  e = max(0, In(i) - Pw(j -> i) O(j) + O(j) - 1):
// the mass the other cells send to i beyond what i can hold next to j's own (i holds 1).
//
// Rigidity: for each 8-neighbour y of j that is itself a source, linked with strength
// D = min(1, rigidity_link_gain D(j, y)) (D(j, y) of eq. 15, carried with j),
//   literal:  R(j -> i) = prod_y [(1 - D) + D sum_a' Pw(y moves by a') K(a - a')]
// with a = x_i - x_j, K(d) = exp(-|d|^2 / (2 r^2)), r = rigidity_sigma_cells. The literal form
// visits every move of every neighbour for every move of j (O(M^4) per neighbour, O(M^6) over an
// M x M neighbourhood). Factorised, a neighbour enters through one precomputed array:
//   - B_y(a) = sum_a' Pw(y moves by a') K(a - a') on y's own window lattice, computed once per
//     source by a separable blur (O(M^3)); when y's window has the same lattice as j's (the
//     common case: neighbours of one object share their rounded prediction and window kind) the
//     literal term is read from B_y exactly;
//   - otherwise, y's pmf is replaced by the Gaussian of its two moments (mean m_y, per-axis
//     variance t_y^2), for which the sum is closed-form (a Gaussian blurred by a Gaussian):
//     r^2 / (r^2 + t_y^2) exp(-|a - m_y|^2 / (2 (r^2 + t_y^2))).
// Cost O(M^3 + M^2 K) per source. The reference (reference_filter.h) keeps the literal form; a
// test bounds the difference (which comes from the second case only).
// Both constraints read Pw of the previous stage only (one Jacobi-like pass, order-free).

#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {

// The mean and per-axis variance of a source's displacement pmf, in cells.
struct DisplacementMoments {
  double mean_x_cells = 0.0;
  double mean_y_cells = 0.0;
  double variance_cells2 = 0.0;  // per axis
};

// What the rigidity term reads of each linked neighbour y: B_y over y's window (EntryCount()
// floats, laid out as associations.weight) and, unless rigidity_exact_across_lattices, y's
// moments. Empty when the rigidity constraint is off.
struct RigidityBlur {
  std::vector<float> blurred;
  std::vector<DisplacementMoments> moments;
  std::vector<double> integer_kernel;  // K's 1-D factor at whole-cell offsets 0, 1, ...
};

// B_y and the moments of the sources ApplyConstraints reads them of (a source some neighbour
// links to), from Pw (the weights after step 3); the others' are left 0. Why apart from
// ApplyConstraints: it reads neither the target index nor the update list, so the update runs it
// beside the serial passes that build them. `workspace.source_of_cell` must map the sources
// (MapSources). Parallel over sources; deterministic.
RigidityBlur BlurForRigidity(const Associations& associations, const WindowIndexer& indexer,
                             const FilterWorkspace& workspace, const FilterOptions& options);

// Replaces associations.weight (Pw) by P of eq. 11. `workspace.source_of_cell` must map the
// sources (MapSources); `blur` is BlurForRigidity of the same Pw. Parallel over targets, then
// over sources; deterministic.
void ApplyConstraints(const WindowIndexer& indexer, const TargetIndex& targets,
                      const FilterWorkspace& workspace, const FilterOptions& options,
                      const RigidityBlur& blur, Associations& associations);

}  // namespace lookout::grid
