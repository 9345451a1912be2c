#include "lookout/app/tracking_stage.h"

#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "lookout/app/wall_clock.h"
#include "lookout/core/chi_square.h"
#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

std::size_t ArgMax(const std::array<double, kAllObjectClasses.size()>& values) {
  std::size_t best = 0;
  for (std::size_t c = 1; c < values.size(); ++c) {
    if (values[c] > values[best]) best = c;
  }
  return best;
}

// Where an object's centre lies behind its seen side, along the side's normal: a depth and its
// variance. A known class: half its box's extent there (the long side shows when the segment is
// nearer the length than the width), its spread in centre_offset_sigma_m. An object of unknown
// class (a lidar-only segment) may be anything from a walker, whose centre is on the side, to a
// car, whose centre lies half its box behind: uniform between the two, so mean h / 2 and
// variance h^2 / 12 for the car's depth h. Before, such an object's centre was its seen side:
// a car seen head-on was tracked 2.25 m ahead of its centre, and the camera's "car" then fell
// outside that track's gate and started a second track (left-turn-across-path). Unless its
// side is walker-sized (DetectionOptions::walker_side_max_m): then a walker's radius, with
// walker_depth_sigma_m. Half a car's depth put a walker's track 1.1 m behind the walker where
// the camera did not see it (the crowd's false tracks, the leg-tracker bag's people beyond the
// benchmark's 0.75 m match).
struct CentreDepth {
  double depth_m = 0.0;
  double variance_m2 = 0.0;
};

// `along_motion`: whether the seen side runs along the object's motion (its long side), when
// its velocity says so (DetectionOptions::heading_min_speed_mps); nullopt: the side's length
// decides, and a box's depth takes the variance of the other side's depth being as likely.
// Why the variance: intersafe-fig9's second car showed its side 1 m long past the corner block
// at its first scan, too short for a long side: its track was born 2.25 m behind the side, 1.35 m
// off, with no depth variance to say so, and took five scans to come to the car.
CentreDepth DepthBehindSide(ObjectClass c, double side_length_m, std::optional<bool> along_motion,
                            const DetectionOptions& o) {
  const auto box = [&](double length, double width) {
    const bool long_side = along_motion.value_or(side_length_m >= 0.5 * (length + width));
    return long_side ? 0.5 * width : 0.5 * length;
  };
  switch (c) {
    case ObjectClass::kPedestrian:
      return {o.footprints.pedestrian_radius_m, 0.0};
    case ObjectClass::kCyclist:
    case ObjectClass::kCar:
    case ObjectClass::kTruck: {
      // Where the motion does not tell which side is seen, the length's verdict is as likely
      // wrong as right (a long side seen in part reads as an end): the depth is the two
      // candidates' mixture, its second moment about the one chosen ((L - W) / 2)^2 / 2.
      const ClassFootprints::Box b = o.footprints.BoxOf(c);
      const double half_gap = 0.5 * (b.length_m - b.width_m);
      return {box(b.length_m, b.width_m), along_motion ? 0.0 : 0.5 * half_gap * half_gap};
    }
    case ObjectClass::kPole: return {};
    case ObjectClass::kUnknown: {  // a car's, at an unknown depth behind the side
      const ClassFootprints::Box b = o.footprints.BoxOf(ObjectClass::kCar);
      if (side_length_m < o.walker_side_max_m) {
        return {o.footprints.pedestrian_radius_m, o.walker_depth_sigma_m * o.walker_depth_sigma_m};
      }
      const double h = box(b.length_m, b.width_m);
      return {0.5 * h, h * h / 12.0};
    }
  }
  return {};
}

// Whether `segment` runs along the motion of `o` (within 45 degrees of its velocity), when the
// velocity is fast and certain enough to tell.
std::optional<bool> AlongMotion(const fusion::FusedObject& o, const Eigen::Vector2d& segment,
                                const DetectionOptions& options) {
  const Eigen::Vector2d& v = o.velocity_mps;
  const double side = segment.norm();
  if (!(side >= options.min_segment_m) || !v.allFinite() ||
      !(v.norm() >= options.heading_min_speed_mps)) {
    return std::nullopt;
  }
  const Eigen::Matrix2d& pv = o.velocity_covariance;
  if (!pv.allFinite() || !(pv.determinant() > 0.0) ||
      v.dot(pv.inverse() * v) <= ChiSquareQuantile(options.moving_probability, 2.0)) {
    return std::nullopt;
  }
  return std::abs(segment.dot(v)) >= std::cos(kPi / 4.0) * side * v.norm();
}

}  // namespace

