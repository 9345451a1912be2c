#include "lookout/sim/raycast.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/core/random.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Shapes are built field by field here, so these tests depend on nothing but the ray caster.
Shape MakeCircle(const Vector2d& center, double radius, int owner) {
  return Shape{Shape::Kind::kCircle, {}, center, radius, owner};
}

Shape MakePolygon(std::vector<Vector2d> vertices, int owner) {
  return Shape{Shape::Kind::kPolygon, std::move(vertices), Vector2d::Zero(), 0.0, owner};
}

Shape MakeBox(const Vector2d& center, double yaw, double length, double width, int owner) {
  const Vector2d ax(std::cos(yaw) * length / 2.0, std::sin(yaw) * length / 2.0);
  const Vector2d ay(-std::sin(yaw) * width / 2.0, std::cos(yaw) * width / 2.0);
  return MakePolygon({center + ax + ay, center - ax + ay, center - ax - ay, center + ax - ay},
                     owner);
}

Fan MakeFan(const Vector2d& origin, double min_deg, double increment_deg, int count,
            double max_range_m) {
  return Fan{origin, DegToRad(min_deg), DegToRad(increment_deg), count, max_range_m};
}

TEST(RaycastTest, BeamDirectionsAreUnitVectorsAtTheBeamAngles) {
  const Fan fan = MakeFan(Vector2d::Zero(), -179.9, 0.25, 1440, 150.0);
  for (int i = 0; i < fan.count; ++i) {
    const Vector2d d = fan.BeamDirection(i);
    EXPECT_NEAR(d.x(), std::cos(fan.BeamAngle(i)), 1e-14) << "beam " << i;
    EXPECT_NEAR(d.y(), std::sin(fan.BeamAngle(i)), 1e-14) << "beam " << i;
  }
}

TEST(RaycastTest, WallAtKnownDistance) {
  // The face x = 10 of a thick wall: beam at angle a hits at 10 / cos(a).
  const std::vector<Shape> world = {
      MakePolygon({{10, -50}, {11, -50}, {11, 50}, {10, 50}}, kStaticOwner)};
  const Fan fan = MakeFan(Vector2d::Zero(), -60.0, 0.5, 241, 150.0);
  const FanHits hits = CastFan(fan, world, {}, 0);
  ASSERT_EQ(hits.range_m.size(), 241u);
  for (int i = 0; i < fan.count; ++i) {
    const auto b = static_cast<std::size_t>(i);
    EXPECT_NEAR(hits.range_m[b], 10.0 / std::cos(fan.BeamAngle(i)), 1e-9) << "beam " << i;
    EXPECT_EQ(hits.owner[b], kStaticOwner);
  }
}

TEST(RaycastTest, CircleAtKnownDistanceAndBearing) {
  const double d = 20.0, r = 1.5, bearing = DegToRad(30.0);
  const Vector2d origin(3.0, -2.0);
  const Vector2d center = origin + d * Vector2d(std::cos(bearing), std::sin(bearing));
  const std::vector<Shape> actors = {MakeCircle(center, r, 0)};
  const Fan fan = MakeFan(origin, 0.0, 0.1, 601, 150.0);
  const FanHits hits = CastFan(fan, {}, actors, 1);
  int hit_count = 0;
  for (int i = 0; i < fan.count; ++i) {
    const auto b = static_cast<std::size_t>(i);
    const double off_axis = fan.BeamAngle(i) - bearing;
    const double offset = d * std::sin(off_axis);  // miss distance of the beam's line
    if (std::abs(off_axis) < std::asin(r / d) - 1e-6) {
      ++hit_count;
      EXPECT_NEAR(hits.range_m[b], d * std::cos(off_axis) - std::sqrt(r * r - offset * offset),
                  1e-9) << "beam " << i;
      EXPECT_EQ(hits.owner[b], 0);
    } else if (std::abs(off_axis) > std::asin(r / d) + 1e-6) {
      EXPECT_EQ(hits.range_m[b], kInf) << "beam " << i;
      EXPECT_EQ(hits.owner[b], kNoHit);
    }
  }
  EXPECT_GT(hit_count, 0);
  EXPECT_EQ(hits.beams_intersecting[0], hit_count);
  EXPECT_EQ(hits.beams_nearest[0], hit_count);
  EXPECT_DOUBLE_EQ(hits.VisibleFraction(0), 1.0);
}

