#include "lookout/io/ros_conversions.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace lookout::io {
namespace {

Eigen::Vector3d ToVector3(const RosValue& v) {
  return {v["x"].AsDouble(), v["y"].AsDouble(), v["z"].AsDouble()};
}

Eigen::Quaterniond ToQuaternion(const RosValue& v) {
  Eigen::Quaterniond q(v["w"].AsDouble(), v["x"].AsDouble(), v["y"].AsDouble(),
                       v["z"].AsDouble());
  const double norm = q.norm();
  if (!(norm > 0.5 && norm < 1.5)) {
    // Far from unit length: not a rotation (all zeros is a common "unset").
    throw RosMessageError("", fmt::format("quaternion of norm {} is not a rotation", norm));
  }
  q.normalize();
  return q;
}

// Runs `f`; a RosMessageError from it gets `field` put in front of its path.
template <typename F>
auto Within(std::string_view field, F&& f) {
  try {
    return f();
  } catch (const RosMessageError& e) {
    throw e.Within(field);
  }
}

}  // namespace

TimeNs ToTimeNs(RosTime t) {
  return static_cast<TimeNs>(t.sec) * kNanosPerSecond + static_cast<TimeNs>(t.nsec);
}

double PlanarYaw(const Eigen::Quaterniond& q) {
  // The z-y'-x'' (yaw-pitch-roll) decomposition's yaw.
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                    1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

RosLaserScan ToLaserScan(const RosValue& message) {
  RosLaserScan out;
  const RosValue& header = message["header"];
  out.scan.stamp = Within("header", [&] { return ToTimeNs(header["stamp"].AsTime()); });
  out.frame_id = Within("header", [&] { return header["frame_id"].AsString(); });
  out.scan.angle_min_rad = message["angle_min"].AsDouble();
  out.scan.angle_increment_rad = message["angle_increment"].AsDouble();
  out.scan.max_range_m = message["range_max"].AsDouble();
  out.range_min_m = message["range_min"].AsDouble();
  out.scan_time_s = message["scan_time"].AsDouble();
  const std::vector<double>& ranges =
      *Within("ranges", [&] { return &message["ranges"].AsDoubles(); });
  out.scan.ranges_m.reserve(ranges.size());
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (const double r : ranges) {
    // REP 117: +inf is "no return", kept; everything outside [range_min, range_max] else is
    // to be discarded, which LidarScan spells NaN.
    if (std::isinf(r) && r > 0.0) {
      out.scan.ranges_m.push_back(std::numeric_limits<float>::infinity());
    } else if (std::isnan(r) || r < out.range_min_m || r > out.scan.max_range_m) {
      out.scan.ranges_m.push_back(kNaN);
      ++out.invalid_beams;
    } else {
      out.scan.ranges_m.push_back(static_cast<float>(r));
    }
  }
  return out;
}

Pose2 RosOdometry::Planar() const {
  return Pose2(position_m.x(), position_m.y(), PlanarYaw(orientation));
}

EgoOdometry RosOdometry::Ego() const {
  return EgoOdometry{stamp, linear_velocity_mps.x(), angular_velocity_radps.z()};
}

RosOdometry ToOdometry(const RosValue& message) {
  RosOdometry out;
  const RosValue& header = message["header"];
  out.stamp = Within("header", [&] { return ToTimeNs(header["stamp"].AsTime()); });
  out.frame_id = Within("header", [&] { return header["frame_id"].AsString(); });
  out.child_frame_id = message["child_frame_id"].AsString();
  Within("pose.pose", [&] {
    const RosValue& pose = message["pose"]["pose"];
    out.position_m = Within("position", [&] { return ToVector3(pose["position"]); });
    out.orientation = Within("orientation", [&] { return ToQuaternion(pose["orientation"]); });
    return 0;
  });
  Within("twist.twist", [&] {
    const RosValue& twist = message["twist"]["twist"];
    out.linear_velocity_mps = Within("linear", [&] { return ToVector3(twist["linear"]); });
    out.angular_velocity_radps = Within("angular", [&] { return ToVector3(twist["angular"]); });
    return 0;
  });
  return out;
}

Pose2 RosTransform::Planar() const {
  return Pose2(translation_m.x(), translation_m.y(), PlanarYaw(rotation));
}

std::vector<RosTransform> ToTransforms(const RosValue& message) {
  const std::vector<RosValue>& transforms = message["transforms"].AsArray();
  std::vector<RosTransform> out;
  out.reserve(transforms.size());
  for (std::size_t i = 0; i < transforms.size(); ++i) {
    out.push_back(Within(fmt::format("transforms[{}]", i), [&] {
      const RosValue& t = transforms[i];
      RosTransform transform;
      transform.stamp = ToTimeNs(t["header"]["stamp"].AsTime());
      transform.parent_frame = t["header"]["frame_id"].AsString();
      transform.child_frame = t["child_frame_id"].AsString();
      transform.translation_m = ToVector3(t["transform"]["translation"]);
      transform.rotation = ToQuaternion(t["transform"]["rotation"]);
      return transform;
    }));
  }
  return out;
}

PersonTruth ToPersonTruth(const RosValue& message, TimeNs record_time) {
  PersonTruth out;
  out.stamp = record_time;
  const std::uint64_t id = message["id"].AsUint();
  if (id > std::numeric_limits<std::uint32_t>::max()) {
    throw RosMessageError("id", fmt::format("{} does not fit 32 bits", id));
  }
  out.id = static_cast<std::uint32_t>(id);
  const RosValue& position = message["pose"]["position"];
  out.x_m = position["x"].AsDouble();
  out.y_m = position["y"].AsDouble();
  if (!std::isfinite(out.x_m) || !std::isfinite(out.y_m)) {
    throw RosMessageError("pose.position", "is not finite");
  }
  return out;
}

}  // namespace lookout::io
