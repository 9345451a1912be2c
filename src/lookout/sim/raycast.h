#pragma once

// Exact 2D ray casting of a fan of beams (a lidar sweep, a camera's visibility fan) against
// the shapes of the simulated world: polygon edges and circles, intersected analytically.
//
// Cost: a fan is cast shape by shape, not beam by beam. Each polygon edge and each circle
// covers an angular interval as seen from the origin, and only the beams inside that interval
// are intersected with it; shapes whose bounding circle lies beyond the maximum range are
// skipped whole. A 641-beam sweep of a junction with tens of actors therefore costs about
// (beams per shape x shapes), not (beams x shapes) -- bench/raycast_bench.cc measures it.
//
// Conventions, fixed here so that the fast fan and the slow reference agree (on owners
// exactly, on ranges to the last few bits: the fan skips polygons' back faces, which can
// only matter at a vertex the front face shares):
// - A hit at distance t counts when 0 <= t <= max range (inclusive).
// - Beams through a vertex or along an edge hit it: edges are closed at both ends (with a
//   hair of slack), and a beam along an edge hits at the edge's nearer end. A beam tangent to
//   a circle hits it when the rounded discriminant is >= 0. The angular intervals are widened
//   by a hair, so such beams always reach the analytic test, which alone decides.
// - Ties between shapes at exactly the same distance go to the lower owner index, so the
//   static world (kStaticOwner = -1) hides an actor that touches it from the same side.
//   The order of the shapes in the input never changes the result.
// - An origin inside a shape, or on its boundary, ignores that shape: a sensor that sits in
//   a wall (or in an actor it is colliding with) has no meaningful 2D view of it, and ignoring
//   it keeps the rest of the sweep valid. Such an actor counts as not intersected (visible
//   fraction 0).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "lookout/sim/shapes.h"

namespace lookout::sim {

// The owner of a beam that hits nothing within range.
inline constexpr int kNoHit = -2;

// `count` beams from one origin; beam i points at angle_min_rad + i * angle_increment_rad in
// the world frame. The fan must turn less than a full circle: (count - 1) * increment < 2 pi.
struct Fan {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;  // > 0
  int count = 0;
  double max_range_m = 0.0;          // > 0

  double BeamAngle(int i) const {
    return angle_min_rad + static_cast<double>(i) * angle_increment_rad;
  }
  // Unit vector of beam i, within a few ulps of (cos, sin) of BeamAngle(i); CastFan uses
  // exactly these directions, so the brute-force reference can be given the same rays.
  Eigen::Vector2d BeamDirection(int i) const;
};

struct FanHits {
  // Per beam: distance to the nearest hit, +infinity when none within max range ...
  std::vector<double> range_m;
  // ... and the owner of the shape hit (kStaticOwner, an actor index), or kNoHit.
  std::vector<int> owner;
  // Per actor index in [0, actor_count): beams that cross the actor's shapes within max range
  // as if it were alone in the world, and beams whose nearest hit is the actor.
  std::vector<int> beams_intersecting;
  std::vector<int> beams_nearest;

  // Share of the beams that would hit the actor that do: nearest / intersecting, in [0, 1];
  // 0 when no beam would hit it at all (outside the fan, out of range, or around the origin).
  double VisibleFraction(int actor) const;
};

// Casts `fan` against the static world and the dynamic shapes (actor footprints); the two
// spans are only a convenience, treated alike. Every owner must be kStaticOwner or in
// [0, actor_count); an actor may own several shapes. Pure and thread-safe.
FanHits CastFan(const Fan& fan, std::span<const Shape> static_world,
                std::span<const Shape> dynamic, int actor_count);

// The slow literal reference for tests: one ray against every edge and circle, the same
// conventions as CastFan. `direction` must be a unit vector.
struct RayHit {
  double range_m = 0.0;  // +infinity when no hit within max_range_m
  int owner = kNoHit;
};
RayHit CastRayBruteForce(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                         double max_range_m, std::span<const Shape> shapes);

}  // namespace lookout::sim