TEST(RaycastTest, MaxRangeIsInclusiveAndFartherHitsAreDropped) {
  const std::vector<Shape> world = {MakePolygon({{10, -1}, {12, -1}, {12, 1}, {10, 1}}, 0)};
  const Fan fan = MakeFan(Vector2d::Zero(), 0.0, 1.0, 1, 10.0);
  EXPECT_DOUBLE_EQ(CastFan(fan, {}, world, 1).range_m[0], 10.0);
  Fan shorter = fan;
  shorter.max_range_m = 9.999;
  const FanHits hits = CastFan(shorter, {}, world, 1);
  EXPECT_EQ(hits.range_m[0], kInf);
  EXPECT_EQ(hits.beams_intersecting[0], 0);
  EXPECT_DOUBLE_EQ(hits.VisibleFraction(0), 0.0);
}

TEST(RaycastTest, ActorBehindWallIsOccluded) {
  const std::vector<Shape> world = {MakeBox({10.0, 0.0}, 0.0, 1.0, 10.0, kStaticOwner)};
  const std::vector<Shape> actors = {MakeBox({20.0, 0.0}, 0.3, 4.5, 1.8, 0),
                                     MakeCircle({20.0, 14.0}, 0.3, 1)};
  const Fan fan = MakeFan(Vector2d::Zero(), -80.0, 0.25, 641, 150.0);
  const FanHits hits = CastFan(fan, world, actors, 2);
  for (const int owner : hits.owner) EXPECT_NE(owner, 0);
  EXPECT_GT(hits.beams_intersecting[0], 5);
  EXPECT_EQ(hits.beams_nearest[0], 0);
  EXPECT_DOUBLE_EQ(hits.VisibleFraction(0), 0.0);
  // The pedestrian at bearing 35 deg is clear of the wall (which ends at 27.8 deg).
  EXPECT_GT(hits.beams_nearest[1], 0);
  EXPECT_DOUBLE_EQ(hits.VisibleFraction(1), 1.0);
}

TEST(RaycastTest, PartialOcclusionGivesFractionBetweenZeroAndOne) {
  // A pedestrian half behind a pole-like post: some beams reach it, some do not.
  const std::vector<Shape> world = {MakeCircle({5.0, 0.25}, 0.3, kStaticOwner)};
  const std::vector<Shape> actors = {MakeCircle({10.0, 0.0}, 0.5, 0)};
  const Fan fan = MakeFan(Vector2d::Zero(), -10.0, 0.05, 401, 150.0);
  const FanHits hits = CastFan(fan, world, actors, 1);
  EXPECT_GT(hits.VisibleFraction(0), 0.1);
  EXPECT_LT(hits.VisibleFraction(0), 0.9);
  EXPECT_LE(hits.beams_nearest[0], hits.beams_intersecting[0]);
}

TEST(RaycastTest, FieldOfViewEdgesAreInclusive) {
  // 160 deg at 0.25 deg: 641 beams, the last one exactly at +80 deg.
  const Fan fan = MakeFan(Vector2d::Zero(), -80.0, 0.25, 641, 150.0);
  EXPECT_NEAR(fan.BeamAngle(640), DegToRad(80.0), 1e-12);
  const auto on_beam = [&](double deg, double range) {
    return Vector2d(range * std::cos(DegToRad(deg)), range * std::sin(DegToRad(deg)));
  };
  // Thin posts on the two edge beams: both hit. Posts 0.2 deg outside (radius subtends
  // 0.057 deg): never hit, not even counted as intersecting.
  const std::vector<Shape> actors = {
      MakeCircle(on_beam(80.0, 10.0), 0.01, 0), MakeCircle(on_beam(-80.0, 10.0), 0.01, 1),
      MakeCircle(on_beam(80.2, 10.0), 0.01, 2), MakeCircle(on_beam(-80.2, 10.0), 0.01, 3)};
  const FanHits hits = CastFan(fan, {}, actors, 4);
  EXPECT_EQ(hits.owner[640], 0);
  EXPECT_NEAR(hits.range_m[640], 9.99, 1e-9);
  EXPECT_EQ(hits.owner[0], 1);
  EXPECT_NEAR(hits.range_m[0], 9.99, 1e-9);
  EXPECT_EQ(hits.beams_intersecting[2], 0);
  EXPECT_EQ(hits.beams_intersecting[3], 0);
  int returns = 0;
  for (const double r : hits.range_m) returns += std::isfinite(r) ? 1 : 0;
  EXPECT_EQ(returns, 2);
}

