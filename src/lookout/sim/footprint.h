#pragma once

// The outline a vehicle or a pedestrian occupies on the ground, and its shape at a pose.

#include "lookout/core/pose2.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"

namespace lookout::sim {

// A box (cars, trucks, cyclists, the ego) centred on the pose with its length along the
// heading, or a circle (pedestrians) centred on it. Metres.
struct Footprint {
  enum class Kind { kBox, kCircle };
  Kind kind = Kind::kBox;
  double length_m = 0.0;  // box
  double width_m = 0.0;   // box
  double radius_m = 0.0;  // circle

  static Footprint Box(double length_m, double width_m) {
    return {Kind::kBox, length_m, width_m, 0.0};
  }
  static Footprint Circle(double radius_m) { return {Kind::kCircle, 0.0, 0.0, radius_m}; }
  // Pedestrians: a circle of the spec's radius. Other classes: a box of the spec's length and
  // width, or the class defaults (DefaultLength, DefaultWidth) where those are not positive.
  static Footprint ForActor(const ActorSpec& actor);
  static Footprint ForEgo(const EgoSpec& ego) { return Box(ego.length_m, ego.width_m); }
};

// The footprint placed at `pose` (the footprint centre and heading, world frame).
Shape FootprintAt(const Footprint& footprint, const Pose2& pose, int owner);

}  // namespace lookout::sim
