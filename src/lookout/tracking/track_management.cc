#include "lookout/tracking/track_management.h"

#include <algorithm>
#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

int UpdatesToConfirm(const TrackManagementOptions& o, const Detection& d) {
  return d.sensors >= 2 ? o.confirm_updates_two_sensors : o.confirm_updates_one_sensor;
}

}  // namespace

void TrackManagementOptions::Validate(const std::string& source) const {
  auto require = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, field, problem);
  };
  require(confirm_updates_one_sensor >= 1, "confirm_updates_one_sensor", "must be >= 1");
  require(confirm_updates_two_sensors >= 1, "confirm_updates_two_sensors", "must be >= 1");
  require(max_misses_pedestrian >= 0, "max_misses_pedestrian", "must be >= 0");
  require(max_misses_cyclist >= 0, "max_misses_cyclist", "must be >= 0");
  require(max_misses_vehicle >= 0, "max_misses_vehicle", "must be >= 0");
  require(max_misses_unknown >= 0, "max_misses_unknown", "must be >= 0");
  require(max_misses_tentative >= 0, "max_misses_tentative", "must be >= 0");
  require(std::isfinite(max_hidden_distance_m) && max_hidden_distance_m >= 0.0,
          "max_hidden_distance_m", "must be >= 0");
  require(std::isfinite(max_hidden_s) && max_hidden_s >= 0.0, "max_hidden_s", "must be >= 0");
  require(min_visible_fraction > 0.0 && min_visible_fraction <= 1.0, "min_visible_fraction",
          "must be in (0, 1]");
  require(camera_detection_probability > 0.0 && camera_detection_probability < 1.0,
          "camera_detection_probability", "must be in (0, 1)");
  require(camera_ghost_probability > 0.0 && camera_ghost_probability < 1.0,
          "camera_ghost_probability", "must be in (0, 1)");
  require(min_existence_probability >= 0.0 && min_existence_probability < 0.5,
          "min_existence_probability", "must be in [0, 0.5)");
  require(std::isfinite(existence_log_odds_limit) && existence_log_odds_limit > 0.0,
          "existence_log_odds_limit", "must be > 0");
  require(seen_velocity_agreement_probability >= 0.0 && seen_velocity_agreement_probability < 1.0,
          "seen_velocity_agreement_probability", "must be in [0, 1)");
  require(std::isfinite(initial_speed_sigma_pedestrian_mps) &&
              initial_speed_sigma_pedestrian_mps > 0.0,
          "initial_speed_sigma_pedestrian_mps", "must be > 0");
}

double InitialSpeedSigma(const TrackManagementOptions& o, ObjectClass c, double others_mps) {
  return c == ObjectClass::kPedestrian ? o.initial_speed_sigma_pedestrian_mps : others_mps;
}

double ExistenceAfter(const TrackManagementOptions& o, double log_odds, CameraEvidence e) {
  const double pd = o.camera_detection_probability, pg = o.camera_ghost_probability;
  switch (e) {
    case CameraEvidence::kNone: return log_odds;
    case CameraEvidence::kSeen: log_odds += std::log(pd / pg); break;
    case CameraEvidence::kUnseen: log_odds += std::log((1.0 - pd) / (1.0 - pg)); break;
  }
  return std::clamp(log_odds, -o.existence_log_odds_limit, o.existence_log_odds_limit);
}

bool Expired(const TrackManagementOptions& o, const Track& t) {
  if (t.misses > MaxMisses(o, t) || t.lost) return true;
  const double p = o.min_existence_probability;
  return p > 0.0 && t.existence_log_odds < std::log(p / (1.0 - p));
}

int MaxMisses(const TrackManagementOptions& o, const Track& t) {
  if (t.status == TrackStatus::kTentative) return o.max_misses_tentative;
  switch (t.object_class) {
    case ObjectClass::kPedestrian: return o.max_misses_pedestrian;
    case ObjectClass::kCyclist: return o.max_misses_cyclist;
    case ObjectClass::kCar:
    case ObjectClass::kTruck: return o.max_misses_vehicle;
    case ObjectClass::kPole:
    case ObjectClass::kUnknown: return o.max_misses_unknown;
  }
  return o.max_misses_unknown;
}

Track BornTrack(const TrackManagementOptions& o, const Detection& d, TimeNs stamp) {
  Track t;
  t.object_class = d.object_class;
  t.stamp = stamp;
  t.last_detected = stamp;
  t.updates = 1;
  if (d.seen_point_m)
    t.early_seen_points.push_back({stamp, *d.seen_point_m, d.seen_point_covariance});
  t.existence_log_odds = ExistenceAfter(o, 0.0, d.camera);
  if (t.updates >= UpdatesToConfirm(o, d)) t.status = TrackStatus::kConfirmed;
  return t;
}

Track AfterDetection(const TrackManagementOptions& o, Track t, const Detection& d, TimeNs stamp) {
  ++t.updates;
  if (t.updates > 3) t.early_seen_points.clear();
  if (t.updates <= 3 && d.seen_point_m &&
      t.early_seen_points.size() + 1 == static_cast<std::size_t>(t.updates)) {
    t.early_seen_points.push_back({stamp, *d.seen_point_m, d.seen_point_covariance});
  }
  t.misses = 0;
  t.stamp = stamp;
  t.last_detected = stamp;
  t.coasting = false;
  t.existence_log_odds = ExistenceAfter(o, t.existence_log_odds, d.camera);
  if (t.object_class == ObjectClass::kUnknown) t.object_class = d.object_class;
  if (t.status == TrackStatus::kTentative && t.updates >= UpdatesToConfirm(o, d)) {
    t.status = TrackStatus::kConfirmed;
  }
  return t;
}

bool Hidden(const TrackManagementOptions& o, const ViewFraction& view) {
  return view.seen < o.min_visible_fraction && view.in_view >= o.min_visible_fraction;
}

Track AfterMiss(const TrackManagementOptions& o, Track t, const ViewFraction& view, TimeNs stamp) {
  t.stamp = stamp;
  t.coasting = true;
  if (t.status != TrackStatus::kConfirmed || !Hidden(o, view)) {
    ++t.misses;
    return t;
  }
  const double unseen_s = ToSeconds(stamp - t.last_detected);
  // A state without a velocity (the trackers' always have one) is bounded by time alone.
  const double speed = t.state.mean.size() >= 4 ? t.Velocity().norm() : 0.0;
  if (unseen_s > o.max_hidden_s || unseen_s * speed > o.max_hidden_distance_m) t.lost = true;
  return t;
}

}  // namespace lookout::tracking