TEST(RaycastTest, WrapsAroundPlusMinusPi) {
  // A fan looking backwards (170 to 190 deg) and a box straddling the -x axis.
  const std::vector<Shape> world = {MakeBox({-15.0, 0.0}, 0.0, 2.0, 4.0, kStaticOwner)};
  for (const double min_deg : {170.0, -190.0, 530.0}) {
    const Fan fan = MakeFan(Vector2d::Zero(), min_deg, 0.25, 81, 150.0);
    const FanHits hits = CastFan(fan, world, {}, 0);
    int returns = 0;
    for (int i = 0; i < fan.count; ++i) {
      const auto b = static_cast<std::size_t>(i);
      const double off_axis = WrapAngle(fan.BeamAngle(i) - kPi);
      // The near face x = -14 spans +-2 m: +-8.13 deg.
      if (std::abs(off_axis) < std::atan2(2.0, 14.0) - 1e-6) {
        ++returns;
        EXPECT_NEAR(hits.range_m[b], 14.0 / std::cos(off_axis), 1e-9)
            << "min " << min_deg << " beam " << i;
      } else if (std::abs(off_axis) > std::atan2(2.0, 14.0) + 1e-6) {
        EXPECT_EQ(hits.range_m[b], kInf) << "min " << min_deg << " beam " << i;
      }
    }
    EXPECT_EQ(returns, 65) << "min " << min_deg;  // beams at -8 .. +8 deg
  }
  // A circle exactly at bearing pi seen by a forward-looking full fan from -180 deg.
  const std::vector<Shape> pole = {MakeCircle({-10.0, 0.0}, 0.5, kStaticOwner)};
  const Fan full = MakeFan(Vector2d::Zero(), -180.0, 1.0, 360, 150.0);
  const FanHits hits = CastFan(full, pole, {}, 0);
  EXPECT_NEAR(hits.range_m[0], 9.5, 1e-9);      // -180 deg
  const double off = 10.0 * std::sin(DegToRad(1.0));  // +179 deg misses the axis by this
  EXPECT_NEAR(hits.range_m[359], 10.0 * std::cos(DegToRad(1.0)) - std::sqrt(0.25 - off * off),
              1e-9);
  EXPECT_NEAR(hits.range_m[1], hits.range_m[359], 1e-9);
}

TEST(RaycastTest, BeamsAlongEdgesAndThroughVerticesHit) {
  // Box [5, 10] x [0, 2]: the beam at 0 deg runs along its bottom edge, and the beam through
  // the corner (5, 2) touches one vertex.
  const std::vector<Shape> world = {MakePolygon({{5, 0}, {10, 0}, {10, 2}, {5, 2}}, 0)};
  const double corner_deg = RadToDeg(std::atan2(2.0, 5.0));
  const Fan along = MakeFan(Vector2d::Zero(), 0.0, 1.0, 1, 150.0);
  EXPECT_DOUBLE_EQ(CastFan(along, {}, world, 1).range_m[0], 5.0);
  const Fan corner = MakeFan(Vector2d::Zero(), corner_deg, 1.0, 1, 150.0);
  EXPECT_NEAR(CastFan(corner, {}, world, 1).range_m[0], std::hypot(5.0, 2.0), 1e-9);
  // Both agree with the reference.
  for (const Fan& f : {along, corner}) {
    const RayHit ref = CastRayBruteForce(f.origin_m, f.BeamDirection(0), 150.0, world);
    EXPECT_EQ(ref.range_m, CastFan(f, {}, world, 1).range_m[0]);
  }
}

TEST(RaycastTest, OriginInsideAShapeIgnoresThatShape) {
  const std::vector<Shape> world = {MakeBox(Vector2d::Zero(), 0.0, 4.0, 2.0, kStaticOwner),
                                    MakeCircle({30.0, 0.0}, 1.0, kStaticOwner)};
  const std::vector<Shape> actors = {MakeCircle({0.5, 0.0}, 1.0, 0)};
  const Fan fan = MakeFan(Vector2d::Zero(), -5.0, 1.0, 11, 150.0);
  const FanHits hits = CastFan(fan, world, actors, 1);
  EXPECT_DOUBLE_EQ(hits.range_m[5], 29.0);  // the box and the actor around it are ignored
  EXPECT_EQ(hits.beams_intersecting[0], 0);
  EXPECT_DOUBLE_EQ(hits.VisibleFraction(0), 0.0);
  // On the boundary counts as inside.
  const Fan on_edge = MakeFan({2.0, 0.0}, -5.0, 1.0, 11, 150.0);
  EXPECT_DOUBLE_EQ(CastFan(on_edge, world, {}, 0).range_m[5], 27.0);
}

