#include "lookout/stereo/oriented_box.h"

#include <cmath>

#include "lookout/core/pose2.h"

namespace lookout::stereo {

using Eigen::Vector2d;

std::array<Vector2d, 4> OrientedBox::Corners() const {
  const Pose2 pose(center_m, yaw_rad);
  const double hl = 0.5 * length_m;
  const double hw = 0.5 * width_m;
  return {pose * Vector2d(-hl, -hw), pose * Vector2d(hl, -hw), pose * Vector2d(hl, hw),
          pose * Vector2d(-hl, hw)};
}

bool OrientedBox::Contains(const Vector2d& point_m) const {
  const Vector2d u = Pose2(center_m, yaw_rad).Inverse() * point_m;
  return std::abs(u.x()) <= 0.5 * length_m && std::abs(u.y()) <= 0.5 * width_m;
}

std::optional<FrontSegment> FrontSegmentFacing(const OrientedBox& box,
                                               const Vector2d& viewpoint_m) {
  if (box.Contains(viewpoint_m)) return std::nullopt;
  const Pose2 pose(box.center_m, box.yaw_rad);
  const Vector2d u = pose.Inverse() * viewpoint_m;  // the viewpoint in box axes
  const double hl = 0.5 * box.length_m;
  const double hw = 0.5 * box.width_m;
  // The ray from the centre towards u leaves through an end (x = +-hl) when |u_x| / hl >=
  // |u_y| / hw; multiplied out so that a zero length or width needs no division.
  Vector2d start, end;  // box axes, counter-clockwise
  if (std::abs(u.x()) * hw >= std::abs(u.y()) * hl) {
    const double s = u.x() >= 0.0 ? 1.0 : -1.0;
    start = Vector2d(s * hl, -s * hw);
    end = Vector2d(s * hl, s * hw);
  } else {
    const double s = u.y() >= 0.0 ? 1.0 : -1.0;
    start = Vector2d(s * hl, s * hw);
    end = Vector2d(-s * hl, s * hw);
  }
  const Vector2d middle = 0.5 * (start + end);
  FrontSegment front;
  front.start_m = pose * start;
  front.end_m = pose * end;
  front.midpoint_m = pose * middle;
  // d/dyaw of R(yaw) m = R(yaw) (-m_y, m_x).
  front.midpoint_yaw_derivative = pose.Rotation() * Vector2d(-middle.y(), middle.x());
  return front;
}

}  // namespace lookout::stereo