ObjectClass MostLikelyClass(const fusion::FusedObject& object) {
  return kAllObjectClasses[ArgMax(object.class_pmf)];
}

std::vector<CameraHistory> CameraTrackHistory::Update(const fusion::FusedObjectFrame& frame) {
  std::vector<CameraHistory> out;
  out.reserve(frame.objects.size());
  for (const fusion::FusedObject& o : frame.objects) {
    if (!o.stereo_id) {
      out.push_back({MostLikelyClass(o), 0});
      continue;
    }
    Evidence& e = evidence_[*o.stereo_id];
    if (ToSeconds(frame.stamp - e.last_seen) > forget_after_s_) e = Evidence{};
    for (std::size_t c = 0; c < e.log_sum.size(); ++c) {
      // A probability of 0 would veto a class forever; 1e-6 keeps it recoverable.
      e.log_sum[c] += std::log(std::max(o.class_pmf[c], 1e-6));
    }
    e.last_seen = frame.stamp;
    ++e.frames;
    out.push_back({kAllObjectClasses[ArgMax(e.log_sum)], e.frames});
  }
  std::erase_if(evidence_, [&](const auto& entry) {
    return ToSeconds(frame.stamp - entry.second.last_seen) > forget_after_s_;
  });
  return out;
}

std::optional<TrackerKind> ParseTrackerKind(const std::string& name) {
  if (name == "mht") return TrackerKind::kMht;
  if (name == "gnn") return TrackerKind::kGnn;
  return std::nullopt;
}

const char* ToString(TrackerKind kind) {
  switch (kind) {
    case TrackerKind::kMht: return "mht";
    case TrackerKind::kGnn: return "gnn";
  }
  return "mht";
}

void DetectionOptions::Validate(const std::string& source) const {
  auto positive = [&](double v, const char* field) {
    if (!std::isfinite(v) || v <= 0.0) throw InputError(source, 0, field, "must be > 0");
  };
  if (const auto field = footprints.FirstInvalidField()) {
    throw InputError(source, 0, *field, "must be > 0");
  }
  if (!std::isfinite(centre_offset_sigma_m) || centre_offset_sigma_m < 0.0) {
    throw InputError(source, 0, "centre_offset_sigma_m", "must be >= 0");
  }
  if (!std::isfinite(centre_offset_sigma_two_m) || centre_offset_sigma_two_m < 0.0) {
    throw InputError(source, 0, "centre_offset_sigma_two_m", "must be >= 0");
  }
  positive(min_segment_m, "min_segment_m");
  positive(walker_side_max_m, "walker_side_max_m");
  positive(walker_depth_sigma_m, "walker_depth_sigma_m");
  positive(static_speed_mps, "static_speed_mps");
  positive(heading_min_speed_mps, "heading_min_speed_mps");
  if (!(moving_probability > 0.0 && moving_probability < 1.0)) {
    throw InputError(source, 0, "moving_probability", "must be in (0, 1)");
  }
  if (!std::isfinite(camera_fov_rad) || camera_fov_rad <= 0.0 || camera_fov_rad >= 2.0 * kPi) {
    throw InputError(source, 0, "camera_fov_rad", "must be in (0, 2 pi)");
  }
  positive(camera_max_depth_m, "camera_max_depth_m");
  if (!std::isfinite(camera_view_margin_rad) || camera_view_margin_rad < 0.0) {
    throw InputError(source, 0, "camera_view_margin_rad", "must be >= 0");
  }
  if (!std::isfinite(camera_view_margin_m) || camera_view_margin_m < 0.0) {
    throw InputError(source, 0, "camera_view_margin_m", "must be >= 0");
  }
  if (!(camera_gate_probability > 0.0 && camera_gate_probability < 1.0)) {
    throw InputError(source, 0, "camera_gate_probability", "must be in (0, 1)");
  }
  if (!std::isfinite(building_margin_m) || building_margin_m < 0.0) {
    throw InputError(source, 0, "building_margin_m", "must be >= 0");
  }
  if (!std::isfinite(camera_occluder_margin_m) || camera_occluder_margin_m < 0.0) {
    throw InputError(source, 0, "camera_occluder_margin_m", "must be >= 0");
  }
  if (!std::isfinite(camera_occluder_margin_rad) || camera_occluder_margin_rad < 0.0) {
    throw InputError(source, 0, "camera_occluder_margin_rad", "must be >= 0");
  }
}

