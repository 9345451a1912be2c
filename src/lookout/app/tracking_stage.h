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
// users), the lidar-only objects that the grid holds static (parked cars, buildings' corners:
// the tracker follows road users; a static road user seen by the camera stays in), and, when
// the ego's map is known, the lidar-only objects whose centre lies inside a building (ghosts of
// its walls, building_map.h; where the camera sees them its silence ends them too, but most
// lie beside the road, outside its view).
//
// Which tracks are output (tracks(), the risk stage's input): the tracker's confirmed tracks
// but those the camera has not spoken for (existence log odds <= 0: no camera object, or more
// evidence against than for) that may be standing still: slower than static_speed_mps, or a
// velocity within the chi-square gate of zero. The same rule as for detections (lidar-only
// objects the grid holds static are static structure), on the track's motion over many scans,
// which is surer than one cluster's cells. The grid's ghosts on walls, parked cars and building
// corners, which it calls moving but which stay where they are, go; so does a lidar-only road
// user until its track shows it moving (a few scans), or while it stands where the camera
// cannot see it.
//
// What the camera says about each (tracking::CameraEvidence, for the track management's
// existence odds against ghosts): seen, when the camera reported it; unseen, when it is a
// lidar-only object whose centre lies inside the camera's field of view and depth (less a
// margin for the estimate's error) and no camera object of the frame lies within its gate
// (the camera saw something there that fusion did not pair: no evidence); none otherwise, and
// for every object of a cycle whose fusion had no camera frame (a camera that stops says
// nothing about the objects).

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lookout/app/building_map.h"
#include "lookout/core/class_footprint.h"
#include "lookout/core/pose2.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/tracking/gnn_tracker.h"
#include "lookout/tracking/mht_tracker.h"
#include "lookout/tracking/scan_visibility.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

enum class TrackerKind { kMht, kGnn };

// "mht", "gnn"; nullopt for an unknown name.
std::optional<TrackerKind> ParseTrackerKind(const std::string& name);
const char* ToString(TrackerKind kind);

struct DetectionOptions {
  // The classes' footprints (core/class_footprint.h): the depth behind the seen side of an
  // object of each class.
  ClassFootprints footprints;
  // Added to the point's covariance (isotropic) for the guessed depth: real cars are 3.5-5 m.
  // It also stands for what a detection's covariance leaves out (pairs on the wrong walker, a
  // side the motion cannot tell). For an object both sensors saw, centre_offset_sigma_two_m:
  // the fused covariance holds its errors (mean NEES in its 95 % band in 11 of the catalogue's
  // 12 scenarios since 2026-12-04), and 0.25 m over fused points right to a few centimetres made
  // a track's velocity covariance far larger than its error (docs/tracking-metrics.md, "The
  // floor under a fused detection"). 0.15 m: the smallest of 0.10, 0.12, 0.13, 0.15 and 0.20
  // that keeps every scenario's MOTA and IDF1 >= 0.9 (at 0.13 and below cyclist-crossing's MOTA
  // is 0.895: its cyclist's track splits at the pull-out).
  double centre_offset_sigma_m = 0.25;
  double centre_offset_sigma_two_m = 0.15;
  // Below this length the front segment gives no direction; the line of sight does.
  double min_segment_m = 0.2;
  // An object of unknown class whose seen side is shorter than this is walker-sized (the
  // segmentation's bound for a round arc, lidar::SegmentationOptions::min_box_side_m): its
  // centre is a walker's radius behind the side, give or take walker_depth_sigma_m (it may
  // be a cyclist end-on, or the visible end of something longer), not half a car's depth.
  double walker_side_max_m = 0.7;
  double walker_depth_sigma_m = 0.3;
  bool keep_static_lidar_objects = false;
  // The camera's field of view and depth (the seed vehicle's camera, docs/scenarios.md), and
  // how far inside them a centre must be for the camera's silence to count.
  double camera_fov_rad = 70.0 * kPi / 180.0;
  double camera_max_depth_m = 35.0;
  double camera_view_margin_rad = 3.0 * kPi / 180.0;
  double camera_view_margin_m = 2.0;
  // A camera object within this chi-square gate (2 dof) of a lidar-only object saw it.
  double camera_gate_probability = 0.999;
  // The camera's silence on a lidar-only object is no evidence when another object the lidar
  // saw stands between the camera and it: nearer by more than this (further behind than a
  // second segment of one road user: a cyclist's two wheels are 1.5 m apart), its seen side
  // within this angle of the object's bearing from the camera (a walker's half width at 20 m
  // is about 1 degree). A walker hidden from the camera by a nearer one, and still seen by the
  // lidar, was otherwise deleted as a ghost (occluded-pedestrian).
  double camera_occluder_margin_m = 2.5;
  double camera_occluder_margin_rad = 1.0 * kPi / 180.0;
  // A lidar-only object whose centre lies deeper than this inside a building of the ego's map
  // (building_map.h) is a ghost of its wall: left out. Half a walker's radius, so that a road
  // user beside a wall (its centre at least its radius outside) stays in with its estimate's
  // error.
  double building_margin_m = 0.15;
  // A track without the camera's support is a road user only when it moves: faster than
  // this (the grid's and fusion's "dynamic" threshold), and its velocity significantly not
  // zero (outside this chi-square gate of zero, 2 dof).
  double static_speed_mps = 0.5;
  double moving_probability = 0.99;
  // Which side of its box an object shows: a road user moves along its length, so a seen side
  // within 45 degrees of the object's velocity is its long side, otherwise its front or rear,
  // when the velocity is at least this fast and significantly not zero (moving_probability);
  // otherwise the side's length decides (longer than half the box's length plus width: the
  // long side). The length alone flips between the two on a long side seen in part (2.5-3.5 m
  // of a car's 4.5 m), and each flip moves the centre by 1.35 m.
  double heading_min_speed_mps = 1.0;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "detection options") const;
};

