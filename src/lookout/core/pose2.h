#pragma once

#include <Eigen/Core>

namespace lookout {

// A rigid transform of the plane: rotation by `yaw` (rad, counter-clockwise) then translation.
// As a pose of frame B in frame A, it maps B coordinates to A coordinates.
struct Pose2 {
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  double yaw = 0.0;

  Pose2() = default;
  Pose2(double x, double y, double yaw_rad) : translation(x, y), yaw(yaw_rad) {}
  Pose2(const Eigen::Vector2d& t, double yaw_rad) : translation(t), yaw(yaw_rad) {}

  double x() const { return translation.x(); }
  double y() const { return translation.y(); }

  Eigen::Matrix2d Rotation() const;
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const;  // apply to a point
  Pose2 operator*(const Pose2& other) const;                   // compose: this after other
  Pose2 Inverse() const;
};

// Wraps an angle to [-pi, pi).
double WrapAngle(double angle_rad);

inline constexpr double kPi = 3.14159265358979323846;
inline double DegToRad(double deg) { return deg * kPi / 180.0; }
inline double RadToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace lookout