void TrackingStageOptions::Validate(const std::string& source) const {
  mht.Validate(source + ": mht");
  gnn.Validate(source + ": gnn");
  detections.Validate(source + ": detections");
  visibility.Validate(source + ": visibility");
}

namespace {

// Whether a camera object of `frame` lies within the gate of `o` (both at their seen sides).
bool CameraObjectNear(const fusion::FusedObjectFrame& frame, const fusion::FusedObject& o,
                      double gate) {
  for (const fusion::FusedObject& c : frame.objects) {
    if (!c.stereo_id) continue;
    const Eigen::Vector2d d = c.point_m - o.point_m;
    const Eigen::Matrix2d s = c.point_covariance + o.point_covariance;
    if (!d.allFinite() || !s.allFinite() || s.determinant() <= 0.0) continue;
    if (d.dot(s.inverse() * d) <= gate) return true;
  }
  return false;
}

// Whether another object of `frame` that the lidar saw stands between the camera and `o`:
// nearer than `o` by more than camera_occluder_margin_m, its seen side spanning `o`'s bearing
// from the camera (widened by camera_occluder_margin_rad). The camera cannot be asked about
// what it cannot see.
bool HiddenFromCamera(const Pose2& camera_mount, const fusion::FusedObjectFrame& frame,
                      const fusion::FusedObject& o, const DetectionOptions& options) {
  const Pose2 to_camera = camera_mount.Inverse();
  const Eigen::Vector2d q = to_camera * o.point_m;
  const double range = q.norm();
  const double bearing = std::atan2(q.y(), q.x());
  for (const fusion::FusedObject& other : frame.objects) {
    if (&other == &o || !other.lidar_id) continue;
    const Eigen::Vector2d a = to_camera * other.front_start_m;
    const Eigen::Vector2d b = to_camera * other.front_end_m;
    if (std::max(a.norm(), b.norm()) > range - options.camera_occluder_margin_m) continue;
    const double ba = std::atan2(a.y(), a.x());
    const double bb = std::atan2(b.y(), b.x());
    const double w = options.camera_occluder_margin_rad;
    if (bearing >= std::min(ba, bb) - w && bearing <= std::max(ba, bb) + w) return true;
  }
  return false;
}

bool InCameraView(const Pose2& camera_mount, const Eigen::Vector2d& vehicle_point,
                  const DetectionOptions& o) {
  const Eigen::Vector2d p = camera_mount.Inverse() * vehicle_point;
  return p.x() > 0.0 && p.x() <= o.camera_max_depth_m - o.camera_view_margin_m &&
         std::abs(std::atan2(p.y(), p.x())) <= 0.5 * o.camera_fov_rad - o.camera_view_margin_rad;
}

}  // namespace

bool ShowsMotion(const tracking::Track& t, const DetectionOptions& options,
                 bool moved_when_detected) {
  if (t.coasting && t.misses == 0) return moved_when_detected;
  const Eigen::Vector2d v = t.Velocity();
  if (v.norm() < options.static_speed_mps) return false;
  const Eigen::Matrix2d pv = t.state.cov.block<2, 2>(2, 2);
  if (!pv.allFinite() || pv.determinant() <= 0.0) return false;
  return v.dot(pv.inverse() * v) > ChiSquareQuantile(options.moving_probability, 2.0);
}

bool IsRoadUser(const tracking::Track& t, bool shows_motion) {
  return t.existence_log_odds > 0.0 || shows_motion;
}

