#pragma once

// What every multi-target tracker gives the pipeline (the GNN baseline of gnn_tracker.h and the
// MHT alike): detections in, one scan at a time, confirmed tracks out. The pipeline, the
// metrics and the risk stage see trackers only through this interface, so that every table can
// put the MHT beside the baseline on the same input.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/time.h"
#include "lookout/tracking/kalman.h"

namespace lookout::tracking {

// What the camera says about a detection: whether the object is a road user at all, where the
// lidar alone may report grid ghosts (docs/tracking.md, track management).
enum class CameraEvidence {
  kNone,    // outside the camera's view, or no camera frame this scan: no evidence
  kSeen,    // the camera reported it (fused with it, or a camera object)
  kUnseen,  // inside the camera's field of view and depth, and the camera reported nothing there
};

// One object to track, in a ground-fixed frame: a fused object, or one sensor's.
struct Detection {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m^2
  ObjectClass object_class = ObjectClass::kUnknown;
  int sensors = 1;  // how many sensors saw it (2: lidar and stereo)
  CameraEvidence camera = CameraEvidence::kNone;
};

enum class TrackStatus { kTentative, kConfirmed };

// A track's state at one scan: what Track::previous links to.
struct TrackSnapshot {
  TimeNs stamp = 0;
  Gaussian state;  // (x, y, vx, vy)
};

struct Track {
  std::uint32_t id = 0;
  TrackStatus status = TrackStatus::kTentative;
  ObjectClass object_class = ObjectClass::kUnknown;
  Gaussian state;  // (x, y, vx, vy)
  TimeNs stamp = 0;
  int updates = 0;       // detections associated so far
  int misses = 0;        // consecutive scans without one
  bool coasting = false; // the last scan brought no detection
  // The log odds that the track is a road user rather than a ghost of the lidar's object
  // source, from the camera's evidence on its detections (track_management.h); 0 without any.
  double existence_log_odds = 0.0;
  // The filter's mode probabilities (the MHT's IMM: CV, CA, left turn, right turn); empty for
  // a single-model filter.
  Eigen::VectorXd mode_probabilities;
  // The same track after the scan before (seed 004 VII.D: "a reference to its instance in the
  // previous frame"), by value so that a track is a plain value; empty for a new track.
  std::optional<TrackSnapshot> previous;

  Eigen::Vector2d Position() const { return state.mean.head<2>(); }
  Eigen::Vector2d Velocity() const { return state.mean.segment<2>(2); }
  // Orientation of the pose: the direction of motion, rad counter-clockwise from x (east).
  double HeadingRad() const { return std::atan2(state.mean(3), state.mean(2)); }
};

// Whether a detection can be used: finite, with a symmetric positive definite covariance.
bool DetectionUsable(const Detection& detection);

// Whether a detection of class `detection` may join a track of class `track`.
bool ClassesCompatible(ObjectClass track, ObjectClass detection);

class Tracker {
 public:
  virtual ~Tracker() = default;

  // One scan at `stamp`, detections in a ground-fixed frame. A stamp not after the previous
  // scan's is refused: nothing changes and the call returns false (the caller logs it).
  // Detections with a non-finite field or a covariance that is not symmetric positive definite
  // are dropped and counted.
  virtual bool Step(TimeNs stamp, const std::vector<Detection>& detections) = 0;

  // The confirmed tracks after the last scan, in increasing id order.
  virtual std::vector<Track> ConfirmedTracks() const = 0;
  virtual std::int64_t dropped_detections() const = 0;
  virtual std::int64_t refused_scans() const = 0;
};

}  // namespace lookout::tracking
