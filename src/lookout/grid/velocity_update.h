#pragma once

// Step 6 of docs/extended-grid.md: the velocity update, the paper's eq. 14.
//
// For a cell i that gathers contributions w_ji = P(j -> i) O_{k-1}(j) from tracked cells:
//   v_obs(i)   = sum_j w_ji (x_i - x_j) / dt / sum_j w_ji                            (eq. 14)
//   spread(i)  = sum_j w_ji |x_i - x_j - mean|^2 / sum_j w_ji                (cells^2)
//   v_prev(i), c_prev(i) = the w-weighted means of the sources' velocities and confidences
//   V_k(i)     = (1 - b) v_prev + b v_obs,    b = 1 - (1 - velocity_blend) c_prev
//   conf_k(i)  = S_k(i) [(1 - velocity_blend) c_prev + velocity_blend / (1 + spread / s0)]
// with s0 = confidence_spread_cells2. A carried velocity of zero confidence is replaced by the
// observation (b = 1), a confident one is blended. Newly appearing occupancy (S ~ 0, step 5)
// gets zero confidence, as the paper's uniform velocity pmf. A source that received nothing
// (everything left it) is reset to V = 0, conf = 0; other cells keep their velocity.

#include <span>
#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {

struct VelocityLayers {
  std::span<float> velocity_x_mps;
  std::span<float> velocity_y_mps;
  std::span<float> confidence;
};

// `seen` must already hold S_k (UpdateOccupancy). Parallel over the update cells; deterministic.
void UpdateVelocity(const Associations& associations, const TargetIndex& targets,
                    const std::vector<UpdateCell>& cells, double dt_s, double cell_size_m,
                    const FilterOptions& options, std::span<const float> seen,
                    const VelocityLayers& out);

}  // namespace lookout::grid
