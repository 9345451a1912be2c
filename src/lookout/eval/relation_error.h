#pragma once

// The relation-based error of Kuemmerle et al., "On measuring the accuracy of SLAM algorithms"
// (Autonomous Robots 27(4), 2009). A relation is the reference's relative motion
// delta*_ij = x*_i^-1 x*_j between two times; the estimate's own relative motion
// delta_ij = x_i^-1 x_j is compared with it by the paper's metric
//   epsilon(delta) = 1/N sum_ij trans(delta_ij (-) delta*_ij)^2 + rot(delta_ij (-) delta*_ij)^2,
// with a (-) b = b^-1 a. Unlike the ATE, an early error is not propagated to every later pose:
// each relation sees only the error accumulated between its two times. As the paper's tables
// do, translation and rotation are kept apart, each as mean and standard deviation of the
// absolute and of the squared error.

#include <cstddef>
#include <limits>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/eval/trajectory_error.h"

namespace lookout::eval {

// The reference motion from the pose at t1_s to the pose at t2_s, in the frame of the first.
struct Relation2 {
  double t1_s = 0.0;
  double t2_s = 0.0;
  Pose2 motion;
};

struct RelationError {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Standard deviations are of the population (divided by N): the relations are all there is.
  double translation_mean_m = kNaN;
  double translation_std_m = kNaN;
  double translation_squared_mean_m2 = kNaN;
  double translation_squared_std_m2 = kNaN;
  double rotation_mean_rad = kNaN;  // |yaw| of the error, in [0, pi]
  double rotation_std_rad = kNaN;
  double rotation_squared_mean_rad2 = kNaN;
  double rotation_squared_std_rad2 = kNaN;
  std::size_t used = 0;       // relations whose two times the estimate covers
  std::size_t unmatched = 0;  // relations with a time outside the estimate (or in a gap)
};

// The relation error of `estimate`, interpolated at each relation's two times as
// InterpolatePose does. Throws InputError when the estimate's time goes backwards.
RelationError ComputeRelationError(const Trajectory2& estimate,
                                   const std::vector<Relation2>& relations,
                                   const TrajectoryErrorOptions& options = {});

struct RelationGeneratorOptions {
  // Pair each reference pose i with pose i + step_poses ...
  std::size_t step_poses = 1;
  // ... or, when positive, with the first pose at least this far along the reference path
  // (the paper's relations are between scans some metres apart). Poses with no such partner
  // make no relation.
  double min_travel_m = 0.0;

  // Throws InputError (file "options") naming the bad field.
  void Validate() const;
};

// Relations from a reference trajectory (the paper builds them from manually checked scan
// matches; a trajectory taken as the reference gives the same kind of data).
std::vector<Relation2> GenerateRelations(const Trajectory2& reference,
                                         const RelationGeneratorOptions& options = {});

}  // namespace lookout::eval
