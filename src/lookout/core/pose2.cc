#include "lookout/core/pose2.h"

#include <cmath>

namespace lookout {

Eigen::Matrix2d Pose2::Rotation() const {
  const double c = std::cos(yaw);
  const double s = std::sin(yaw);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& p) const {
  return Rotation() * p + translation;
}

Pose2 Pose2::operator*(const Pose2& other) const {
  return Pose2(Rotation() * other.translation + translation, WrapAngle(yaw + other.yaw));
}

Pose2 Pose2::Inverse() const {
  const Eigen::Matrix2d rt = Rotation().transpose();
  return Pose2(-(rt * translation), WrapAngle(-yaw));
}

double WrapAngle(double angle_rad) {
  double a = std::fmod(angle_rad + kPi, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace lookout
