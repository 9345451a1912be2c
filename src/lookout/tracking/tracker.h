#pragma once

// What every multi-target tracker gives the pipeline (the GNN baseline of gnn_tracker.h and the
// MHT alike): detections in, one scan at a time, confirmed tracks out. The pipeline, the
// metrics and the risk stage see trackers only through this interface, so that every table can
// put the MHT beside the baseline on the same input.

#include <Eigen/Core>
#include <array>
#include <boost/container/static_vector.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
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

// Where a detection puts an object's centre if the object is of a given class.
struct ClassCentre {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m^2
};

// One object to track, in a ground-fixed frame: a fused object, or one sensor's.
struct Detection {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m^2
  ObjectClass object_class = ObjectClass::kUnknown;
  int sensors = 1;  // how many sensors saw it (2: lidar and stereo)
  CameraEvidence camera = CameraEvidence::kNone;
  // A velocity measured with the object (the camera tracks what it sees), same frame; only a
  // new track's prior (BirthState) reads it.
  std::optional<Eigen::Vector2d> velocity_mps;
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Identity();  // (m/s)^2
  // The point the sensors saw (the front segment's middle), before the tracking stage put the
  // object's centre behind it; same frame. Its unknown depth is the same from scan to scan, so
  // scans' seen points measure the velocity without it (ThreePointVelocity).
  std::optional<Eigen::Vector2d> seen_point_m;
  Eigen::Matrix2d seen_point_covariance = Eigen::Matrix2d::Identity();  // m^2
  // For a detection of unknown class: where an object of class c would have its centre
  // (indexed by ObjectClass), where the tracking stage says; a track of class c measures that
  // (MeasurementFor).
  std::array<std::optional<ClassCentre>, kAllObjectClasses.size()> class_centres;
};

// The position a track of class `track_class` measures in `d`: d's centre for that class where
// d is of unknown class and holds a usable one, else d's own position and covariance.
// Why: an object the camera stops seeing is of unknown class, and the tracking stage puts its
// centre half a car's depth behind its seen side, with that depth's variance. A cyclist whose
// class the camera had given its track left the camera's view and its track followed that centre
// 0.8 m sideways; the offset, the same every scan, became a sideways velocity of 0.6 m/s that
// carried the track off its cyclist once a building hid it (intersafe-fig8). The track knows
// what the detection does not: which class's depth applies.
ClassCentre MeasurementFor(const Detection& d, ObjectClass track_class);

// A new track's state (x, y, vx, vy) from its first detection: the detection's position and
// covariance; the detection's measured velocity where it has one (finite, its covariance
// positive definite) that is surer than the prior, else zero with speed_sigma_mps per axis.
// Why: a track born of a camera object without it takes two or three updates to learn a
// velocity the camera already reports, and meanwhile the risk stage extrapolates a velocity
// that is two noisy points' difference (near-miss: a car crossing at 10 m/s read as (-2.3, 6.6)
// +- 4 m/s after its second update, a false warning at TTC 1.2 s).
Gaussian BirthState(const Detection& detection, double speed_sigma_mps);

// A detection's seen point with its stamp (Detection::seen_point_m), kept by a young track.
struct SeenPoint {
  TimeNs stamp = 0;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
};
// In place, not on the heap: a Track is copied with every track hypothesis, and a vector's
// allocation there cost the MHT step 10 % (docs/PERFORMANCE.md).
using EarlySeenPoints = boost::container::static_vector<SeenPoint, 3>;

// The velocity of a track's first three seen points, where the two steps agree: v12 and v23,
// each a difference over its interval, must differ by no more than the chi-square (2 dof)
// quantile of `agreement_probability` under the covariance of their difference (s2 is in
// both); then (s3 - s1) / (t3 - t1) with covariance (C1 + C3) / (t3 - t1)^2. nullopt otherwise
// (fewer than three points, stamps not increasing, or the steps disagree).
// Why: the tracking stage centres an object of unknown class half a car's depth behind its
// seen side, with that depth's variance (0.42 m^2) in the detection's covariance, and a Kalman
// filter takes it as fresh noise at every scan although it is the same at every scan: after
// three scans a car crossing at 8 m/s read 3.2 +- 3.9 m/s (straight-crossing-path), and its
// track waited two more scans for a velocity the output test calls moving. The seen points'
// differences measure the velocity of the part the sensors saw, the depth cancelled. Why three
// and the agreement: a track whose first detections are two different pieces of a body (or two
// bodies) reads a confident 12-24 m/s from two points; the two steps of such a track disagree.
std::optional<Gaussian> ThreePointVelocity(std::span<const SeenPoint> points,
                                           double agreement_probability);

