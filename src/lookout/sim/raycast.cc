#include "lookout/sim/raycast.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "lookout/core/pose2.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Angular intervals are widened by this much so that beams exactly on an interval's end
// (tangent to a circle, through a vertex, along an edge) reach the analytic test, which then
// decides as the brute-force reference does. 1e-9 rad is 0.15 um at 150 m.
constexpr double kAngleSlackRad = 1e-9;
// Edges are closed at both ends with this slack on the edge parameter, so a beam through a
// shared vertex cannot slip between the two edges through rounding.
constexpr double kEdgeParamSlack = 1e-12;
// Geometric tolerance for "parallel and on the same line" and "origin on the boundary".
constexpr double kOnLineTolerance_m = 1e-9;
// Culling margin: a shape is skipped only when it is farther than max range by this much, so
// culling can never drop a hit that the analytic test would keep.
constexpr double kCullMargin_m = 1e-9;

// Beam directions: sines and cosines dominate a cast if taken per beam, so beam i = 32 q + r
// is the first beam's direction turned by 32 q increments, then by r increments: 32 + count/32
// sine-cosine pairs per fan instead of count. Each turn adds about one ulp of error.
constexpr int kFineSteps = 32;

Vector2d UnitAt(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

double CoarseAngle(int coarse, double increment_rad) {
  return static_cast<double>(coarse * kFineSteps) * increment_rad;
}

// v turned by the angle whose cosine and sine are cs.
Vector2d Rotate(const Vector2d& v, const Vector2d& cs) {
  return {cs.x() * v.x() - cs.y() * v.y(), cs.y() * v.x() + cs.x() * v.y()};
}

double DistanceToSegment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d e = b - a;
  const double len2 = e.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(e) / len2, 0.0, 1.0) : 0.0;
  return (a + s * e - p).norm();
}

// Distance along the ray o + t u (u a unit vector) to the closed segment [a, b]; +inf when
// the ray misses it.
double RaySegment(const Vector2d& o, const Vector2d& u, const Vector2d& a, const Vector2d& b) {
  const Vector2d e = b - a;
  const Vector2d w = a - o;
  const double denom = Cross(u, e);
  if (denom * denom <= kOnLineTolerance_m * kOnLineTolerance_m * e.squaredNorm()) {
    // Parallel. Only a beam along the edge's own line hits it, at the nearer end.
    if (std::abs(Cross(w, u)) > kOnLineTolerance_m) return kInf;
    const double ta = w.dot(u);
    const double tb = (b - o).dot(u);
    if (std::min(ta, tb) >= 0.0) return std::min(ta, tb);
    return std::max(ta, tb) >= 0.0 ? 0.0 : kInf;
  }
  const double t = Cross(w, e) / denom;
  const double s = Cross(w, u) / denom;
  if (t < 0.0 || s < -kEdgeParamSlack || s > 1.0 + kEdgeParamSlack) return kInf;
  return t;
}

// Distance along the ray to a circle the origin is outside of; +inf when it misses.
double RayCircle(const Vector2d& o, const Vector2d& u, const Vector2d& c, double r) {
  const Vector2d m = c - o;
  const double b = m.dot(u);
  const double c2 = m.squaredNorm() - r * r;  // > 0: the origin is outside
  if (b <= 0.0) return kInf;                  // the circle is behind the origin
  const double disc = b * b - c2;
  if (disc < 0.0) return kInf;
  // The nearer root b - sqrt(disc), written without cancellation for far, small circles.
  return c2 / (b + std::sqrt(disc));
}

