#pragma once

#include <vector>

#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"

namespace lookout::sim {

// The static world of a scenario as shapes: the preset's (four_way: two roads 7 m wide
// crossing at the origin, building blocks on the four corners set back from the kerb, a few
// poles and signs) followed by the file's obstacles, all owned by kStaticOwner.
std::vector<Shape> BuildStaticWorld(const World& world);

}  // namespace lookout::sim