TEST(RaycastTest, TiesGoToTheLowerOwner) {
  // An actor's face flush with a wall's face: the static world wins the tie.
  const std::vector<Shape> world = {MakePolygon({{10, -1}, {11, -1}, {11, 1}, {10, 1}}, -1)};
  const std::vector<Shape> actors = {MakePolygon({{10, -1}, {12, -1}, {12, 1}, {10, 1}}, 0)};
  const Fan fan = MakeFan(Vector2d::Zero(), 0.0, 1.0, 1, 150.0);
  const FanHits hits = CastFan(fan, world, actors, 1);
  EXPECT_EQ(hits.owner[0], kStaticOwner);
  EXPECT_EQ(CastFan(fan, actors, world, 1).owner[0], kStaticOwner);  // order does not matter
}

TEST(RaycastTest, ActorWithSeveralShapesCountsEachBeamOnce) {
  // A tractor and its trailer as two boxes of one actor, given out of order.
  const std::vector<Shape> actors = {MakeBox({20.0, 0.0}, 0.0, 4.0, 2.5, 1),
                                     MakeBox({14.0, 5.0}, 0.0, 1.0, 1.0, 0),
                                     MakeBox({25.0, 0.0}, 0.0, 4.0, 2.5, 1)};
  const Fan fan = MakeFan(Vector2d::Zero(), -30.0, 0.1, 601, 150.0);
  const FanHits hits = CastFan(fan, {}, actors, 2);
  int beams_on_1 = 0;
  for (int i = 0; i < fan.count; ++i) {
    const RayHit h = CastRayBruteForce(fan.origin_m, fan.BeamDirection(i), 150.0,
                                       std::span(actors).subspan(0, 1));
    beams_on_1 += std::isfinite(h.range_m) ? 1 : 0;
  }
  EXPECT_EQ(hits.beams_intersecting[1], beams_on_1);
  EXPECT_EQ(hits.beams_nearest[1], beams_on_1);
}

// A random simple polygon: a star-shaped ring (often non-convex) around a centre.
Shape RandomStar(Rng& rng, const Vector2d& center, int owner) {
  const int n = 3 + static_cast<int>(rng.UniformIndex(6));
  std::vector<Vector2d> ring;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * kPi * (j + rng.Uniform(0.1, 0.9)) / n;
    const double r = rng.Uniform(0.5, 6.0);
    ring.push_back(center + r * Vector2d(std::cos(a), std::sin(a)));
  }
  if (rng.Bernoulli(0.5)) std::reverse(ring.begin(), ring.end());
  return MakePolygon(std::move(ring), owner);
}