// The most likely class of a fused object's pmf (the first of equals).
ObjectClass MostLikelyClass(const fusion::FusedObject& object);

// What the camera's own track says about one fused object (CameraTrackHistory).
struct CameraHistory {
  ObjectClass object_class = ObjectClass::kUnknown;  // the most likely over the camera's track
  int frames = 0;  // frames of its camera track so far, this one included; 0: not seen
};

// The tracker's detections from one fused frame, in the odometry frame. `history`, when not
// empty, gives each object's camera history (one per object); otherwise the class is
// MostLikelyClass and a camera object counts as seen once. A camera object counts as the
// camera's evidence for an object (CameraEvidence::kSeen) from its camera track's second frame
// on: the camera's false objects are never tracked over frames. `camera_mount` (vehicle
// frame): the camera whose frame is recent enough for this cycle, nullopt when there is none.
// `buildings` (odometry frame): the ego's map; a lidar-only object whose centre lies inside one
// deeper than building_margin_m is left out and counted in `*in_buildings` (when given).
// Objects with a non-finite field are passed on as they are: the tracker drops and counts
// them. Pure.
std::vector<tracking::Detection> DetectionsFromFusedObjects(
    const fusion::FusedObjectFrame& frame, const DetectionOptions& options,
    const std::vector<CameraHistory>& history = {},
    const std::optional<Pose2>& camera_mount = std::nullopt,
    const BuildingOutlines& buildings = {}, std::int64_t* in_buildings = nullptr);

// Whether a confirmed track moves: its speed at least static_speed_mps and its velocity
// outside the chi-square gate of zero of moving_probability; or, hidden since its last
// detection (coasting without a miss: tracking/track_management.h), whether it moved at the
// scan before (`moved_when_detected`, the caller's memory). Pure.
// Why the second: a hidden track's prediction says nothing new of whether the object moves,
// only how sure the prediction is, and its velocity covariance grows at every scan. A lidar-only
// walker hidden behind a building (crowd) coasted within 0.4 m of it for 1.3 s and within 2 m
// for 4.6 s, but its track left the output at the scan after it was hidden. A track missed
// where the sensors could see it is judged afresh: its silence is evidence (on the leg-tracker
// bag, clutter's tracks kept by their last motion were 7 more false frames).
bool ShowsMotion(const tracking::Track& track, const DetectionOptions& options,
                 bool moved_when_detected);

// Whether a confirmed track is output as a road user (above): the camera's evidence for it, or
// its motion (ShowsMotion). Pure.
bool IsRoadUser(const tracking::Track& track, const DetectionOptions& options,
                bool moved_when_detected = false);
// The same with the track's motion already judged (`shows_motion`: ShowsMotion's verdict).
bool IsRoadUser(const tracking::Track& track, bool shows_motion);

// The camera's evidence per camera track id: its frames, and the sum of the log class
// probabilities of its frames. Forgets an id not seen for `forget_after_s`.
class CameraTrackHistory {
 public:
  explicit CameraTrackHistory(double forget_after_s = 1.0) : forget_after_s_(forget_after_s) {}
  // Each object's history after adding this frame: the class over the camera track when the
  // camera saw it, MostLikelyClass otherwise.
  std::vector<CameraHistory> Update(const fusion::FusedObjectFrame& frame);

 private:
  struct Evidence {
    std::array<double, kAllObjectClasses.size()> log_sum{};
    TimeNs last_seen = 0;
    int frames = 0;
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
  // Where the cycle's lidar scan could see (tracking/scan_visibility.h): tracks it could not
  // see coast through the scan without a miss (both trackers). Off: every track could have
  // been seen at every scan, the trackers' behaviour before 2026-12-03.
  bool scan_visibility = true;
  tracking::ScanVisibilityOptions visibility;

  void Validate(const std::string& source = "tracking options") const;
};

class TrackingStage {
 public:
  explicit TrackingStage(const TrackingStageOptions& options = {});

  // One cycle. `camera_mount`: the camera whose frame the cycle's fusion used (nullopt: none).
  // `scan`: the lidar scan of the cycle (taken at the frame's stamp, the ego at the frame's
  // pose), which tells where the sensors could see; null: everywhere.
  // A frame whose stamp is not after the previous one's is refused by the trackers: the tracks
  // stay as they were and a warning is logged (warnings()).
  void Step(const fusion::FusedObjectFrame& frame,
            const std::optional<Pose2>& camera_mount = std::nullopt,
            const LidarScan* scan = nullptr);
  // The buildings of the ego's map in the odometry frame (empty: none).
  void SetBuildings(BuildingOutlines buildings) { buildings_ = std::move(buildings); }
  // Lidar-only objects left out so far for lying inside a building.
  std::int64_t detections_in_buildings() const { return in_buildings_; }

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
  // The ids of the tracks that showed motion at the last scan (ShowsMotion), increasing.
  std::vector<std::uint32_t> moving_ids_, baseline_moving_ids_;
  std::vector<tracking::Detection> detections_;
  CameraTrackHistory camera_history_;
  std::optional<TimeNs> last_stamp_;
  std::vector<double> step_ms_, baseline_step_ms_;
  std::vector<std::string> warnings_;
  std::int64_t warning_count_ = 0;
  std::int64_t dropped_reported_ = 0;
  BuildingOutlines buildings_;
  std::int64_t in_buildings_ = 0;
};

}  // namespace lookout::app
