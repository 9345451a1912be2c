#pragma once

// Step 6 of docs/extended-grid.md: the velocity update, the paper's eq. 14.
//
// The paper's eq. 14 reads the velocity of a cell i from the displacements that carried mass
// into it. Lookout reads it from where each source's mass went, then gathers that per target:
//   for each source j, over its window, weighting each move by whether the mass survived where
//   it went (the target's posterior occupancy O_k(t): a move into a cell now seen free
//   destroyed the mass it carried):
//     mean_j = sum_t P(j -> t) O_k(t) (x_t - x_j) / sum_t P(j -> t) O_k(t)        (cells)
//     var_j  = the same weighted variance of the displacement
//   for a cell i that gathers contributions w_ji = P(j -> i) O_{k-1}(j):
//     v_obs(i)   = sum_j w_ji mean_j / dt / sum_j w_ji
//     spread(i)  = sum_j w_ji (var_j + |mean_j|^2) / sum_j w_ji - |v_obs dt|^2   (cells^2)
//     v_prev(i), c_prev(i) = the w-weighted means of the sources' predicted velocities and
//                            confidences
//     V_k(i)     = (1 - b) v_prev + b v_obs,    b = 1 - (1 - velocity_blend) c_prev
//     conf_k(i)  = S_k(i) [(1 - velocity_blend) c_prev + velocity_blend / (1 + spread / s0)]
// with s0 = confidence_spread_cells2. Why not the paper's form: at the end of a straight
// surface (a wall beside the road) a cell gathers mass from one side only, so the mean of the
// displacements that reached it points along the surface although nothing moved; a driving ego
// reveals such ends all the time, and the paper's form read 20-40 % of the static world as
// moving on the catalogue. Per source, a wall cell's mass stays where its window is symmetric,
// and its velocity stays what the prediction said. A carried velocity of zero confidence is
// replaced by the observation (b = 1), a confident one is blended. Newly appearing occupancy
// (S ~ 0, step 5) gets zero confidence, as the paper's uniform velocity pmf. A source that
// received nothing (everything left it) is reset to V = 0, conf = 0; other cells keep their
// velocity.

#include <span>
#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {

// How much a source's move into a target of posterior occupancy `target_occupancy` and
// measurement `target_measurement` counts towards the source's mean displacement
// (FilterOptions::survival_needs_evidence). Pure.
double SurvivalWeight(double target_occupancy, double target_measurement,
                      const FilterOptions& options);

struct VelocityLayers {
  std::span<float> velocity_x_mps;
  std::span<float> velocity_y_mps;
  std::span<float> confidence;
};

// `seen` must already hold S_k (UpdateOccupancy). `cells`: the update list, or its MovedCells
// (the others keep their velocity). Parallel over the cells; deterministic.
void UpdateVelocity(const Associations& associations, const TargetIndex& targets,
                    std::span<const UpdateCell> cells, double dt_s, double cell_size_m,
                    const FilterOptions& options, const MeasurementGrid& z,
                    std::span<const float> occupancy, std::span<const float> seen,
                    const VelocityLayers& out);

}  // namespace lookout::grid
