#pragma once

// Where one lidar scan could see (tracker.h, SensorView). The beams across an object at a
// position are those within its half width of the line of sight to its centre (at least the
// one nearest that line). Of them, a beam inside the scan's fan, with the object within the
// lidar's reach, is in view; a beam in view sees the object when it returned no nearer than the
// object's nearest possible face (its centre less its half length and a margin), or returned
// nothing (open space the object would have stopped). A beam stopped short of it, by a nearer
// road user, a parked car or a building's corner, leaves it hidden. A beam with a non-finite
// range says nothing, so sees nothing.
//
// Half width for the span, half length for the depth: the span is what any face of the object
// covers at least (a car end-on shows its width), so that a neighbour beside it is not taken
// for an occluder; the depth is how far any face can stand in front of its centre (a car's
// nose, end-on), so that the object does not hide itself.
//
// The scan's detections overrule its beams: an object within its half length (and a margin) of
// a detection of the scan was seen, whatever the beams say (the camera sees round a nearer object's
// edge where the lidar's returns do not reach, and fusion reports the object).
//
// One lidar stands for both sensors: the camera looks out from nearly the same place inside the
// lidar's fan (docs/scenarios.md), so what hides an object from the one hides it from the
// other.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "lookout/core/class_footprint.h"
#include "lookout/core/messages.h"
#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/tracking/tracker.h"

namespace lookout::tracking {

struct ScanVisibilityOptions {
  // The classes' footprints (core/class_footprint.h): half a class's width for the beams across
  // it, half its length for its faces' depth. Trucks are taken as cars (the view asks whether the
  // beams reach a body, and a car's half width is the narrower, surer span); unknown objects and
  // poles as a walker's width and a car's depth (an unknown object may be either; taking it for
  // shallower would let it hide itself).
  ClassFootprints footprints;
  // Added to the depth: the centre's estimate is off by a few decimetres.
  double depth_margin_m = 0.5;
  // Added to the half length for the detections' overrule: a track's centre and the centre a
  // detection gives differ by the guessed depth (an unknown walker's is put 1.1 m behind its
  // seen side) and the track's error.
  double detection_margin_m = 1.0;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "scan visibility options") const;
};

class ScanVisibility final : public SensorView {
 public:
  // `sensor_pose`: the lidar in the tracker's frame when it took `scan` (the ego's pose
  // composed with the scan's mount). Keeps a copy of the ranges.
  // `detections`: the scan's detections (positions in the tracker's frame).
  ScanVisibility(const LidarScan& scan, const Pose2& sensor_pose,
                 const ScanVisibilityOptions& options = {},
                 std::vector<Eigen::Vector2d> detections = {});

  ViewFraction View(const Eigen::Vector2d& position_m, ObjectClass c) const override;

 private:
  ScanVisibilityOptions options_;
  Pose2 world_to_sensor_;
  double angle_min_rad_, angle_increment_rad_, max_range_m_, no_return_m_;
  std::vector<float> ranges_m_;
  std::vector<Eigen::Vector2d> detections_;
};

}  // namespace lookout::tracking
