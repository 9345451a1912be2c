#include "lookout/app/tracking_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::size_t ArgMax(const std::array<double, kAllObjectClasses.size()>& values) {
  std::size_t best = 0;
  for (std::size_t c = 1; c < values.size(); ++c) {
    if (values[c] > values[best]) best = c;
  }
  return best;
}

// Half the object's extent behind its seen side, along the side's normal.
double DepthBehindSide(ObjectClass c, double side_length_m, const DetectionOptions& o) {
  const auto box = [&](double length, double width) {
    // The long side shows when the segment is nearer the length than the width.
    return side_length_m >= 0.5 * (length + width) ? 0.5 * width : 0.5 * length;
  };
  switch (c) {
    case ObjectClass::kPedestrian: return o.pedestrian_radius_m;
    case ObjectClass::kCyclist: return box(o.cyclist_length_m, o.cyclist_width_m);
    case ObjectClass::kCar: return box(o.car_length_m, o.car_width_m);
    case ObjectClass::kTruck: return box(o.truck_length_m, o.truck_width_m);
    case ObjectClass::kPole:
    case ObjectClass::kUnknown: return 0.0;
  }
  return 0.0;
}

}  // namespace

ObjectClass MostLikelyClass(const fusion::FusedObject& object) {
  return kAllObjectClasses[ArgMax(object.class_pmf)];
}

std::vector<ObjectClass> CameraClassHistory::Update(const fusion::FusedObjectFrame& frame) {
  std::vector<ObjectClass> out;
  out.reserve(frame.objects.size());
  for (const fusion::FusedObject& o : frame.objects) {
    if (!o.stereo_id) {
      out.push_back(MostLikelyClass(o));
      continue;
    }
    Evidence& e = evidence_[*o.stereo_id];
    if (ToSeconds(frame.stamp - e.last_seen) > forget_after_s_) e = Evidence{};
    for (std::size_t c = 0; c < e.log_sum.size(); ++c) {
      // A probability of 0 would veto a class forever; 1e-6 keeps it recoverable.
      e.log_sum[c] += std::log(std::max(o.class_pmf[c], 1e-6));
    }
    e.last_seen = frame.stamp;
    out.push_back(kAllObjectClasses[ArgMax(e.log_sum)]);
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
  positive(car_length_m, "car_length_m");
  positive(car_width_m, "car_width_m");
  positive(truck_length_m, "truck_length_m");
  positive(truck_width_m, "truck_width_m");
  positive(cyclist_length_m, "cyclist_length_m");
  positive(cyclist_width_m, "cyclist_width_m");
  positive(pedestrian_radius_m, "pedestrian_radius_m");
  if (!std::isfinite(centre_offset_sigma_m) || centre_offset_sigma_m < 0.0) {
    throw InputError(source, 0, "centre_offset_sigma_m", "must be >= 0");
  }
  positive(min_segment_m, "min_segment_m");
}

void TrackingStageOptions::Validate(const std::string& source) const {
  mht.Validate(source + ": mht");
  gnn.Validate(source + ": gnn");
  detections.Validate(source + ": detections");
}

std::vector<tracking::Detection> DetectionsFromFusedObjects(
    const fusion::FusedObjectFrame& frame, const DetectionOptions& options,
    const std::vector<ObjectClass>& classes) {
  std::vector<tracking::Detection> out;
  out.reserve(frame.objects.size());
  const Eigen::Matrix2d r = frame.ego_pose.Rotation();
  const Eigen::Vector2d lidar = frame.mount.translation;
  for (std::size_t i = 0; i < frame.objects.size(); ++i) {
    const fusion::FusedObject& o = frame.objects[i];
    const ObjectClass c = classes.size() == frame.objects.size() ? classes[i] : MostLikelyClass(o);
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
    const Eigen::Vector2d centre =
        n > 1e-9 ? Eigen::Vector2d(o.point_m + DepthBehindSide(c, side, options) * away / n)
                 : o.point_m;
    tracking::Detection d;
    d.position_m = frame.ego_pose * centre;
    d.covariance = r * o.point_covariance * r.transpose() +
                   options.centre_offset_sigma_m * options.centre_offset_sigma_m *
                       Eigen::Matrix2d::Identity();
    d.object_class = c;
    d.sensors = o.sensor_count;
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

void TrackingStage::Step(const fusion::FusedObjectFrame& frame) {
  detections_ = DetectionsFromFusedObjects(frame, options_.detections, classes_.Update(frame));
  const Clock::time_point start = Clock::now();
  const bool accepted = tracker_->Step(frame.stamp, detections_);
  step_ms_.push_back(MsSince(start));
  if (baseline_) {
    const Clock::time_point baseline_start = Clock::now();
    baseline_->Step(frame.stamp, detections_);
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
  tracks_ = tracker_->ConfirmedTracks();
  if (baseline_) baseline_tracks_ = baseline_->ConfirmedTracks();
}

}  // namespace lookout::app