bool IsRoadUser(const tracking::Track& t, const DetectionOptions& options,
                bool moved_when_detected) {
  return IsRoadUser(t, ShowsMotion(t, options, moved_when_detected));
}

std::vector<tracking::Detection> DetectionsFromFusedObjects(
    const fusion::FusedObjectFrame& frame, const DetectionOptions& options,
    const std::vector<CameraHistory>& history, const std::optional<Pose2>& camera_mount,
    const BuildingOutlines& buildings, std::int64_t* in_buildings) {
  std::vector<tracking::Detection> out;
  out.reserve(frame.objects.size());
  const Eigen::Matrix2d r = frame.ego_pose.Rotation();
  const Eigen::Vector2d lidar = frame.mount.translation;
  const double camera_gate = ChiSquareQuantile(options.camera_gate_probability, 2.0);
  for (std::size_t i = 0; i < frame.objects.size(); ++i) {
    const fusion::FusedObject& o = frame.objects[i];
    const bool with_history = history.size() == frame.objects.size();
    const ObjectClass c = with_history ? history[i].object_class : MostLikelyClass(o);
    const int camera_frames = with_history ? history[i].frames : (o.stereo_id ? 1 : 0);
    if (c == ObjectClass::kPole) continue;
    const bool lidar_only = !o.stereo_id.has_value();
    if (lidar_only && !o.dynamic && !options.keep_static_lidar_objects) continue;
    // The side's outward normal: away from the lidar, across the segment.
    const Eigen::Vector2d segment = o.front_end_m - o.front_start_m;
    const double side = segment.norm();
    Eigen::Vector2d away = o.point_m - lidar;
    if (side >= options.min_segment_m && std::isfinite(side)) {
      Eigen::Vector2d normal(-segment.y(), segment.x());
      if (normal.dot(away) < 0.0) normal = -normal;
      away = normal;
    }
    const double n = away.norm();
    const Eigen::Vector2d normal = n > 1e-9 ? Eigen::Vector2d(away / n) : Eigen::Vector2d::Zero();
    const std::optional<bool> along = AlongMotion(o, segment, options);
    // The centre `at` behind the seen side, in the tracker's frame.
    const double offset_sigma =
        o.sensor_count == 2 ? options.centre_offset_sigma_two_m : options.centre_offset_sigma_m;
    const auto centre_at = [&](const CentreDepth& at) {
      const Eigen::Matrix2d in_vehicle =
          o.point_covariance + at.variance_m2 * normal * normal.transpose();
      return tracking::ClassCentre{
          frame.ego_pose * Eigen::Vector2d(o.point_m + at.depth_m * normal),
          r * in_vehicle * r.transpose() +
              offset_sigma * offset_sigma * Eigen::Matrix2d::Identity()};
    };
    const CentreDepth depth = DepthBehindSide(c, side, along, options);
    const Eigen::Vector2d centre = o.point_m + depth.depth_m * normal;  // vehicle frame
    const tracking::ClassCentre own = centre_at(depth);
    tracking::Detection d;
    d.position_m = own.position_m;
    d.covariance = own.covariance;
    if (lidar_only && DepthInsideBuildings(buildings, d.position_m) > options.building_margin_m) {
      if (in_buildings) ++*in_buildings;
      continue;
    }
    if (c == ObjectClass::kUnknown) {
      // Each box's centre, for a track that knows its class (tracking::MeasurementFor). Not a
      // walker's: measured, the walkers' tracks then took merged or split arcs a radius behind
      // their middle with no depth variance, and the crowd's false tracks rose 34 -> 93.
      for (const ObjectClass k : {ObjectClass::kCyclist, ObjectClass::kCar, ObjectClass::kTruck}) {
        d.class_centres[static_cast<std::size_t>(k)] =
            centre_at(DepthBehindSide(k, side, along, options));
      }
    }
    d.object_class = c;
    d.sensors = o.sensor_count;
    d.seen_point_m = frame.ego_pose * o.point_m;
    d.seen_point_covariance = r * o.point_covariance * r.transpose();
    if (o.stereo_id) {
      // The camera's velocity (fused with the lidar's where it had one), over the ground.
      d.velocity_mps = r * o.velocity_mps;
      d.velocity_covariance = r * o.velocity_covariance * r.transpose();
      if (camera_frames >= 2) d.camera = tracking::CameraEvidence::kSeen;
    } else if (camera_mount && InCameraView(*camera_mount, centre, options) &&
               !CameraObjectNear(frame, o, camera_gate) &&
               !HiddenFromCamera(*camera_mount, frame, o, options)) {
      d.camera = tracking::CameraEvidence::kUnseen;
    }
    out.push_back(d);
  }
  return out;
}