// True when p is inside the polygon or within kOnLineTolerance_m of its boundary.
bool InsideOrOnPolygon(const std::vector<Vector2d>& ring, const Vector2d& p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vector2d& a = ring[i];
    const Vector2d& b = ring[j];
    if (DistanceToSegment(p, a, b) <= kOnLineTolerance_m) return true;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

// Shapes the origin is inside of or on are ignored (see raycast.h); so are degenerate polygons.
bool OriginIgnores(const Shape& shape, const Vector2d& origin) {
  if (shape.kind == Shape::Kind::kCircle) {
    return (origin - shape.center).norm() <= shape.radius + kOnLineTolerance_m;
  }
  return shape.vertices.size() < 2 || InsideOrOnPolygon(shape.vertices, origin);
}

// Everything about one cast that the per-shape loops share.
class FanCaster {
 public:
  FanCaster(const Fan& fan, int actor_count) : fan_(fan) {
    const auto n = static_cast<std::size_t>(fan.count);
    // Fan::BeamDirection, with its sines and cosines shared between beams: the same
    // operations in the same order, hence the same bits.
    const Vector2d first = UnitAt(fan.angle_min_rad);
    std::array<Vector2d, kFineSteps> fine;
    for (int f = 0; f < kFineSteps; ++f) {
      fine[static_cast<std::size_t>(f)] =
          UnitAt(static_cast<double>(f) * fan.angle_increment_rad);
    }
    directions_.reserve(n);
    for (int coarse = 0; coarse * kFineSteps < fan.count; ++coarse) {
      const Vector2d start =
          Rotate(first, UnitAt(CoarseAngle(coarse, fan.angle_increment_rad)));
      const int end = std::min(kFineSteps, fan.count - coarse * kFineSteps);
      for (int f = 0; f < end; ++f) {
        directions_.push_back(Rotate(start, fine[static_cast<std::size_t>(f)]));
      }
    }
    hits_.range_m.assign(n, kInf);
    hits_.owner.assign(n, kNoHit);
    hits_.beams_intersecting.assign(static_cast<std::size_t>(actor_count), 0);
    hits_.beams_nearest.assign(static_cast<std::size_t>(actor_count), 0);
    counted_for_.assign(n, kNoHit);
  }

  // Shapes of one actor must be cast one after another (see counted_for_).
  void Cast(const Shape& shape) {
    if (shape.kind == Shape::Kind::kCircle) {
      CastCircle(shape);
    } else {
      CastPolygon(shape);
    }
  }

  FanHits Finish() && {
    for (const int owner : hits_.owner) {
      if (owner >= 0) ++hits_.beams_nearest[static_cast<std::size_t>(owner)];
    }
    return std::move(hits_);
  }

 private:
  void CastCircle(const Shape& shape) {
    const Vector2d m = shape.center - fan_.origin_m;
    const double d = m.norm();
    if (d - shape.radius > fan_.max_range_m + kCullMargin_m) return;
    if (OriginIgnores(shape, fan_.origin_m)) return;
    const double half_width = std::asin(std::min(1.0, shape.radius / d));
    const double centre = std::atan2(m.y(), m.x());
    ForEachBeam(centre - half_width, 2.0 * half_width, [&](std::size_t i) {
      Record(i, RayCircle(fan_.origin_m, directions_[i], shape.center, shape.radius),
             shape.owner);
    });
  }

  void CastPolygon(const Shape& shape) {
    const std::vector<Vector2d>& ring = shape.vertices;
    if (ring.size() < 2) return;
    Vector2d centre = Vector2d::Zero();
    for (const Vector2d& v : ring) centre += v;
    centre /= static_cast<double>(ring.size());
    double radius = 0.0;
    for (const Vector2d& v : ring) radius = std::max(radius, (v - centre).norm());
    const double d = (centre - fan_.origin_m).norm();
    if (d - radius > fan_.max_range_m + kCullMargin_m) return;
    if (d <= radius + kOnLineTolerance_m && OriginIgnores(shape, fan_.origin_m)) return;

    angles_.resize(ring.size());
    for (std::size_t j = 0; j < ring.size(); ++j) {
      const Vector2d r = ring[j] - fan_.origin_m;
      angles_[j] = std::atan2(r.y(), r.x());
    }
    // Back faces are skipped: a ray from outside first meets a closed polygon on an edge that
    // faces the origin or lies along the ray, so the nearest hit, and whether the ray crosses
    // the polygon at all, never depend on the back faces. That halves the edge tests. A
    // polygon with no clear orientation (zero area) keeps all its edges.
    double twice_area = 0.0;
    for (std::size_t j = 0; j < ring.size(); ++j) {
      twice_area += Cross(ring[j] - centre, ring[j + 1 == ring.size() ? 0 : j + 1] - centre);
    }
    const double orientation =
        std::abs(twice_area) > 1e-12 * radius * radius ? (twice_area > 0.0 ? 1.0 : -1.0) : 0.0;
    // Edge by edge: each edge covers the shorter angular arc between its ends (it does not
    // pass through the origin, which was checked above), so only those beams are tested.
    for (std::size_t j = 0; j < ring.size(); ++j) {
      const std::size_t k = j + 1 == ring.size() ? 0 : j + 1;
      const Vector2d& a = ring[j];
      const Vector2d& b = ring[k];
      // > 0: the origin is on the interior side of the edge's line (counter-clockwise rings
      // have the interior on the left).
      const double facing_away = orientation * Cross(b - a, fan_.origin_m - a);
      if (facing_away > kOnLineTolerance_m * (b - a).norm()) continue;
      if (DistanceToSegment(fan_.origin_m, a, b) > fan_.max_range_m + kCullMargin_m) continue;
      const double turn = WrapAngle(angles_[k] - angles_[j]);
      const double lo = turn >= 0.0 ? angles_[j] : angles_[k];
      ForEachBeam(lo, std::abs(turn), [&](std::size_t i) {
        Record(i, RaySegment(fan_.origin_m, directions_[i], a, b), shape.owner);
      });
    }
  }

  // Calls fn(beam) for every beam whose angle lies in [lo, lo + span] modulo 2 pi (widened by
  // kAngleSlackRad). The interval is taken relative to the first beam and wrapped into
  // [0, 2 pi); its part past 2 pi wraps around to the start of the fan, which handles fans and
  // shapes that straddle +-pi.
  template <class Fn>
  void ForEachBeam(double lo, double span, Fn&& fn) const {
    constexpr double kTwoPi = 2.0 * kPi;
    double rel = std::fmod(lo - fan_.angle_min_rad, kTwoPi);
    if (rel < 0.0) rel += kTwoPi;
    const double last_beam = static_cast<double>(fan_.count - 1);
    for (const double start : {rel, rel - kTwoPi}) {
      const double first =
          std::max(0.0, std::ceil((start - kAngleSlackRad) / fan_.angle_increment_rad));
      const double last = std::min(
          last_beam, std::floor((start + span + kAngleSlackRad) / fan_.angle_increment_rad));
      for (double i = first; i <= last; i += 1.0) fn(static_cast<std::size_t>(i));
    }
  }

  void Record(std::size_t beam, double t, int owner) {
    if (!(t <= fan_.max_range_m)) return;  // also rejects +inf
    double& best = hits_.range_m[beam];
    int& best_owner = hits_.owner[beam];
    if (t < best || (t == best && owner < best_owner)) {
      best = t;
      best_owner = owner;
    }
    if (owner >= 0 && counted_for_[beam] != owner) {
      counted_for_[beam] = owner;
      ++hits_.beams_intersecting[static_cast<std::size_t>(owner)];
    }
  }

  const Fan& fan_;
  std::vector<Vector2d> directions_;
  std::vector<double> angles_;  // scratch: vertex bearings of the current polygon
  FanHits hits_;
  // Per beam, the actor it was last counted as intersecting: an actor's shapes are cast
  // consecutively, so this counts each beam once per actor however many of its edges or
  // shapes the beam crosses.
  std::vector<int> counted_for_;
};

void RecordBest(double t, int owner, double max_range_m, RayHit& best) {
  if (t <= max_range_m && (t < best.range_m || (t == best.range_m && owner < best.owner))) {
    best.range_m = t;
    best.owner = owner;
  }
}

}  // namespace

