#pragma once

// Options of the fusion stage (seed 004 section VI), one struct, units in the names.

#include "lookout/fusion/lidar_point_model.h"
#include "lookout/stereo/stereo_options.h"

namespace lookout::fusion {

// Where a fused object's velocity comes from when both sensors saw it.
enum class VelocitySource {
  // Both, weighted by their covariances (the same formula as the positions): both sensors
  // measure the velocity over the ground, the camera from 6D optical flow in one frame
  // (0.3 m/s near, 0.8 m/s at 35 m), the grid from many scans; the covariances say which is
  // better for this object, and the weighted mean is never worse than either in expectation.
  kInformationWeighted,
  kLidar,   // the lidar object's alone
  kStereo,  // the camera's alone
};

struct FusionOptions {
  stereo::StereoObjectOptions stereo;

  // Association gate (docs/fusion.md): a stereo and a lidar point may pair when their
  // Mahalanobis distance under S = R_L + R_V(z) + sigma_def^2 I is within the chi-square
  // (2 dof) quantile of gate_probability. R_V(z) grows with the stereo depth, so the gate does.
  double gate_probability = 0.99;
  // The two sensors' points are not the same point exactly (the lidar's front segment is
  // what the scan saw of the outline, the camera's the middle of its box's side): this much
  // disagreement (m, each axis) is allowed for in the gate. Not in the fused covariance.
  double point_definition_sigma_m = 0.25;

  // A pair whose two points disagree beyond the chi-square (2 dof) quantile of
  // disagreement_probability under their own covariances (no point_definition_sigma_m) has its
  // fused covariance scaled by d^2 / quantile (DisagreementScale, gaussian_fusion.h): the fused
  // point stays, its covariance holds the disagreement. 1: off. 0.95 since the lidar's point
  // for a well-seen walker is no longer 3-10 times too wide in variance (docs/fusion.md, "A
  // whole arc's centre"): at 0.99 the few pairs of a walker's camera object with a neighbour's
  // segment (a child behind its parent) took pushchair-group's fused NEES out of its band.
  double disagreement_probability = 0.95;
  // A pair whose two points disagree beyond the chi-square (2 dof) quantile of this
  // probability (under the same covariances) is taken as one point on something else: the
  // fused covariance, scaled as above, becomes TwoBodiesMixture's (gaussian_fusion.h), the
  // fusion and each point alone as three hypotheses about the fused point. Beyond this point
  // an understated covariance no longer explains the disagreement (the crowd: a walker's camera
  // object with a neighbour's segment, its own hidden). The same point for the body's history
  // (history_disagreement_probability). 1: off. 0.999: at 0.99 the mixture takes the
  // disagreements of right-turn-cyclist's corner views, whose fused point is right
  // (docs/fusion.md, "Two bodies in one pair").
  double two_bodies_probability = 0.999;

  // Pieces (fuse_objects.h): an unpaired dynamic lidar object whose front segment comes within
  // this distance of another dynamic lidar object's (a longer one, or one the camera paired) is
  // a piece of the same body, left out. 0: off. 0.5 m: fig8's cyclist comes apart as its side
  // and its front face 0.46 m apart; 0.3 m catches a third of the crowd's pieces, 0.8 m no more
  // than 0.5 m does (docs/fusion.md, "Pieces").
  double piece_gap_m = 0.5;

  // What the lidar object's point covariance leaves out (lidar_point_model.h), added before
  // the pair is fused. Not in the gate: the gate has point_definition_sigma_m for that, and a
  // segmentation object's class is known only once the camera has paired it.
  LidarPointModelOptions lidar_point;

  // Time offset: the latest stereo frame is predicted to the lidar stamp with its speeds. A
  // frame further than this from the lidar stamp (either way) is not used: at 20 Hz the latest
  // one is at most 50 ms old.
  double max_stereo_age_s = 0.1;
  // White-noise acceleration of the prediction: the covariance grows by
  // (acceleration_sigma dt^2 / 2)^2 per axis for the position, (acceleration_sigma dt)^2 for
  // the velocity. 3 m/s^2 covers braking and a pedestrian's start.
  double acceleration_sigma_mps2 = 3.0;

  // A camera track's last pair as a second gate for its next (pair_memory.h): kept this long
  // (a lidar frame is 80 ms); 0: off, each frame pairs afresh as the paper does.
  double pair_memory_s = 0.3;
  // A pair whose fused point disagrees with its camera track's own prior (the last pair's
  // fused point predicted to this stamp) beyond the chi-square (2 dof) quantile of this
  // probability, under the two covariances summed, has its fused covariance scaled by
  // d^2 / quantile, as DisagreementScale does for the pair's two points, and, still beyond
  // two_bodies_probability's point, made DisagreementMixture's (gaussian_fusion.h): the fused
  // point or the body's history right, the spread along the offset between them (the
  // mixture at this 0.99 point widened right points: docs/fusion.md, "Two bodies in one
  // pair"). The camera's depth cannot tell a walker from the
  // lamp post it passes (a walker's camera object with the post's segment, its own returns
  // hidden, in the crowd: the pair agrees within its gate, the body's history 0.4 m away does
  // not). 1: off. 0.99, since at 0.95 right-turn-cyclist's fused NEES fell under its band
  // (docs/fusion.md, "A body's own history").
  double history_disagreement_probability = 0.99;

  VelocitySource velocity_source = VelocitySource::kInformationWeighted;

  // A stereo class becomes a pmf: the reported class with this probability, the rest spread
  // evenly over the other five (the camera's confusion model; the simulator's class_accuracy).
  double stereo_class_confidence = 0.9;

  // An object whose velocity comes from the camera (alone or fused) is dynamic when its speed
  // is at least dynamic_speed_mps and significantly above zero: v^T C^-1 v beyond the
  // chi-square (2 dof) quantile of dynamic_probability. A lidar object's own flag (the grid's,
  // from many scans) counts too.
  double dynamic_speed_mps = 0.5;
  double dynamic_probability = 0.99;

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;
};

}  // namespace lookout::fusion
