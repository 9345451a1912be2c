#include "lookout/grid/min_area_rectangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/pose2.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

// > 0 when o -> a -> b turns counter-clockwise.
double Cross(const Vector2d& o, const Vector2d& a, const Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// The rectangle's axis as a direction in [-pi/2, pi/2).
double AxisAngle(double yaw_rad) {
  double a = WrapAngle(yaw_rad);
  if (a >= kPi / 2.0) a -= kPi;
  if (a < -kPi / 2.0) a += kPi;
  return a;
}

}  // namespace

std::vector<Vector2d> ConvexHull(std::vector<Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Vector2d& a, const Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const Vector2d& p : points) {  // lower chain
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {  // upper chain
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

OrientedRectangle MinAreaRectangle(const std::vector<Vector2d>& points) {
  const std::vector<Vector2d> hull = ConvexHull(points);
  OrientedRectangle best;
  if (hull.empty()) return best;
  if (hull.size() == 1) {
    best.center_m = hull[0];
    return best;
  }
  double best_area = std::numeric_limits<double>::infinity();
  const std::size_t n = hull.size();
  // A segment (n == 2) has one edge direction; the loop visits it twice, harmlessly.
  for (std::size_t i = 0; i < n; ++i) {
    const Vector2d edge = hull[(i + 1) % n] - hull[i];
    const double norm = edge.norm();
    if (norm <= 0.0) continue;
    const Vector2d u = edge / norm;
    const Vector2d v(-u.y(), u.x());
    double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
    double v_min = u_min, v_max = -u_min;
    for (const Vector2d& p : hull) {
      u_min = std::min(u_min, p.dot(u));
      u_max = std::max(u_max, p.dot(u));
      v_min = std::min(v_min, p.dot(v));
      v_max = std::max(v_max, p.dot(v));
    }
    const double area = (u_max - u_min) * (v_max - v_min);
    // Strictly smaller: the first of equal edges wins, whatever rounding says of the others.
    if (area < best_area * (1.0 - 1e-12)) {
      best_area = area;
      best.center_m = 0.5 * (u_min + u_max) * u + 0.5 * (v_min + v_max) * v;
      const double along_u = u_max - u_min, along_v = v_max - v_min;
      if (along_u >= along_v) {
        best.length_m = along_u;
        best.width_m = along_v;
        best.yaw_rad = AxisAngle(std::atan2(u.y(), u.x()));
      } else {
        best.length_m = along_v;
        best.width_m = along_u;
        best.yaw_rad = AxisAngle(std::atan2(v.y(), v.x()));
      }
    }
  }
  return best;
}

}  // namespace lookout::grid
