#include "lookout/sim/shapes.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

// Twice the signed area of triangle (a, b, c): > 0 when c is left of the directed line a->b,
// < 0 right of it, 0 on it.
double Orient(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  return Cross(b - a, c - a);
}

// For a point p already known to be collinear with a and b: is it within their bounding box,
// that is, on the closed segment [a, b]?
bool WithinSegmentBox(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

// Closed segments [a, b] and [c, d] share a point (proper crossing, touching, or collinear
// overlap), the textbook orientation test.
bool SegmentsIntersect(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const double o1 = Orient(c, d, a);
  const double o2 = Orient(c, d, b);
  const double o3 = Orient(a, b, c);
  const double o4 = Orient(a, b, d);
  if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) &&
      ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))) {
    return true;
  }
  return (o1 == 0.0 && WithinSegmentBox(c, d, a)) || (o2 == 0.0 && WithinSegmentBox(c, d, b)) ||
         (o3 == 0.0 && WithinSegmentBox(a, b, c)) || (o4 == 0.0 && WithinSegmentBox(a, b, d));
}

double SquaredDistanceToSegment(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0.0) return (p - a).squaredNorm();
  const double u = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (a + u * ab - p).squaredNorm();
}

// Calls f(a, b) for every edge of the closed ring, the closing edge included.
template <typename F>
bool AnyEdge(const std::vector<Vector2d>& ring, F&& f) {
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (f(ring[i], ring[(i + 1) % n])) return true;
  }
  return false;
}

bool PolygonContains(const std::vector<Vector2d>& ring, const Vector2d& p) {
  // The boundary first, so that the shape is closed whatever the crossing rule below says
  // about points on edges.
  if (AnyEdge(ring, [&](const Vector2d& a, const Vector2d& b) {
        return Orient(a, b, p) == 0.0 && WithinSegmentBox(a, b, p);
      })) {
    return true;
  }
  // Even-odd crossing number of a ray towards +x. Each edge is half-open in y, so a ray
  // through a vertex counts it once; works for either orientation.
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vector2d& a = ring[j];
    const Vector2d& b = ring[i];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

// Convex when every turn has the same sign; straight and zero-length edges turn by 0 and are
// ignored. Only meaningful for simple rings, which is what Shape requires.
bool IsConvex(const std::vector<Vector2d>& ring) {
  const std::size_t n = ring.size();
  bool left = false;
  bool right = false;
  for (std::size_t i = 0; i < n; ++i) {
    const double turn = Orient(ring[i], ring[(i + 1) % n], ring[(i + 2) % n]);
    left = left || turn > 0.0;
    right = right || turn < 0.0;
  }
  return !(left && right);
}

// Separating axis theorem: two convex polygons are disjoint exactly when the projections on
// the normal of some edge of either are disjoint. Touching projections do not separate
// (closed shapes).
bool ConvexPolygonsOverlap(const std::vector<Vector2d>& a, const std::vector<Vector2d>& b) {
  const auto separated_by_edges_of = [](const std::vector<Vector2d>& p,
                                        const std::vector<Vector2d>& q) {
    return AnyEdge(p, [&](const Vector2d& e0, const Vector2d& e1) {
      const Vector2d axis(e0.y() - e1.y(), e1.x() - e0.x());  // unnormalised normal
      double p_min = axis.dot(p.front());
      double p_max = p_min;
      for (const Vector2d& v : p) {
        const double s = axis.dot(v);
        p_min = std::min(p_min, s);
        p_max = std::max(p_max, s);
      }
      double q_min = axis.dot(q.front());
      double q_max = q_min;
      for (const Vector2d& v : q) {
        const double s = axis.dot(v);
        q_min = std::min(q_min, s);
        q_max = std::max(q_max, s);
      }
      // A zero-length edge has a zero axis: every projection is 0 and nothing separates.
      return p_max < q_min || q_max < p_min;
    });
  };
  return !separated_by_edges_of(a, b) && !separated_by_edges_of(b, a);
}

// Any simple polygons: their boundaries cross, or one lies wholly inside the other (then
// any one of its vertices is inside).
bool GeneralPolygonsOverlap(const std::vector<Vector2d>& a, const std::vector<Vector2d>& b) {
  const bool edges_meet = AnyEdge(a, [&](const Vector2d& a0, const Vector2d& a1) {
    return AnyEdge(b, [&](const Vector2d& b0, const Vector2d& b1) {
      return SegmentsIntersect(a0, a1, b0, b1);
    });
  });
  return edges_meet || PolygonContains(a, b.front()) || PolygonContains(b, a.front());
}

// Exact for any simple polygon: the circle's centre is inside, or some edge comes within
// the radius.
bool PolygonCircleOverlap(const std::vector<Vector2d>& ring, const Vector2d& center,
                          double radius) {
  if (PolygonContains(ring, center)) return true;
  const double r2 = radius * radius;
  return AnyEdge(ring, [&](const Vector2d& a, const Vector2d& b) {
    return SquaredDistanceToSegment(a, b, center) <= r2;
  });
}

}  // namespace

Shape Shape::Circle(const Eigen::Vector2d& center, double radius, int owner) {
  assert(radius >= 0.0);
  Shape s;
  s.kind = Kind::kCircle;
  s.center = center;
  s.radius = radius;
  s.owner = owner;
  return s;
}

Shape Shape::Polygon(std::vector<Eigen::Vector2d> vertices, int owner) {
  assert(vertices.size() >= 3);
  Shape s;
  s.kind = Kind::kPolygon;
  s.vertices = std::move(vertices);
  s.owner = owner;
  return s;
}

Shape Shape::Box(const Pose2& pose, double length, double width, int owner) {
  const double hl = 0.5 * length;
  const double hw = 0.5 * width;
  return Polygon({pose * Vector2d(-hl, -hw), pose * Vector2d(hl, -hw), pose * Vector2d(hl, hw),
                  pose * Vector2d(-hl, hw)},
                 owner);
}

bool Contains(const Shape& shape, const Eigen::Vector2d& point) {
  if (shape.kind == Shape::Kind::kCircle) {
    return (point - shape.center).squaredNorm() <= shape.radius * shape.radius;
  }
  return !shape.vertices.empty() && PolygonContains(shape.vertices, point);
}

bool Overlap(const Shape& a, const Shape& b) {
  using Kind = Shape::Kind;
  if (a.kind == Kind::kCircle && b.kind == Kind::kCircle) {
    const double r = a.radius + b.radius;
    return (a.center - b.center).squaredNorm() <= r * r;
  }
  if (a.kind == Kind::kCircle) return Overlap(b, a);
  if (a.vertices.empty()) return false;
  if (b.kind == Kind::kCircle) return PolygonCircleOverlap(a.vertices, b.center, b.radius);
  if (b.vertices.empty()) return false;
  if (!BoundingBox(a).Intersects(BoundingBox(b))) return false;
  if (IsConvex(a.vertices) && IsConvex(b.vertices)) {
    return ConvexPolygonsOverlap(a.vertices, b.vertices);
  }
  return GeneralPolygonsOverlap(a.vertices, b.vertices);
}

Aabb BoundingBox(const Shape& shape) {
  if (shape.kind == Shape::Kind::kCircle) {
    const Vector2d r(shape.radius, shape.radius);
    return {shape.center - r, shape.center + r};
  }
  if (shape.vertices.empty()) return {};
  Aabb box{shape.vertices.front(), shape.vertices.front()};
  for (const Vector2d& v : shape.vertices) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

}  // namespace lookout::sim
