#pragma once

// Scores ego poses against the simulator's truth after every lidar cycle: the
// localisation.* keys of docs/cli-contract.md. The estimate lives in the odometry frame, whose
// pose in the world is the ego's true pose at the first odometry reading (t = 0): the truth is
// brought into that frame by this known start pose, and nothing is fitted to the answer (no
// alignment), so a heading error at the start shows as a growing position error, as it would
// for the grid.
//
// Keys, each with its prefix (`localisation.` for the lidar chain's localisation,
// `localisation.dead_reckoning_` for the dead reckoning beside it): ate_rmse_m (RMS of the
// vehicle origin's position error), heading_rmse_deg, max_error_m, and step_rmse_m: the RMS
// error of the motion from one scan to the next (the relation error of Kuemmerle et al. over
// one scan period), which the grid's velocities feel, where the ATE measures drift.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "lookout/core/ego_state.h"
#include "lookout/core/pose2.h"

namespace lookout::app {

class LocalisationScorer {
 public:
  // `world_from_odom`: the odometry frame in the world; `prefix` e.g. "localisation.".
  LocalisationScorer(const Pose2& world_from_odom, std::string prefix);

  // One cycle: the estimate (odometry frame; nullopt when the source had none: counted) and
  // the true ego pose (world frame) at the same time.
  void Observe(const std::optional<EgoState>& estimate, const Pose2& truth_world);

  // The keys above, once any estimate was observed; `<prefix>missing_frames` always.
  void Report(std::map<std::string, double>& metrics) const;

 private:
  Pose2 odom_from_world_;
  std::string prefix_;
  double sum_position_sq_ = 0.0;
  double sum_heading_sq_ = 0.0;
  double sum_step_sq_ = 0.0;
  double max_error_m_ = 0.0;
  std::optional<Pose2> last_estimate_;
  Pose2 last_truth_;
  std::int64_t steps_ = 0;
  std::int64_t frames_ = 0;
  std::int64_t missing_ = 0;
};

}  // namespace lookout::app
