#include "lookout/app/building_map.h"

#include <algorithm>
#include <limits>

#include "lookout/core/planar_geometry.h"

namespace lookout::app {

BuildingOutlines Transformed(const BuildingOutlines& outlines, const Pose2& frame_from_map) {
  BuildingOutlines out = outlines;
  for (std::vector<Eigen::Vector2d>& ring : out) {
    for (Eigen::Vector2d& v : ring) v = frame_from_map * v;
  }
  return out;
}

double DepthInsideBuildings(const BuildingOutlines& outlines, const Eigen::Vector2d& p) {
  double depth = 0.0;
  for (const std::vector<Eigen::Vector2d>& ring : outlines) {
    if (ring.size() < 3 || !InsidePolygon(ring, p)) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      nearest = std::min(nearest, PointToSegment(p, ring[j], ring[i]));
    }
    depth = std::max(depth, nearest);
  }
  return depth;
}

}  // namespace lookout::app
