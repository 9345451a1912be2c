#pragma once

// Point-against-polygon and point-against-segment tests in the plane, shared by the grid's
// class regions, the risk stage's box distances, the ego map's buildings and the grid metrics;
// and the plane's cross product, which the simulator, the segmentation and the turn paths use.
// Inline: the grid calls the first per cell and the risk stage the second per pair of boxes and
// step.

#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace lookout {

// The z component of the 3-D cross product (a, 0) x (b, 0): > 0 when b is counter-clockwise of a.
inline double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Even-odd rule: a horizontal ray from `p` crosses the ring an odd number of times. `ring` is a
// simple closed ring, either orientation (the last vertex joins the first); a point on an edge
// may go either way.
inline bool InsidePolygon(const std::vector<Eigen::Vector2d>& ring, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

// The distance from `p` to the segment [a, b] (to `a` when the segment is a point).
inline double PointToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                             const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + u * ab)).norm();
}

}  // namespace lookout
