#include "lookout/risk/footprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "lookout/core/planar_geometry.h"

namespace lookout::risk {
namespace {

Eigen::Vector2d Normal(const Eigen::Vector2d& axis) { return {-axis.y(), axis.x()}; }

bool IsPoint(const Footprint& f) { return f.half_length_m <= 0.0 && f.half_width_m <= 0.0; }

// Half the rectangle's extent along the unit vector n.
double HalfExtent(const Footprint& f, const Eigen::Vector2d& u, const Eigen::Vector2d& v,
                  const Eigen::Vector2d& n) {
  return f.half_length_m * std::abs(u.dot(n)) + f.half_width_m * std::abs(v.dot(n));
}

// Signed distance from point p to the rectangle of f (no radius): closed form in its frame.
double PointToRectangle(const Eigen::Vector2d& p, const Footprint& f) {
  const Eigen::Vector2d d = p - f.centre_m;
  const Eigen::Vector2d q(std::abs(d.dot(f.axis)) - f.half_length_m,
                          std::abs(d.dot(Normal(f.axis))) - f.half_width_m);
  const Eigen::Vector2d outside = q.cwiseMax(0.0);
  return outside.norm() + std::min(std::max(q.x(), q.y()), 0.0);
}

std::array<Eigen::Vector2d, 4> Corners(const Footprint& f) {
  const Eigen::Vector2d l = f.half_length_m * f.axis;
  const Eigen::Vector2d w = f.half_width_m * Normal(f.axis);
  return {f.centre_m + l + w, f.centre_m - l + w, f.centre_m - l - w, f.centre_m + l - w};
}

// The signed distance between the two rectangles (radii left out). Separating axes: the
// rectangles overlap exactly when their projections overlap on each of the four edge normals,
// and the least overlap is then the penetration depth (the shortest separating translation lies
// along an edge normal of one of two convex polygons). Apart, the distance is attained between
// a corner of one and an edge of the other.
double RectangleSeparation(const Footprint& a, const Footprint& b) {
  if (IsPoint(a)) return PointToRectangle(a.centre_m, b);
  if (IsPoint(b)) return PointToRectangle(b.centre_m, a);
  const Eigen::Vector2d ua = a.axis, va = Normal(a.axis);
  const Eigen::Vector2d ub = b.axis, vb = Normal(b.axis);
  const Eigen::Vector2d d = b.centre_m - a.centre_m;
  double depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& n : {ua, va, ub, vb}) {
    const double overlap = HalfExtent(a, ua, va, n) + HalfExtent(b, ub, vb, n) - std::abs(d.dot(n));
    if (overlap < 0.0) {
      depth = overlap;
      break;
    }
    depth = std::min(depth, overlap);
  }
  if (depth >= 0.0) return -depth;
  const std::array<Eigen::Vector2d, 4> ca = Corners(a), cb = Corners(b);
  double distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t j = (i + 1) % 4;
    for (const Eigen::Vector2d& p : ca) {
      distance = std::min(distance, PointToSegment(p, cb[i], cb[j]));
    }
    for (const Eigen::Vector2d& p : cb) {
      distance = std::min(distance, PointToSegment(p, ca[i], ca[j]));
    }
  }
  return distance;
}

}  // namespace

Footprint Footprint::Circle(const Eigen::Vector2d& centre_m, double radius_m) {
  Footprint f;
  f.centre_m = centre_m;
  f.radius_m = radius_m;
  f.bounding_radius_m = radius_m;
  return f;
}

Footprint Footprint::Box(const Eigen::Vector2d& centre_m, double yaw_rad, double length_m,
                         double width_m, double margin_m) {
  Footprint f;
  f.centre_m = centre_m;
  f.yaw_rad = yaw_rad;
  f.half_length_m = 0.5 * length_m;
  f.half_width_m = 0.5 * width_m;
  f.radius_m = margin_m;
  f.axis = Eigen::Vector2d(std::cos(yaw_rad), std::sin(yaw_rad));
  f.bounding_radius_m = std::hypot(f.half_length_m, f.half_width_m) + margin_m;
  return f;
}

double Separation(const Footprint& a, const Footprint& b) {
  return RectangleSeparation(a, b) - a.radius_m - b.radius_m;
}

bool Overlap(const Footprint& a, const Footprint& b, const Eigen::Vector2d& offset_m) {
  const Eigen::Vector2d d = b.centre_m + offset_m - a.centre_m;
  const double reach = a.bounding_radius_m + b.bounding_radius_m;
  if (d.squaredNorm() > reach * reach) return false;
  const double radii = a.radius_m + b.radius_m;
  if (IsPoint(a) || IsPoint(b)) {
    return IsPoint(a) ? PointToRectangle(a.centre_m - offset_m, b) <= radii
                      : PointToRectangle(b.centre_m + offset_m, a) <= radii;
  }
  // The widest gap between the projections on the four edge normals: no more than the
  // distance, which it equals when the closest features are an edge and a parallel edge or a
  // corner facing an edge squarely. Beyond the radii, apart; at or below zero, overlapping;
  // between, the exact distance decides.
  const Eigen::Vector2d ua = a.axis, va = Normal(a.axis), ub = b.axis, vb = Normal(b.axis);
  double widest = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& n : {ua, va, ub, vb}) {
    widest = std::max(widest, std::abs(d.dot(n)) - HalfExtent(a, ua, va, n) -
                                  HalfExtent(b, ub, vb, n));
  }
  if (widest > radii) return false;
  if (widest <= 0.0) return true;
  Footprint moved = b;
  moved.centre_m += offset_m;
  return Separation(a, moved) <= 0.0;
}

}  // namespace lookout::risk
