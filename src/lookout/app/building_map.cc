#include "lookout/app/building_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lookout::app {
namespace {

double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Even-odd rule: a horizontal ray from p crosses the ring an odd number of times.
bool InsideRing(const std::vector<Eigen::Vector2d>& ring, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      inside = !inside;
    }
  }
  return inside;
}

}  // namespace

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
    if (ring.size() < 3 || !InsideRing(ring, p)) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      nearest = std::min(nearest, SegmentDistance(p, ring[j], ring[i]));
    }
    depth = std::max(depth, nearest);
  }
  return depth;
}

}  // namespace lookout::app
