#pragma once

// Absolute trajectory error (ATE) of an estimated 2D trajectory against a reference: the
// estimate is matched to the reference by time stamp, rigidly aligned to it in closed form, and
// the RMS of the remaining position and heading errors is reported. The relation error of
// Kuemmerle et al. (2009) is in relation_error.h; the text formats in trajectory_io.h.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/pose2.h"

namespace lookout::eval {

// A pose at a time (seconds, in the time base of its log).
struct StampedPose2 {
  double t_s = 0.0;
  Pose2 pose;
};

// Poses in non-decreasing time; a burst may share one stamp.
using Trajectory2 = std::vector<StampedPose2>;

struct TrajectoryErrorOptions {
  // A reference time is matched only if the estimate's poses on both sides of it are at most
  // this far apart: an estimate that stopped for a while says nothing about the time between.
  double max_interpolation_gap_s = std::numeric_limits<double>::infinity();

  // Throws InputError (file "options") naming the bad field.
  void Validate() const;
};

// The pose of `trajectory` at t_s: between the last pose at or before t_s and the first after
// it, the position is interpolated linearly and the heading along the shorter arc; a time equal
// to a stamp gives that pose (the last of a burst sharing it). None before the first or after
// the last stamp, or across a gap wider than max_gap_s. `trajectory` must be sorted by time.
std::optional<Pose2> InterpolatePose(const Trajectory2& trajectory, double t_s,
                                     double max_gap_s = std::numeric_limits<double>::infinity());

// The rigid transform T (rotation and translation, no scale) minimising
// sum_i |T * source_i - target_i|^2 in closed form: the least-squares similarity of Umeyama
// (1991) with the scale fixed to 1, equal to Horn's (1987) absolute orientation. In the plane the
// rotation angle is atan2(sum cross(a_i, b_i), sum dot(a_i, b_i)) over the centred pairs.
// Requires equally long, non-empty inputs.
Pose2 AlignRigid(const std::vector<Eigen::Vector2d>& source,
                 const std::vector<Eigen::Vector2d>& target);

struct AbsoluteTrajectoryError {
  double ate_rmse_m = std::numeric_limits<double>::quiet_NaN();
  double heading_rmse_rad = std::numeric_limits<double>::quiet_NaN();  // after the alignment
  std::size_t matched = 0;    // reference poses matched to the estimate
  std::size_t unmatched = 0;  // reference poses outside the estimate's span or in a gap
  Pose2 alignment;            // estimate frame -> reference frame
};

// ATE of poses already paired one to one (same length): align, then RMS of the errors.
AbsoluteTrajectoryError AbsoluteErrorOfPairs(const std::vector<Pose2>& estimate,
                                             const std::vector<Pose2>& reference);

// ATE of `estimate` against `reference` matched by time: every reference pose is paired with
// the estimate interpolated at its time (InterpolatePose). Throws InputError when a
// trajectory's time goes backwards.
AbsoluteTrajectoryError ComputeAbsoluteTrajectoryError(const Trajectory2& estimate,
                                                       const Trajectory2& reference,
                                                       const TrajectoryErrorOptions& options = {});

// Throws InputError (file `name`, field "[i].t") at the first pose earlier than the one before
// it, or whose time is not finite.
void CheckTrajectoryTimes(const Trajectory2& trajectory, const std::string& name);

}  // namespace lookout::eval
