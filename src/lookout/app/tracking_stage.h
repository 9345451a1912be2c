#pragma once

// Tracking as a pipeline stage (seed 004 section VII): each cycle's fused objects (vehicle frame
// at the lidar stamp) become detections in the ground-fixed odometry frame, through the frame's
// ego pose, and go to a tracking::Tracker chosen by option: Reid's MHT with the IMM
// (tracking/mht_tracker.h, the default) or the GNN baseline (tracking/gnn_tracker.h). The GNN
// runs beside the MHT on the same detections, so that every metric table has both.
//
// Which point is tracked: the object's centre. Both sensors report the middle of the side that
// faces the lidar (the front segment, seed 004 VI), which moves over the object as the view
// changes (a car turning in front of the ego shows its side, then its rear) and lies up to half
// a car's length (2.25 m) from the centre. The risk stage's circles are centred on the object,
// and the truth is scored at the centre; so each detection is moved from the front segment's
// middle, away from the lidar, by half the object's depth behind that side: the class's default
// width when the segment is the long side, its length when it is the short one.
//
// Which class: the camera's, over its own track. The camera classifies each frame anew (the
// simulated one confuses 10 % of them), and the trackers gate by class (no pedestrian joins a
// car's track), so one confused frame would start a second track beside the true one. The
// camera's track id is stable while it follows an object, so the stage sums the log class
// probabilities of every frame of that id and gives the detection the most likely class over
// the history. Objects the camera did not see keep the lidar's class.
//
// Which objects become detections: every fused object but poles (street furniture, not road
// users) and the lidar-only objects that the grid holds static (parked cars, buildings' corners:
// the tracker follows road users; a static road user seen by the camera stays in).

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lookout/fusion/fused_object.h"
#include "lookout/tracking/gnn_tracker.h"
#include "lookout/tracking/mht_tracker.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

enum class TrackerKind { kMht, kGnn };

// "mht", "gnn"; nullopt for an unknown name.
std::optional<TrackerKind> ParseTrackerKind(const std::string& name);
const char* ToString(TrackerKind kind);

struct DetectionOptions {
  // The default footprints of the scenario format (docs/scenarios.md), the depth behind the
  // seen side of an object of each class.
  double car_length_m = 4.5, car_width_m = 1.8;
  double truck_length_m = 8.0, truck_width_m = 2.5;
  double cyclist_length_m = 1.8, cyclist_width_m = 0.6;
  double pedestrian_radius_m = 0.3;
  // Added to the point's covariance (isotropic) for the guessed depth: real cars are 3.5-5 m.
  double centre_offset_sigma_m = 0.25;
  // Below this length the front segment gives no direction; the line of sight does.
  double min_segment_m = 0.2;
  bool keep_static_lidar_objects = false;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "detection options") const;
};

// The most likely class of a fused object's pmf (the first of equals).
ObjectClass MostLikelyClass(const fusion::FusedObject& object);

// The tracker's detections from one fused frame, in the odometry frame. `classes`, when not
// empty, gives each object's class (one per object), otherwise MostLikelyClass. Objects with a
// non-finite field are passed on as they are: the tracker drops and counts them. Pure.
std::vector<tracking::Detection> DetectionsFromFusedObjects(
    const fusion::FusedObjectFrame& frame, const DetectionOptions& options,
    const std::vector<ObjectClass>& classes = {});

// The camera's class evidence per camera track id: the sum of the log class probabilities of
// its frames. Forgets an id not seen for `forget_after_s`.
class CameraClassHistory {
 public:
  explicit CameraClassHistory(double forget_after_s = 1.0) : forget_after_s_(forget_after_s) {}
  // Each object's class after adding this frame's evidence: over the camera track's history
  // when the camera saw it, MostLikelyClass otherwise.
  std::vector<ObjectClass> Update(const fusion::FusedObjectFrame& frame);

 private:
  struct Evidence {
    std::array<double, kAllObjectClasses.size()> log_sum{};
    TimeNs last_seen = 0;
  };
  double forget_after_s_;
  std::map<std::uint32_t, Evidence> evidence_;
};

struct TrackingStageOptions {
  TrackerKind tracker = TrackerKind::kMht;
  // Run the GNN baseline beside the tracker (nothing to compare when the tracker is the GNN).
  bool baseline = true;
  tracking::MhtOptions mht;
  tracking::GnnOptions gnn;
  DetectionOptions detections;

  void Validate(const std::string& source = "tracking options") const;
};

class TrackingStage {
 public:
  explicit TrackingStage(const TrackingStageOptions& options = {});

  // One cycle. A frame whose stamp is not after the previous one's is refused by the trackers:
  // the tracks stay as they were and a warning is logged (warnings()).
  void Step(const fusion::FusedObjectFrame& frame);

  const tracking::Tracker& tracker() const { return *tracker_; }
  // The GNN beside the tracker, or nullptr when it does not run.
  const tracking::Tracker* baseline() const { return baseline_.get(); }
  TrackerKind kind() const { return options_.tracker; }

  // The confirmed tracks after the last accepted cycle (odometry frame), and its stamp.
  const std::vector<tracking::Track>& tracks() const { return tracks_; }
  const std::vector<tracking::Track>& baseline_tracks() const { return baseline_tracks_; }
  std::optional<TimeNs> last_stamp() const { return last_stamp_; }
  const std::vector<tracking::Detection>& last_detections() const { return detections_; }

  // Wall time of each of the tracker's steps, and of the baseline's, ms.
  const std::vector<double>& step_ms() const { return step_ms_; }
  const std::vector<double>& baseline_step_ms() const { return baseline_step_ms_; }
  // The first kMaxWarnings warnings ("tracking: frame at 1.200 s refused: ..."), and how many
  // there were in all.
  static constexpr std::size_t kMaxWarnings = 20;
  const std::vector<std::string>& warnings() const { return warnings_; }
  std::int64_t warning_count() const { return warning_count_; }

 private:
  void Warn(std::string message);

  TrackingStageOptions options_;
  std::unique_ptr<tracking::Tracker> tracker_;
  std::unique_ptr<tracking::Tracker> baseline_;
  std::vector<tracking::Track> tracks_, baseline_tracks_;
  std::vector<tracking::Detection> detections_;
  CameraClassHistory classes_;
  std::optional<TimeNs> last_stamp_;
  std::vector<double> step_ms_, baseline_step_ms_;
  std::vector<std::string> warnings_;
  std::int64_t warning_count_ = 0;
  std::int64_t dropped_reported_ = 0;
};

}  // namespace lookout::app
