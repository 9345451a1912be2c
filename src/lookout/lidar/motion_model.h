#pragma once

// Motion models of the particle filter's prediction (seed 004 IV.A: "the car-like motion
// model"): the odometry increment between two scans, perturbed in the model's own parameters,
// applied to a particle. Pure functions of the increment, the options and the random stream.
//
// - Bicycle (car-like): a car cannot turn on the spot or slide sideways, so an increment is an
//   arc of signed length s at a steering angle delta (curvature tan(delta) / wheelbase). The
//   noise is on s (relative) and on delta (absolute), and delta is clamped to the steering
//   limit: every sampled motion is one a car can drive.
// - Differential drive (robot logs): rotate rot1, translate trans, rotate rot2 (Thrun, Burgard,
//   Fox, Probabilistic Robotics, table 5.6), any increment is reachable.

#include "lookout/core/pose2.h"
#include "lookout/core/random.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

// The arc parameters of an increment (in the start frame): signed arc length and heading
// change. Exact for an increment that is an arc; for one that is not (a sideways slip, which
// a car cannot drive) the chord's length and the heading change are kept.
struct Arc {
  double length_m = 0.0;
  double heading_change_rad = 0.0;
};
Arc ArcOfIncrement(const Pose2& increment);
// The increment of driving an arc from the origin heading along +x.
Pose2 IncrementOfArc(const Arc& arc);

// Differential-drive decomposition of an increment: rot1, trans, rot2 (trans negative when
// the motion is backwards, so that reversing does not read as a half turn).
struct RotTransRot {
  double rot1_rad = 0.0;
  double trans_m = 0.0;
  double rot2_rad = 0.0;
};
RotTransRot DecomposeIncrement(const Pose2& increment);
Pose2 ComposeIncrement(const RotTransRot& motion);

// A sample of the pose reached from `pose` when odometry measured `increment` (in the vehicle
// frame at the start). With all noise options zero it is exactly pose * increment for the
// differential drive, and for the bicycle when the increment is a drivable arc.
Pose2 SampleBicycle(const Pose2& pose, const Pose2& increment, const MotionModelOptions& options,
                    Rng& rng);
Pose2 SampleDifferentialDrive(const Pose2& pose, const Pose2& increment,
                              const MotionModelOptions& options, Rng& rng);
// The model that options.kind selects.
Pose2 SampleMotion(const Pose2& pose, const Pose2& increment, const MotionModelOptions& options,
                   Rng& rng);

}  // namespace lookout::lidar