TrackingStage::TrackingStage(const TrackingStageOptions& options) : options_(options) {
  options_.Validate();
  switch (options_.tracker) {
    case TrackerKind::kMht: tracker_ = std::make_unique<tracking::MhtTracker>(options_.mht); break;
    case TrackerKind::kGnn: tracker_ = std::make_unique<tracking::GnnTracker>(options_.gnn); break;
  }
  if (options_.baseline && options_.tracker != TrackerKind::kGnn) {
    baseline_ = std::make_unique<tracking::GnnTracker>(options_.gnn);
  }
}

void TrackingStage::Warn(std::string message) {
  ++warning_count_;
  if (warnings_.size() < kMaxWarnings) warnings_.push_back(std::move(message));
}

void TrackingStage::Step(const fusion::FusedObjectFrame& frame,
                         const std::optional<Pose2>& camera_mount, const LidarScan* scan) {
  detections_ = DetectionsFromFusedObjects(frame, options_.detections,
                                           camera_history_.Update(frame), camera_mount,
                                           buildings_, &in_buildings_);
  const tracking::OpenView open_view;
  const tracking::SensorView* view = &open_view;
  std::optional<tracking::ScanVisibility> scan_view;
  if (scan && options_.scan_visibility) {
    std::vector<Eigen::Vector2d> seen;
    for (const tracking::Detection& d : detections_) seen.push_back(d.position_m);
    view = &scan_view.emplace(*scan, frame.ego_pose * scan->mount, options_.visibility,
                              std::move(seen));
  }
  const Clock::time_point start = Clock::now();
  const bool accepted = tracker_->Step(frame.stamp, detections_, *view);
  step_ms_.push_back(MsSince(start));
  if (baseline_) {
    const Clock::time_point baseline_start = Clock::now();
    baseline_->Step(frame.stamp, detections_, *view);
    baseline_step_ms_.push_back(MsSince(baseline_start));
  }
  if (!accepted) {
    Warn(fmt::format("tracking: frame at {:.3f} s refused: not after the previous one at {:.3f} s",
                     ToSeconds(frame.stamp), last_stamp_ ? ToSeconds(*last_stamp_) : 0.0));
    return;
  }
  if (tracker_->dropped_detections() > dropped_reported_) {
    Warn(fmt::format("tracking: frame at {:.3f} s: {} object(s) dropped (non-finite field or "
                     "covariance not positive definite)",
                     ToSeconds(frame.stamp), tracker_->dropped_detections() - dropped_reported_));
    dropped_reported_ = tracker_->dropped_detections();
  }
  last_stamp_ = frame.stamp;
  // Confirmed tracks come in increasing id order, so the ids that move stay sorted.
  const auto road_users = [&](std::vector<tracking::Track> tracks,
                              std::vector<std::uint32_t>& moving_ids) {
    std::vector<std::uint32_t> moving_now;
    std::erase_if(tracks, [&](const tracking::Track& t) {
      const bool moved = std::binary_search(moving_ids.begin(), moving_ids.end(), t.id);
      const bool shows_motion = ShowsMotion(t, options_.detections, moved);
      if (shows_motion) moving_now.push_back(t.id);
      return !IsRoadUser(t, shows_motion);
    });
    moving_ids = std::move(moving_now);
    return tracks;
  };
  tracks_ = road_users(tracker_->ConfirmedTracks(), moving_ids_);
  if (baseline_) {
    baseline_tracks_ = road_users(baseline_->ConfirmedTracks(), baseline_moving_ids_);
  }
}

}  // namespace lookout::app
