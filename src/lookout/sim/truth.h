#pragma once

// Ground truth: what really happened in the simulated world, for scoring every stage.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/core/object_class.h"
#include "lookout/core/time.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/trajectory.h"

namespace lookout::sim {

struct ActorTruth {
  int index = 0;  // in Scenario::actors
  std::string id;
  ObjectClass object_class = ObjectClass::kCar;
  KinematicState state;
  Shape footprint;  // world frame
  double visible_fraction_lidar = 0.0;   // share of the beams that would hit it, that do
  double visible_fraction_stereo = 0.0;  // the same for the camera's ray fan
  // Scenario time at which the actor's footprint first touches the ego's, if it ever does.
  std::optional<double> contact_time_s;
};

struct EgoTruth {
  KinematicState state;
  Shape footprint;
};

struct TruthFrame {
  TimeNs stamp = 0;
  EgoTruth ego;
  std::vector<ActorTruth> actors;  // only the actors present at `stamp`
  // What each beam of the lidar scan at `stamp` hit, beam for beam: kStaticOwner, an actor
  // index (ActorTruth::index), or kNoHit. The geometric cast, before noise and dropouts: a
  // beam the scan reports as a dropout still has its owner here. For scoring per-beam
  // classifications (moving and static hits); not part of any message a stage receives.
  std::vector<int> lidar_beam_owner;
};

// True occupancy and velocity per cell, for any grid geometry (world frame).
struct TruthRaster {
  GridGeometry geometry;
  std::vector<std::uint8_t> occupied;    // 1 when the cell centre lies inside a shape
  std::vector<Eigen::Vector2f> velocity;  // of the rigid body at the cell centre, m/s
  std::vector<int> owner;                 // kStaticOwner, an actor index, or -2 for free
};

inline constexpr int kFreeCell = -2;

// Rasterises actors (moving) and the static world (still) onto `geometry`. The ego is not
// included: it is the observer. Velocity at a cell centre c of a body with centre p, velocity
// v and yaw rate w is v + w x (c - p). A cell is occupied when its centre lies in a shape
// (boundary included). Where shapes overlap, actors win over the static world and a later
// actor in `frame.actors` over an earlier one; a cell has one owner and its velocity.
// Cost: each shape visits only the cells of its bounding box.
TruthRaster RasteriseTruth(const TruthFrame& frame, const std::vector<Shape>& static_world,
                           const GridGeometry& geometry);

}  // namespace lookout::sim