Eigen::Vector2d Fan::BeamDirection(int i) const {
  const int coarse = i / kFineSteps;
  const int fine = i % kFineSteps;
  return Rotate(Rotate(UnitAt(angle_min_rad), UnitAt(CoarseAngle(coarse, angle_increment_rad))),
                UnitAt(static_cast<double>(fine) * angle_increment_rad));
}

double FanHits::VisibleFraction(int actor) const {
  const auto a = static_cast<std::size_t>(actor);
  if (beams_intersecting[a] == 0) return 0.0;
  return static_cast<double>(beams_nearest[a]) / static_cast<double>(beams_intersecting[a]);
}

FanHits CastFan(const Fan& fan, std::span<const Shape> static_world,
                std::span<const Shape> dynamic, int actor_count) {
  assert(fan.count >= 0 && actor_count >= 0);
  assert(fan.count == 0 || fan.angle_increment_rad > 0.0);
  assert(static_cast<double>(fan.count - 1) * fan.angle_increment_rad < 2.0 * kPi);
  FanCaster caster(fan, actor_count);
  if (fan.count == 0) return std::move(caster).Finish();

  // Shapes nobody owns first, then the actors' shapes grouped by owner (the counting needs
  // the grouping); footprints usually arrive one per actor in index order, so the sort is
  // rarely needed. The order never changes a range or an owner (ties go by owner).
  std::vector<const Shape*> order;
  order.reserve(dynamic.size());
  for (const std::span<const Shape> shapes : {static_world, dynamic}) {
    for (const Shape& s : shapes) {
      assert(s.owner < actor_count);
      if (s.owner < 0) {
        caster.Cast(s);
      } else {
        order.push_back(&s);
      }
    }
  }
  const auto by_owner = [](const Shape* a, const Shape* b) { return a->owner < b->owner; };
  if (!std::is_sorted(order.begin(), order.end(), by_owner)) {
    std::stable_sort(order.begin(), order.end(), by_owner);
  }
  for (const Shape* s : order) caster.Cast(*s);
  return std::move(caster).Finish();
}

RayHit CastRayBruteForce(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                         double max_range_m, std::span<const Shape> shapes) {
  RayHit best{kInf, kNoHit};
  for (const Shape& s : shapes) {
    if (OriginIgnores(s, origin)) continue;
    if (s.kind == Shape::Kind::kCircle) {
      RecordBest(RayCircle(origin, direction, s.center, s.radius), s.owner, max_range_m, best);
      continue;
    }
    for (std::size_t j = 0; j < s.vertices.size(); ++j) {
      const std::size_t k = j + 1 == s.vertices.size() ? 0 : j + 1;
      RecordBest(RaySegment(origin, direction, s.vertices[j], s.vertices[k]), s.owner,
                 max_range_m, best);
    }
  }
  return best;
}

}  // namespace lookout::sim
