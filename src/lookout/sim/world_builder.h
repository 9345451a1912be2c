#pragma once

#include <vector>

#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"

namespace lookout::sim {

// The static world of a scenario as shapes: the preset's (four_way: two roads 7 m wide
// crossing at the origin, building blocks on the four corners set back from the kerb, a few
// poles and signs) followed by the file's obstacles, all owned by kStaticOwner.
// Preset shapes come first, in a fixed order (buildings NE, NW, SW, SE, then poles, then
// signs), then the obstacles in file order: building -> polygon, pole and sign -> circle,
// parked_car -> box. An unknown preset name is a programming error (the loader admits only
// "four_way") and throws std::invalid_argument.
std::vector<Shape> BuildStaticWorld(const World& world);

// The outlines of the world's buildings (the preset's blocks, NE, NW, SW, SE, then the file's
// building obstacles in file order): the part of the static world a map of the ground holds,
// and where no road user can be. World frame; an unknown preset throws as above.
std::vector<std::vector<Eigen::Vector2d>> BuildingOutlines(const World& world);

// The four_way layout, metres. Carriageways: |y| <= kFourWayRoadHalfWidthM (east-west) and
// |x| <= kFourWayRoadHalfWidthM (north-south), free of preset shapes. Sidewalks run
// kFourWaySidewalkWidthM beyond each kerb and hold only poles and signs, 0.5 m from the kerb;
// the building blocks start at the back of the sidewalks and reach kFourWayBlockExtentM.
inline constexpr double kFourWayRoadHalfWidthM = 3.5;
inline constexpr double kFourWaySidewalkWidthM = 2.5;
inline constexpr double kFourWayBlockExtentM = 60.0;

}  // namespace lookout::sim