// What a track's third detection makes of its velocity: `state` with the seen points' velocity
// (ThreePointVelocity) where the track has its three seen points and it is surer
// (WithSurerVelocity); `state` otherwise. agreement_probability 0: `state`.
Gaussian WithSeenVelocity(const Gaussian& state, const EarlySeenPoints& early_seen_points,
                          double agreement_probability);

// `state` (x, y, vx, vy) with its velocity replaced by `velocity` where that is surer (smaller
// trace), the cross terms zeroed; unchanged otherwise.
Gaussian WithSurerVelocity(const Gaussian& state, const Gaussian& velocity);

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
  int misses = 0;        // consecutive scans without one in which a sensor could have seen it
  TimeNs last_detected = 0;  // stamp of the last scan that brought it a detection
  bool lost = false;         // hidden for longer than its prediction is worth (track_management.h)
  bool coasting = false; // the last scan brought no detection
  // The log odds that the track is a road user rather than a ghost of the lidar's object
  // source, from the camera's evidence on its detections (track_management.h); 0 without any.
  double existence_log_odds = 0.0;
  // The seen points of its first detections, while it has had fewer than three
  // (ThreePointVelocity).
  EarlySeenPoints early_seen_points;
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

// The detections that can be used, in their order: finite, with a symmetric positive definite
// covariance. Both trackers drop the others and count them (Tracker::dropped_detections).
std::vector<Detection> UsableDetections(const std::vector<Detection>& detections);

// Whether a detection of class `detection` may join a track of class `track`.
bool ClassesCompatible(ObjectClass track, ObjectClass detection);

// How much of an object the sensors could see at one scan (SensorView), as fractions of it:
// `in_view`, inside the sensors' field of view and reach; `seen`, in view and not hidden
// behind anything nearer (seen <= in_view).
struct ViewFraction {
  double in_view = 1.0;
  double seen = 1.0;
};

// Where the sensors could see at one scan (seed 004 VII: tracks coast "through occlusion"), at
// a position in the tracker's frame, for an object of a class. A scan without a detection for
// a track the sensors could not see says little against it: the MHT gives such a track a low
// detection probability (mht_tracker.h), and track management does not count the scan as a
// miss when something nearer hid it (track_management.h). scan_visibility.h makes a view from
// a lidar scan.
class SensorView {
 public:
  virtual ~SensorView() = default;
  virtual ViewFraction View(const Eigen::Vector2d& position_m, ObjectClass c) const = 0;
};

// A view that sees everything everywhere: every scan could have detected every track.
class OpenView final : public SensorView {
 public:
  ViewFraction View(const Eigen::Vector2d& /*position_m*/, ObjectClass /*c*/) const override {
    return {};
  }
};

class Tracker {
 public:
  virtual ~Tracker() = default;

  // One scan at `stamp`, detections in a ground-fixed frame, `view` where the sensors could see
  // (the same frame). A stamp not after the previous scan's is refused: nothing changes and the
  // call returns false (the caller logs it). Detections with a non-finite field or a covariance
  // that is not symmetric positive definite are dropped and counted.
  virtual bool Step(TimeNs stamp, const std::vector<Detection>& detections,
                    const SensorView& view) = 0;
  // The same with a view that sees everywhere (OpenView).
  bool Step(TimeNs stamp, const std::vector<Detection>& detections) {
    return Step(stamp, detections, OpenView{});
  }

  // The confirmed tracks after the last scan, in increasing id order.
  virtual std::vector<Track> ConfirmedTracks() const = 0;
  virtual std::int64_t dropped_detections() const = 0;
  virtual std::int64_t refused_scans() const = 0;
};

}  // namespace lookout::tracking
