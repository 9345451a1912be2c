#pragma once

// Two estimates of one front point built on the same heading share part of their error. The
// camera's point turns its box by the camera's heading, and the lidar's side point for a round
// body turns its square by the same heading (FacingSidePoint): the turn of the side's middle and
// the choice of which side faces the lidar are one error in both. Fused as independent, the
// heading is counted twice and the fused covariance is too small where the heading matters:
// across the ray, where both points are sharpest, the crowd's side and camera errors were
// correlated at 0.15-0.19 (docs/fusion.md, "Two bodies in one pair"). This is their
// cross-covariance, E[e_a e_b^T], for FuseCorrelated (gaussian_fusion.h).

#include <Eigen/Core>

#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {

// The turn: sigma_yaw^2 J_a J_b^T, the heading slopes of the two means (one heading error; the
// geometric mean of the two variances, which are the camera's one variance in use).
// The side choice: each estimate's error along the two side middles' offset D is (q - I) D,
// I the indicator that the other side faces; both indicators are one fact, coupled as
// comonotone Bernoulli variables (the largest covariance their own variances allow):
// cov = min(q_a, q_b) - q_a q_b where both chose the same side (D_a . D_b >= 0), and
// -(min(q_a, 1 - q_b) - q_a (1 - q_b)) where each chose the other's other. The joint
// covariance stays positive semidefinite where each estimate's own covariance holds its
// share (ExpectedFrontPoint's do). Zero when either shares nothing. Pure.
Eigen::Matrix2d SharedHeadingCovariance(const stereo::HeadingShare& a,
                                        const stereo::HeadingShare& b);

}  // namespace lookout::fusion
