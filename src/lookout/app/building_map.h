#pragma once

// The buildings of the ego's map, and how deep a point lies inside one.
//
// Why: the grid's lidar objects include ghosts of static structure read as moving, and most of
// them lie on building walls (the visible end of a facade slides along it as the ego moves, and
// the cells it uncovers look like motion). The tracking stage places each object's centre half
// its depth behind the side the lidar saw, so a ghost on a wall has its centre inside the
// building (measured over the catalogue on 2026-12-02: 0.2-2.4 m deep, by the class's depth),
// where no road user can be; a road user beside the wall has its centre at least its own radius
// outside. A map of the ground (as a navigation system holds it; in the simulator, the scenario's
// blocks and buildings) tells them apart where the camera cannot see.

#include <Eigen/Core>
#include <vector>

#include "lookout/core/pose2.h"

namespace lookout::app {

// Simple closed rings, either orientation, in one ground-fixed frame; empty: no map.
using BuildingOutlines = std::vector<std::vector<Eigen::Vector2d>>;

// The outlines moved into another frame: each vertex v becomes frame_from_map * v. Pure.
BuildingOutlines Transformed(const BuildingOutlines& outlines, const Pose2& frame_from_map);

// The distance from `p` to the boundary of the building that contains it (the deepest, should
// outlines overlap), 0 when no building contains it (or the point is on a wall). Pure.
double DepthInsideBuildings(const BuildingOutlines& outlines, const Eigen::Vector2d& p);

}  // namespace lookout::app
