#pragma once

// Seed 004 section VI as one pure function: association (VI.A), position fusion (VI.B) and
// the fused list (VI.C) of one lidar frame and the stereo objects brought to its stamp.
//
// Space of fusion: Cartesian, the vehicle frame. The paper fuses (range, bearing) from the
// lidar origin; Lookout takes the stereo point as the paper hands it over (range and bearing
// from the lidar origin with their covariance, stereo/stereo_point.h), carries it to Cartesian
// with the Jacobian (stereo/range_bearing.h), and fuses there, because (1) a bearing is an
// angle and an information-weighted mean of angles breaks at the +-pi seam; (2) the lidar
// object's covariance comes in Cartesian form (LidarObject::point_covariance) and the tracker
// wants Cartesian, so fusing in polar would need two more conversions, each a linearisation;
// (3) in Cartesian form the product of the two Gaussians is exact, whereas in polar form it
// is exact only when both sensors share the origin. The linearisation costs under 2 mm here.

#include <cstdint>
#include <span>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/fusion/fusion_options.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {

struct FuseObjectsResult {
  FusedObjectFrame frame;
  std::size_t pairs = 0;  // objects seen by both sensors
  // Lidar objects left out for a non-finite point or velocity or a covariance that is not
  // positive definite (counted; the lidar stage should never make one).
  std::vector<std::uint32_t> dropped_lidar_ids;
  // The lidar objects as fused: the usable ones, in their order, each with the point
  // covariance fusion gave it (LidarPointCovariance: with the camera's class where paired).
  LidarObjectFrame lidar;
};

// `stereo` must already be in the vehicle frame at lidar.stamp (FusionEngine predicts it).
FuseObjectsResult FuseObjects(const LidarObjectFrame& lidar,
                              std::span<const stereo::StereoPoint> stereo,
                              const FusionOptions& options);

// The camera's class as a pmf: `reported` with probability `confidence`, the rest evenly
// over the other classes.
std::array<double, kAllObjectClasses.size()> StereoClassPmf(ObjectClass reported,
                                                            double confidence);

// Whether a velocity with covariance says "moving": speed >= min_speed_mps and
// v^T C^-1 v >= the chi-square (2 dof) quantile of `probability`.
bool IsSignificantlyMoving(const Eigen::Vector2d& velocity_mps,
                           const Eigen::Matrix2d& covariance, double min_speed_mps,
                           double probability);

}  // namespace lookout::fusion
