#pragma once

// Seed 004 section V.C: a stereo object projected onto the laser plane and into the vehicle
// frame, reduced to the middle of its front line segment, and given as range and bearing from
// the lidar's origin: the point fusion works with.

#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/stereo/oriented_box.h"
#include "lookout/stereo/range_bearing.h"
#include "lookout/stereo/stereo_options.h"
#include "lookout/stereo/stereo_validation.h"

namespace lookout::stereo {

// The part of a front point's error that comes from the box's heading (ExpectedFrontPoint),
// which every estimate built on the same heading shares: the camera's own point, and the
// lidar's side point for a round body, whose square the camera's heading turns
// (fusion::FacingSidePoint). Two such estimates are not independent, and their fusion must not
// count the heading twice (fusion::SharedHeadingCovariance). Zero: nothing shared.
struct HeadingShare {
  double yaw_variance = 0.0;  // rad^2
  // The side choice: q, the probability that the other side faces, and m_b - m_a, from the
  // chosen side's middle to the other's.
  double other_side_probability = 0.0;
  Eigen::Vector2d other_side_offset_m = Eigen::Vector2d::Zero();
  // The turn: d(mean)/d(yaw), the two sides' slopes weighted as the mean weighs them.
  Eigen::Vector2d heading_slope_m = Eigen::Vector2d::Zero();
};

struct StereoPoint {
  std::uint32_t id = 0;  // the camera's track id
  ObjectClass object_class = ObjectClass::kUnknown;
  std::uint32_t history = 0;  // frames the camera has tracked it
  OrientedBox footprint;      // vehicle frame
  // Over the ground, in vehicle axes (the camera reports it in its own axes).
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Identity();
  FrontSegment front;     // vehicle frame, the side facing the lidar origin
  // The object's point, vehicle frame: ExpectedFrontPoint, which is front.midpoint_m except
  // near a corner view (fusion::PredictStereoPoint carries front.midpoint_m with this
  // covariance: the likelier side, not the mixture's mean).
  CartesianPoint point;
  RangeBearing polar;     // the same point from the lidar origin, in the lidar frame
  double depth_m = 0.0;   // of the centre, along the camera's axis
  double yaw_variance = 0.0;  // of footprint.yaw_rad, rad^2 (the camera's)
  HeadingShare heading_share;  // what of point's error the heading makes
};

// The expected front point of a box whose centre and heading are uncertain (vehicle frame;
// centre covariance `center_covariance`, heading variance `yaw_variance`), seen from
// `viewpoint_m`. Far from a corner view it is FrontSegmentFacing's midpoint m with covariance
//     P = C + sigma_yaw^2 (dm/dyaw) (dm/dyaw)^T
// (centre and heading errors independent, as the camera reports no cross term). Near a corner
// view a small error may have picked the wrong side, whose middle lies up to half a diagonal
// away: the test g = W |u_x| - L |u_y| that picks the side (u the viewpoint in box axes) is
// linearised, q = Phi(-|g| / sigma_g) is the probability that the other side faces the
// viewpoint, and the point is the moments of the two-sided mixture:
//     mean = (1 - q) m_a + q m_b,  cov = (1 - q) P_a + q P_b + q (1 - q) (m_b - m_a)(m_b - m_a)^T
// the least-squares estimate of the true side's middle, with a covariance that is honest
// about the ambiguity. nullopt when the viewpoint is inside the box. `share`, when given,
// receives the heading's part of that error (HeadingShare).
// The q of ExpectedFrontPoint alone: the probability that the side facing `viewpoint_m` is
// not the one FrontSegmentFacing picks, from the box's centre and heading uncertainty. 0 when
// the viewpoint is inside the box.
double OtherSideProbability(const OrientedBox& box, const Eigen::Matrix2d& center_covariance,
                            double yaw_variance, const Eigen::Vector2d& viewpoint_m);

std::optional<CartesianPoint> ExpectedFrontPoint(const OrientedBox& box,
                                                 const Eigen::Matrix2d& center_covariance,
                                                 double yaw_variance,
                                                 const Eigen::Vector2d& viewpoint_m,
                                                 HeadingShare* share = nullptr);

// The object's point and its covariance in the vehicle frame (ExpectedFrontPoint, the centre's
// covariance rotated from the camera frame into the vehicle frame), then its range and bearing
// from the lidar origin, the covariance carried over by the Jacobian.
// Returns why the object was dropped when it cannot be used (CheckStereoObject, or the lidar
// origin inside its footprint).
std::variant<StereoPoint, DropReason> ProjectStereoObject(const StereoObject& object,
                                                          const Pose2& camera_mount,
                                                          const Pose2& lidar_mount,
                                                          const StereoObjectOptions& options);

struct ProjectedStereoFrame {
  TimeNs stamp = 0;
  std::vector<StereoPoint> objects;  // in the frame's order, the dropped ones left out
  std::vector<Drop> drops;
};

// Every object of `frame` (camera mount frame.mount) projected for a lidar at `lidar_mount`
// (vehicle frame). Pure.
ProjectedStereoFrame ProjectStereoFrame(const StereoFrame& frame, const Pose2& lidar_mount,
                                        const StereoObjectOptions& options);

}  // namespace lookout::stereo