TEST(RaycastTest, FanAgreesWithBruteForceOnRandomWorlds) {
  int actor_returns = 0;  // keeps the test honest: the random worlds must be hit
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Rng rng(DeriveSeed(seed, "raycast_test", 0));
    const auto random_point = [&](double half) {
      return Vector2d{rng.Uniform(-half, half), rng.Uniform(-half, half)};
    };
    std::vector<Shape> world;
    for (int j = 0, n = static_cast<int>(rng.UniformIndex(12)); j < n; ++j) {
      const Vector2d c = random_point(60.0);
      if (rng.Bernoulli(0.3)) {
        world.push_back(MakeCircle(c, rng.Uniform(0.05, 2.0), kStaticOwner));
      } else if (rng.Bernoulli(0.5)) {
        world.push_back(RandomStar(rng, c, kStaticOwner));
      } else {
        const double yaw = rng.Uniform(-kPi, kPi), length = rng.Uniform(0.5, 20.0);
        world.push_back(MakeBox(c, yaw, length, rng.Uniform(0.5, 20.0), kStaticOwner));
      }
    }
    const int actor_count = static_cast<int>(rng.UniformIndex(10));
    std::vector<Shape> actors;
    for (int a = 0; a < actor_count; ++a) {
      const Vector2d c = random_point(50.0);
      if (rng.Bernoulli(0.3)) {
        actors.push_back(MakeCircle(c, rng.Uniform(0.2, 0.5), a));
      } else {
        const double yaw = rng.Uniform(-kPi, kPi), length = rng.Uniform(1.5, 8.0);
        actors.push_back(MakeBox(c, yaw, length, rng.Uniform(0.6, 2.5), a));
      }
      if (rng.Bernoulli(0.2)) actors.push_back(RandomStar(rng, random_point(50.0), a));
    }
    const double increment = DegToRad(rng.Uniform(0.05, 2.0));
    const int max_count = static_cast<int>(std::floor(2.0 * kPi / increment - 1e-6));
    const Fan fan{random_point(30.0), rng.Uniform(-2.0 * kPi, 2.0 * kPi), increment,
                  1 + static_cast<int>(rng.UniformIndex(static_cast<std::uint64_t>(max_count))),
                  rng.Uniform(5.0, 120.0)};
    const FanHits hits = CastFan(fan, world, actors, actor_count);

    std::vector<Shape> all = world;
    all.insert(all.end(), actors.begin(), actors.end());
    std::vector<int> intersecting(static_cast<std::size_t>(actor_count), 0);
    std::vector<int> nearest(static_cast<std::size_t>(actor_count), 0);
    for (int i = 0; i < fan.count; ++i) {
      const auto b = static_cast<std::size_t>(i);
      const Vector2d dir = fan.BeamDirection(i);
      const RayHit ref = CastRayBruteForce(fan.origin_m, dir, fan.max_range_m, all);
      // Equal up to rounding: the fan skips back faces, whose hits at a shared vertex may
      // differ from the front face's in the last bit.
      if (std::isinf(ref.range_m)) {
        ASSERT_EQ(hits.range_m[b], kInf) << "beam " << i;
      } else {
        ASSERT_NEAR(hits.range_m[b], ref.range_m, 1e-9) << "beam " << i;
      }
      ASSERT_EQ(hits.owner[b], ref.owner) << "beam " << i;
      if (ref.owner >= 0) ++nearest[static_cast<std::size_t>(ref.owner)];
      actor_returns += ref.owner >= 0 ? 1 : 0;
      for (int a = 0; a < actor_count; ++a) {
        std::vector<Shape> alone;
        for (const Shape& s : actors) {
          if (s.owner == a) alone.push_back(s);
        }
        if (std::isfinite(CastRayBruteForce(fan.origin_m, dir, fan.max_range_m, alone).range_m)) {
          ++intersecting[static_cast<std::size_t>(a)];
        }
      }
    }
    EXPECT_EQ(hits.beams_intersecting, intersecting);
    EXPECT_EQ(hits.beams_nearest, nearest);
  }
  EXPECT_GT(actor_returns, 1000);
}

// Grid-aligned worlds seen from grid points by fans with beams at multiples of 45 deg:
// beams along edges and exactly through vertices, the degenerate cases, on purpose.
TEST(RaycastTest, FanAgreesWithBruteForceOnDegenerateAlignments) {
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Rng rng(DeriveSeed(seed, "raycast_test_grid", 0));
    const auto grid = [&](int half) {
      return static_cast<double>(static_cast<int>(rng.UniformIndex(
                 static_cast<std::uint64_t>(2 * half + 1))) - half);
    };
    std::vector<Shape> shapes;
    const int actor_count = 6;
    for (int j = 0; j < 12; ++j) {
      const double x = grid(20), y = grid(20);
      const double w = 1.0 + grid(2) + 2.0, h = 1.0 + grid(2) + 2.0;
      const int owner = j < actor_count ? j : kStaticOwner;
      shapes.push_back(MakePolygon({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, owner));
    }
    const Fan fan{Vector2d(grid(10), grid(10)), -kPi, DegToRad(0.25), 1440, 40.0};
    const FanHits hits = CastFan(fan, shapes, {}, actor_count);
    for (int i = 0; i < fan.count; ++i) {
      const auto b = static_cast<std::size_t>(i);
      const RayHit ref = CastRayBruteForce(fan.origin_m, fan.BeamDirection(i), 40.0, shapes);
      ASSERT_EQ(hits.owner[b], ref.owner) << "beam " << i;
      if (std::isinf(ref.range_m)) {
        ASSERT_EQ(hits.range_m[b], kInf) << "beam " << i;
      } else {
        ASSERT_NEAR(hits.range_m[b], ref.range_m, 1e-9) << "beam " << i;
      }
    }
  }
}

}  // namespace
}  // namespace lookout::sim
