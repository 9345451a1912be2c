#pragma once

// The messages that flow between stages (docs/ARCHITECTURE.md has the data flow). Every one
// carries its timestamp; SI units; frames as docs/conventions.md says: the vehicle frame has
// its origin at the centre of the footprint, x forward, y left; a sensor frame is given by its
// mount pose in the vehicle frame.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout {

// One sweep of a 2D lidar, taken at `stamp` (the sweep is treated as instantaneous).
// Beam i points at angle_min_rad + i * angle_increment_rad in the sensor frame.
// Ranges follow REP 117: +infinity means no return within max_range_m (dropouts too);
// NaN is an erroneous reading that consumers must skip.
struct LidarScan {
  TimeNs stamp = 0;
  Pose2 mount;  // sensor frame in the vehicle frame
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double max_range_m = 0.0;
  std::vector<float> ranges_m;

  double BeamAngle(std::size_t i) const {
    return angle_min_rad + static_cast<double>(i) * angle_increment_rad;
  }
  // Ranges at or beyond this are "no return": many scanners report a beam that saw nothing as
  // their maximum range, so a hair under max_range_m counts too; no limit when it is unset.
  double NoReturnRangeM() const { return max_range_m > 0.0 ? max_range_m * 0.999 : 1e300; }
};

// An object reported by the stereo camera, in the camera frame (x forward along the optical
// axis projected on the ground plane, y left). Seed 004 section V: an oriented cuboid with
// class, speed and variances; Lookout works in the laser plane, so the cuboid is its footprint.
struct StereoObject {
  std::uint32_t id = 0;              // the camera's own track id, stable while it tracks
  ObjectClass object_class = ObjectClass::kUnknown;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;              // heading of the box's length axis
  double length_m = 0.0;
  double width_m = 0.0;
  double speed_longitudinal_mps = 0.0;  // along the camera's x axis
  double speed_lateral_mps = 0.0;       // along the camera's y axis
  Eigen::Matrix2d center_covariance = Eigen::Matrix2d::Identity();  // m^2
  double yaw_variance = 0.0;            // rad^2
  double speed_variance = 0.0;          // (m/s)^2, each component
  std::uint32_t history = 0;  // frames this id has been tracked, this one included
};

struct StereoFrame {
  TimeNs stamp = 0;
  Pose2 mount;  // camera frame in the vehicle frame
  std::vector<StereoObject> objects;
};

// An object found in one lidar scan (seed 004 section IV.D): by the extended grid's rigid
// clusters or by the lidar chain's scan segmentation. Positions are in the vehicle frame at
// the scan's stamp; velocities are over the ground (the odometry frame's motion removed) but
// expressed in vehicle-frame axes, so that fusion and tracking need only the frame's ego pose.
struct LidarObject {
  std::uint32_t id = 0;  // unique within its frame only
  // The middle of the front line segment: what the laser sees best (seed 004 IV.D), the
  // object's point for fusion.
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d point_covariance = Eigen::Matrix2d::Identity();  // m^2
  Eigen::Vector2d front_start_m = Eigen::Vector2d::Zero();  // the front segment's ends
  Eigen::Vector2d front_end_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d centroid_m = Eigen::Vector2d::Zero();
  double range_m = 0.0;      // of the centroid, from the lidar's origin
  double bearing_rad = 0.0;  // of the centroid, in the lidar frame
  // Extent: the smallest rectangle about the object's points, its length along yaw_rad.
  double yaw_rad = 0.0;
  double length_m = 0.0;
  double width_m = 0.0;
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Identity();  // (m/s)^2
  // Probability of each class, indexed by ObjectClass (kAllObjectClasses order); sums to 1.
  std::array<double, kAllObjectClasses.size()> class_pmf{};
  std::uint32_t cell_count = 0;   // grid cells in the cluster (0 from scan segmentation)
  std::uint32_t point_count = 0;  // scan points on the object
  bool dynamic = false;           // moving over the ground
  // What the segmentation moved the front segment and the point by, taking the returns for a
  // round body's arc (towards the lidar, to the body's nearest point); zero otherwise. A box's
  // end seen head on, with a return on each side just behind its corners, looks the same to
  // the scan: the fusion undoes the move where the camera's box is no circle.
  Eigen::Vector2d round_body_shift_m = Eigen::Vector2d::Zero();
  // How far the side may run on, unseen, past front_start_m and past front_end_m: a beam
  // spacing where the scan sees the end free, up to a shadow's far edge where something nearer
  // hides it (the segmentation's HiddenExtent). Zero when the source does not say (the grid's).
  double hidden_start_m = 0.0;
  double hidden_end_m = 0.0;
  // The fields above that say where the front is, for a second reading of the same returns.
  struct FrontReading {
    Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
    Eigen::Matrix2d point_covariance = Eigen::Matrix2d::Identity();
    Eigen::Vector2d front_start_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d front_end_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d round_body_shift_m = Eigen::Vector2d::Zero();
    double hidden_start_m = 0.0;
    double hidden_end_m = 0.0;
  };
  // A small L (both sides shorter than a box's) whose returns a circle fits within the range
  // noise: the scan cannot tell a small box's corner from a round body's arc seen in part (a
  // walker half hidden shows an arc whose furthest return from its chord is off its middle, so
  // the segmentation takes it for an L and one leg for the front). The whole cluster read as
  // an arc, as the segmentation reads one; the fields above hold the L. The fusion takes this
  // where the camera's box is a circle (fusion::ReadAsBody). Only where has_arc_reading: a flag,
  // not a std::optional, whose copies GCC 12's -Wmaybe-uninitialized misreads at -O3 in the
  // unity build (the Eigen members of its payload).
  bool has_arc_reading = false;
  FrontReading arc_reading;

  // The object with its front read as `reading` says.
  void SetFront(const FrontReading& reading) {
    point_m = reading.point_m;
    point_covariance = reading.point_covariance;
    front_start_m = reading.front_start_m;
    front_end_m = reading.front_end_m;
    round_body_shift_m = reading.round_body_shift_m;
    hidden_start_m = reading.hidden_start_m;
    hidden_end_m = reading.hidden_end_m;
  }
};

struct LidarObjectFrame {
  TimeNs stamp = 0;
  Pose2 mount;     // lidar frame in the vehicle frame
  Pose2 ego_pose;  // vehicle frame in the odometry frame at `stamp`
  std::vector<LidarObject> objects;
};

// Wheel odometry and yaw-rate sensor of the ego vehicle.
struct EgoOdometry {
  TimeNs stamp = 0;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
};

}  // namespace lookout
