#pragma once

// Typed conversions of decoded ROS1 messages (ros_message.h) into Lookout's messages. Each
// reads the fields it needs by name from the message as the bag defines it, so a definition
// that lacks a field, or gives it another type, throws RosMessageError naming the field.
//
// Stamps here are absolute: nanoseconds since the Unix epoch (ROS time), as TimeNs. The bag
// log (ros_bag_log.h) moves them to the log's own time base.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/io/ros_message.h"

namespace lookout::io {

TimeNs ToTimeNs(RosTime t);

// sensor_msgs/LaserScan. `scan.stamp` is the header's stamp (the first beam's time); the
// mount is left at identity (the laser's pose on the robot is a transform in /tf, by frame_id).
struct RosLaserScan {
  LidarScan scan;
  // When the bag recorded it (the record's time, not the header's): what orders the scans
  // against messages stamped by the recorder, such as leg_tracker's annotations. 0 until the
  // bag log sets it.
  TimeNs record_stamp = 0;
  std::string frame_id;
  double range_min_m = 0.0;
  double scan_time_s = 0.0;
  // Beams that REP 117 says to discard, made NaN: finite ranges below range_min or above
  // range_max (0 included, as legacy drivers write for "no reading"), -inf ("too close": no
  // usable point), and NaN as given. +inf stays +inf: no return within range.
  std::uint32_t invalid_beams = 0;
};
RosLaserScan ToLaserScan(const RosValue& message);

// nav_msgs/Odometry: the pose of child_frame_id in frame_id, and the twist in child_frame_id.
struct RosOdometry {
  TimeNs stamp = 0;
  std::string frame_id;
  std::string child_frame_id;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();

  Pose2 Planar() const;  // x, y and the yaw about z
  EgoOdometry Ego() const;  // forward speed (linear x) and yaw rate (angular z)
};
RosOdometry ToOdometry(const RosValue& message);

// One geometry_msgs/TransformStamped of a tf2_msgs/TFMessage (or tf/tfMessage): the pose of
// child_frame in parent_frame.
struct RosTransform {
  TimeNs stamp = 0;
  std::string parent_frame;
  std::string child_frame;
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();

  Pose2 Planar() const;
};
std::vector<RosTransform> ToTransforms(const RosValue& message);

// A hand-annotated person of leg_tracker's benchmark bags (leg_tracker/Person: a pose and an
// id, no header, so the stamp is the bag record's time).
struct PersonTruth {
  TimeNs stamp = 0;
  std::uint32_t id = 0;
  double x_m = 0.0;
  double y_m = 0.0;
};
PersonTruth ToPersonTruth(const RosValue& message, TimeNs record_time);

// The yaw about z of a rotation (its heading in the plane).
double PlanarYaw(const Eigen::Quaterniond& rotation);

}  // namespace lookout::io
