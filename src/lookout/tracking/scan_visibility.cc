#include "lookout/tracking/scan_visibility.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "lookout/core/input_error.h"

namespace lookout::tracking {

void ScanVisibilityOptions::Validate(const std::string& source) const {
  if (const auto field = footprints.FirstInvalidField()) {
    throw InputError(source, 0, *field, "must be > 0");
  }
  if (!(std::isfinite(depth_margin_m) && depth_margin_m >= 0.0)) {
    throw InputError(source, 0, "depth_margin_m", "must be >= 0");
  }
  if (!(std::isfinite(detection_margin_m) && detection_margin_m >= 0.0)) {
    throw InputError(source, 0, "detection_margin_m", "must be >= 0");
  }
}

namespace {

struct HalfSizes {
  double width, length;
};

HalfSizes Sizes(const ScanVisibilityOptions& o, ObjectClass c) {
  const ClassFootprints& f = o.footprints;
  switch (c) {
    case ObjectClass::kPedestrian:
      return {f.pedestrian_radius_m, f.pedestrian_radius_m};
    case ObjectClass::kCyclist:
      return {0.5 * f.cyclist_width_m, 0.5 * f.cyclist_length_m};
    case ObjectClass::kCar:
    case ObjectClass::kTruck:
      return {0.5 * f.car_width_m, 0.5 * f.car_length_m};
    case ObjectClass::kPole:
    case ObjectClass::kUnknown:
      break;
  }
  return {f.pedestrian_radius_m, 0.5 * f.car_length_m};
}

}  // namespace

ScanVisibility::ScanVisibility(const LidarScan& scan, const Pose2& sensor_pose,
                               const ScanVisibilityOptions& options,
                               std::vector<Eigen::Vector2d> detections)
    : options_(options),
      world_to_sensor_(sensor_pose.Inverse()),
      angle_min_rad_(scan.angle_min_rad),
      angle_increment_rad_(scan.angle_increment_rad),
      max_range_m_(scan.max_range_m),
      no_return_m_(scan.NoReturnRangeM()),
      ranges_m_(scan.ranges_m),
      detections_(std::move(detections)) {
  options_.Validate();
}

ViewFraction ScanVisibility::View(const Eigen::Vector2d& position_m, ObjectClass c) const {
  constexpr ViewFraction kNothing{0.0, 0.0};
  // A scan without beams, or with a fan that does not turn the right way, sees nothing.
  if (ranges_m_.empty() || !(angle_increment_rad_ > 0.0)) return kNothing;
  const Eigen::Vector2d q = world_to_sensor_ * position_m;
  const double range = q.norm();
  const HalfSizes half = Sizes(options_, c);
  const double near = half.length + options_.detection_margin_m;
  for (const Eigen::Vector2d& d : detections_) {
    if ((d - position_m).squaredNorm() <= near * near) return {};
  }
  if (!std::isfinite(range)) return kNothing;
  if (max_range_m_ > 0.0 && range - half.length > max_range_m_) return kNothing;
  if (range <= half.width) return {};  // the object stands over the sensor
  const double bearing = std::atan2(q.y(), q.x());
  const double half_span = std::asin(half.width / range);
  const auto beam = [&](double angle) { return (angle - angle_min_rad_) / angle_increment_rad_; };
  auto first = static_cast<std::int64_t>(std::ceil(beam(bearing - half_span)));
  auto last = static_cast<std::int64_t>(std::floor(beam(bearing + half_span)));
  if (first > last) first = last = std::llround(beam(bearing));
  const auto count = static_cast<std::int64_t>(ranges_m_.size());
  const double nearest_face = range - half.length - options_.depth_margin_m;
  std::int64_t in_view = 0, seen = 0;
  for (std::int64_t i = std::max<std::int64_t>(first, 0); i <= std::min(last, count - 1); ++i) {
    ++in_view;
    const auto r = static_cast<double>(ranges_m_[static_cast<std::size_t>(i)]);
    if (r >= nearest_face || r >= no_return_m_) ++seen;  // false for NaN; +inf: no return
  }
  const auto beams = static_cast<double>(last - first + 1);
  return {static_cast<double>(in_view) / beams, static_cast<double>(seen) / beams};
}

}  // namespace lookout::tracking
