#pragma once

// The tracking baseline of the tracking issue: global nearest neighbour (one optimal
// assignment per scan) with a single constant-velocity Kalman filter per track, and the track
// management the MHT shares: tentative tracks from unassociated detections, confirmed after one
// update when both sensors saw the object and after three otherwise, coasting (prediction only)
// through misses, deleted after a number of consecutive misses that depends on the class.
//
// Gating: a detection may join a track only inside the chi-square gate of the innovation (2 dof)
// and when their classes are compatible (no pedestrian joins a car's track; unknown joins
// anything). Deterministic: ties and orders follow the input order and track ids.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/time.h"
#include "lookout/tracking/kalman.h"

namespace lookout::tracking {

// One object to track, in a ground-fixed frame: a fused object, or one sensor's.
struct Detection {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m^2
  ObjectClass object_class = ObjectClass::kUnknown;
  int sensors = 1;  // how many sensors saw it (2: lidar and stereo)
};

enum class TrackStatus { kTentative, kConfirmed };

struct Track {
  std::uint32_t id = 0;
  TrackStatus status = TrackStatus::kTentative;
  ObjectClass object_class = ObjectClass::kUnknown;
  Gaussian state;  // (x, y, vx, vy)
  TimeNs stamp = 0;
  int updates = 0;       // detections associated so far
  int misses = 0;        // consecutive scans without one
  bool coasting = false; // the last scan brought no detection

  Eigen::Vector2d Position() const { return state.mean.head<2>(); }
  Eigen::Vector2d Velocity() const { return state.mean.segment<2>(2); }
};

struct GnnOptions {
  double acceleration_psd = 2.0;        // CV process noise, m^2/s^3
  double gate_probability = 0.999;      // chi-square gate, 2 dof
  double initial_speed_sigma_mps = 5.0; // velocity prior of a new track
  int confirm_updates_one_sensor = 3;
  int confirm_updates_two_sensors = 1;
  // Consecutive misses before deletion: a pedestrian hidden behind a car may reappear after
  // a second or two; an unknown object that stops being seen was most likely clutter.
  int max_misses_pedestrian = 25;
  int max_misses_cyclist = 20;
  int max_misses_vehicle = 20;
  int max_misses_unknown = 5;
  int max_misses_tentative = 2;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "tracker options") const;
};

// Whether a detection of class `detection` may join a track of class `track`.
bool ClassesCompatible(ObjectClass track, ObjectClass detection);

class GnnTracker {
 public:
  explicit GnnTracker(const GnnOptions& options = {});

  // One scan at `stamp`. A stamp not after the previous scan's is refused: nothing changes and
  // the call returns false (the caller logs it). Detections with a non-finite field or a
  // covariance that is not symmetric positive definite are dropped and counted.
  bool Step(TimeNs stamp, const std::vector<Detection>& detections);

  const std::vector<Track>& tracks() const { return tracks_; }
  std::vector<Track> ConfirmedTracks() const;
  std::int64_t dropped_detections() const { return dropped_; }
  std::int64_t refused_scans() const { return refused_; }

 private:
  int MaxMisses(const Track& track) const;

  GnnOptions options_;
  std::vector<Track> tracks_;
  std::uint32_t next_id_ = 1;
  std::optional<TimeNs> last_stamp_;
  std::int64_t dropped_ = 0;
  std::int64_t refused_ = 0;
};

}  // namespace lookout::tracking
