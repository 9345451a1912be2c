#include "lookout/fusion/gate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/pose2.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// The gate's half-length along the line of sight grows with depth, as the stereo depth error
// (z^2) does: from under a metre at 5 m to about 4 m at 35 m.
TEST(GateTest, GrowsWithDepth) {
  const FusionOptions options;
  const AssociationGate gate(options);
  const stereo::StereoDepthModel& model = options.stereo.depth_model;
  double previous = 0.0;
  for (double depth = 2.0; depth <= 35.0; depth += 1.0) {
    const double half_length = gate.HalfLengthAlongRay(model, Vector2d(depth, 0.0), 0.1);
    EXPECT_GT(half_length, previous) << "depth " << depth;
    previous = half_length;
  }
  EXPECT_NEAR(gate.HalfLengthAlongRay(model, Vector2d(5.0, 0.0), 0.1), 0.82, 0.01);
  EXPECT_NEAR(gate.HalfLengthAlongRay(model, Vector2d(35.0, 0.0), 0.1), 3.96, 0.01);
}

// The same through DistanceSquared, as association uses it: a lidar point 1.5 m short of the
// stereo point along the ray is outside the gate at 10 m and inside it at 30 m; one 1.5 m to
// the side is outside at both depths (the gate is narrow across the ray).
TEST(GateTest, AcceptsAlongTheRayFarAwayButNotAcrossIt) {
  const FusionOptions options;
  const AssociationGate gate(options);
  const stereo::StereoDepthModel& model = options.stereo.depth_model;
  const Matrix2d lidar_covariance = 0.01 * Matrix2d::Identity();
  for (const double depth : {10.0, 30.0}) {
    const Vector2d stereo(depth, 0.0);
    const Matrix2d stereo_covariance = model.PointCovariance(stereo);
    const double along = gate.DistanceSquared(stereo, stereo_covariance,
                                              stereo - Vector2d(1.5, 0.0), lidar_covariance);
    const double across = gate.DistanceSquared(stereo, stereo_covariance,
                                               stereo + Vector2d(0.0, 1.5), lidar_covariance);
    EXPECT_EQ(gate.Accepts(along), depth > 20.0) << "depth " << depth << ", d2 " << along;
    EXPECT_FALSE(gate.Accepts(across)) << "depth " << depth << ", d2 " << across;
  }
}

TEST(GateTest, ThresholdFollowsTheProbability) {
  FusionOptions options;
  options.gate_probability = 0.95;
  EXPECT_NEAR(AssociationGate(options).threshold(), -2.0 * std::log(0.05), 1e-9);
}

}  // namespace
}  // namespace lookout::fusion
