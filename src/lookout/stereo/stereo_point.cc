#include "lookout/stereo/stereo_point.h"

#include <cmath>
#include <optional>

namespace lookout::stereo {

using Eigen::Matrix2d;
using Eigen::Vector2d;

namespace {

// The standard normal cumulative distribution.
double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// What ExpectedFrontPoint and OtherSideProbability share: the box's frame seen from the
// viewpoint and the side test g = W |u_x| - L |u_y| (FrontSegmentFacing picks the end when
// g >= 0).
struct SideTest {
  SideTest(const OrientedBox& box, const Vector2d& viewpoint_m)
      : pose(box.center_m, box.yaw_rad),
        rotation(pose.Rotation()),
        u(pose.Inverse() * viewpoint_m),
        hl(0.5 * box.length_m),
        hw(0.5 * box.width_m),
        sx(u.x() >= 0.0 ? 1.0 : -1.0),
        sy(u.y() >= 0.0 ? 1.0 : -1.0),
        g(std::abs(u.x()) * hw - std::abs(u.y()) * hl) {}

  // q = Phi(-|g| / sigma_g), g linearised: its gradient in u, and u's in the centre (-R^T) and
  // the heading ((u_y, -u_x)).
  double OtherSideProbability(const Matrix2d& center_covariance, double yaw_variance) const {
    const Vector2d dg_du(sx * hw, -sy * hl);
    const Vector2d dg_dc = -rotation * dg_du;
    const double dg_dyaw = dg_du.dot(Vector2d(u.y(), -u.x()));
    const double variance_g =
        dg_dc.dot(center_covariance * dg_dc) + dg_dyaw * dg_dyaw * yaw_variance;
    if (variance_g > 0.0) return NormalCdf(-std::abs(g) / std::sqrt(variance_g));
    return g == 0.0 ? 0.5 : 0.0;
  }

  Pose2 pose;
  Matrix2d rotation;
  Vector2d u;  // the viewpoint in box axes
  double hl, hw, sx, sy, g;
};

}  // namespace

double OtherSideProbability(const OrientedBox& box, const Matrix2d& center_covariance,
                            double yaw_variance, const Vector2d& viewpoint_m) {
  if (box.Contains(viewpoint_m)) return 0.0;
  return SideTest(box, viewpoint_m).OtherSideProbability(center_covariance, yaw_variance);
}

std::optional<CartesianPoint> ExpectedFrontPoint(const OrientedBox& box,
                                                 const Matrix2d& center_covariance,
                                                 double yaw_variance, const Vector2d& viewpoint_m,
                                                 HeadingShare* share) {
  if (box.Contains(viewpoint_m)) return std::nullopt;
  const SideTest t(box, viewpoint_m);
  // The two candidate sides' middles in box axes: the end facing the viewpoint and the long
  // side facing it.
  const Vector2d end_middle(t.sx * t.hl, 0.0);
  const Vector2d side_middle(0.0, t.sy * t.hw);
  const Vector2d& chosen = t.g >= 0.0 ? end_middle : side_middle;
  const Vector2d& other = t.g >= 0.0 ? side_middle : end_middle;

  auto moments = [&](const Vector2d& middle_box, Vector2d& mean, Vector2d& dm_dyaw,
                     Matrix2d& covariance) {
    mean = t.pose * middle_box;
    dm_dyaw = t.rotation * Vector2d(-middle_box.y(), middle_box.x());
    covariance = center_covariance + yaw_variance * dm_dyaw * dm_dyaw.transpose();
  };
  Vector2d mean_a, mean_b, slope_a, slope_b;
  Matrix2d cov_a, cov_b;
  moments(chosen, mean_a, slope_a, cov_a);
  moments(other, mean_b, slope_b, cov_b);

  const double q = t.OtherSideProbability(center_covariance, yaw_variance);
  const Vector2d difference = mean_b - mean_a;
  CartesianPoint point;
  point.point_m = mean_a + q * difference;
  point.covariance = (1.0 - q) * cov_a + q * cov_b +
                     q * (1.0 - q) * difference * difference.transpose();
  if (share != nullptr) {
    *share = HeadingShare{yaw_variance, q, difference, (1.0 - q) * slope_a + q * slope_b};
  }
  return point;
}

std::variant<StereoPoint, DropReason> ProjectStereoObject(const StereoObject& object,
                                                          const Pose2& camera_mount,
                                                          const Pose2& lidar_mount,
                                                          const StereoObjectOptions& options) {
  if (const std::optional<DropReason> reason = CheckStereoObject(object)) return *reason;

  StereoPoint p;
  p.id = object.id;
  p.object_class = object.object_class;
  p.history = object.history;
  p.depth_m = object.center_m.x();
  p.yaw_variance = object.yaw_variance;
  p.footprint = OrientedBox{camera_mount * object.center_m,
                            WrapAngle(object.yaw_rad + camera_mount.yaw), object.length_m,
                            object.width_m};
  const std::optional<FrontSegment> front =
      FrontSegmentFacing(p.footprint, lidar_mount.translation);
  if (!front) return DropReason::kLidarOriginInside;
  p.front = *front;

  const Matrix2d rotation = camera_mount.Rotation();
  p.velocity_mps =
      rotation * Vector2d(object.speed_longitudinal_mps, object.speed_lateral_mps);
  // speed_variance I is the same in any axes.
  p.velocity_covariance = object.speed_variance * Matrix2d::Identity();

  const Matrix2d center_covariance_camera =
      options.covariance_source == CovarianceSource::kReported
          ? object.center_covariance
          : options.depth_model.PointCovariance(object.center_m);
  // ExpectedFrontPoint succeeds here: FrontSegmentFacing did, and they test the same box.
  const Matrix2d center_covariance = rotation * center_covariance_camera * rotation.transpose();
  p.point = *ExpectedFrontPoint(p.footprint, center_covariance, object.yaw_variance,
                                lidar_mount.translation, &p.heading_share);
  p.polar = ToRangeBearing(p.point, lidar_mount);
  return p;
}

ProjectedStereoFrame ProjectStereoFrame(const StereoFrame& frame, const Pose2& lidar_mount,
                                        const StereoObjectOptions& options) {
  ProjectedStereoFrame out;
  out.stamp = frame.stamp;
  out.objects.reserve(frame.objects.size());
  for (const StereoObject& object : frame.objects) {
    auto result = ProjectStereoObject(object, frame.mount, lidar_mount, options);
    if (auto* point = std::get_if<StereoPoint>(&result)) {
      out.objects.push_back(std::move(*point));
    } else {
      out.drops.push_back(Drop{object.id, std::get<DropReason>(result)});
    }
  }
  return out;
}

}  // namespace lookout::stereo
