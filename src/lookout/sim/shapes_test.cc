#include "lookout/sim/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "lookout/core/random.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

Shape Square(double x0, double y0, double x1, double y1) {
  return Shape::Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, kStaticOwner);
}

// An L: the unit-4 square with its top-right 2 x 2 quarter cut away. Non-convex.
Shape LShape() {
  return Shape::Polygon({{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}}, kStaticOwner);
}

TEST(ShapesTest, BoxCornersFollowThePose) {
  const Shape b = Shape::Box(Pose2(10.0, 5.0, 0.0), 4.0, 2.0, 3);
  ASSERT_EQ(b.kind, Shape::Kind::kPolygon);
  ASSERT_EQ(b.vertices.size(), 4u);
  EXPECT_EQ(b.owner, 3);
  EXPECT_TRUE(b.vertices[0].isApprox(Vector2d(8.0, 4.0)));   // rear right
  EXPECT_TRUE(b.vertices[1].isApprox(Vector2d(12.0, 4.0)));  // front right
  EXPECT_TRUE(b.vertices[2].isApprox(Vector2d(12.0, 6.0)));  // front left
  EXPECT_TRUE(b.vertices[3].isApprox(Vector2d(8.0, 6.0)));   // rear left

  // Heading north: the length runs along y.
  const Shape n = Shape::Box(Pose2(0.0, 0.0, kPi / 2), 4.0, 2.0, kStaticOwner);
  EXPECT_TRUE(Contains(n, {0.0, 1.9}));
  EXPECT_TRUE(Contains(n, {0.9, -1.9}));
  EXPECT_FALSE(Contains(n, {1.1, 0.0}));
  EXPECT_FALSE(Contains(n, {0.0, 2.1}));
}

TEST(ShapesTest, PolygonContainsEitherOrientationAndItsBoundary) {
  const Shape ccw = Square(0, 0, 2, 1);
  const Shape cw = Shape::Polygon({{0, 0}, {0, 1}, {2, 1}, {2, 0}}, kStaticOwner);
  for (const Shape* s : {&ccw, &cw}) {
    EXPECT_TRUE(Contains(*s, {1.0, 0.5}));
    EXPECT_TRUE(Contains(*s, {0.0, 0.0}));  // vertex
    EXPECT_TRUE(Contains(*s, {2.0, 1.0}));  // vertex
    EXPECT_TRUE(Contains(*s, {1.0, 0.0}));  // edge
    EXPECT_TRUE(Contains(*s, {2.0, 0.5}));  // edge
    EXPECT_FALSE(Contains(*s, {2.0 + 1e-9, 0.5}));
    EXPECT_FALSE(Contains(*s, {-1.0, 0.5}));
    EXPECT_FALSE(Contains(*s, {1.0, 1.5}));
    // A ray towards +x through a vertex's height must not flip the answer.
    EXPECT_FALSE(Contains(*s, {-1.0, 1.0}));
    EXPECT_FALSE(Contains(*s, {-1.0, 0.0}));
  }
}

TEST(ShapesTest, NonConvexPolygonContainment) {
  const Shape l = LShape();
  EXPECT_TRUE(Contains(l, {1.0, 3.0}));
  EXPECT_TRUE(Contains(l, {3.0, 1.0}));
  EXPECT_TRUE(Contains(l, {3.0, 2.0}));   // the notch's floor is boundary
  EXPECT_FALSE(Contains(l, {3.0, 3.0}));  // in the notch
  EXPECT_FALSE(Contains(l, {2.5, 2.5}));
  // A ray through the reflex vertex (2, 2).
  EXPECT_TRUE(Contains(l, {1.0, 2.0}));
  EXPECT_FALSE(Contains(l, {-1.0, 2.0}));
}

TEST(ShapesTest, CircleContainsItsDisc) {
  const Shape c = Shape::Circle({1.0, -2.0}, 0.5, 4);
  EXPECT_EQ(c.owner, 4);
  EXPECT_TRUE(Contains(c, {1.0, -2.0}));
  EXPECT_TRUE(Contains(c, {1.5, -2.0}));     // boundary
  EXPECT_FALSE(Contains(c, {1.36, -1.64}));  // |r| = 0.509
  EXPECT_TRUE(Contains(c, {1.35, -1.65}));   // |r| = 0.495
}

TEST(ShapesTest, CircleCircleOverlapIsCentreDistance) {
  const Shape a = Shape::Circle({0, 0}, 1.0, kStaticOwner);
  EXPECT_TRUE(Overlap(a, Shape::Circle({2.5, 0}, 1.5, 0)));  // touching
  EXPECT_FALSE(Overlap(a, Shape::Circle({2.5, 0}, 1.49, 0)));
  EXPECT_TRUE(Overlap(a, Shape::Circle({0.1, 0}, 0.1, 0)));  // inside
  EXPECT_FALSE(Overlap(a, Shape::Circle({3, 4}, 3.99, 0)));
  EXPECT_TRUE(Overlap(a, Shape::Circle({3, 4}, 4.0, 0)));
}

TEST(ShapesTest, PolygonCircleOverlapUsesClosestPoint) {
  const Shape sq = Square(0, 0, 2, 2);
  // Off a corner: the distance is to the vertex, sqrt(2) * 0.5 = 0.7071.
  EXPECT_FALSE(Overlap(sq, Shape::Circle({2.5, 2.5}, 0.70, 0)));
  EXPECT_TRUE(Overlap(sq, Shape::Circle({2.5, 2.5}, 0.71, 0)));
  // Off an edge.
  EXPECT_FALSE(Overlap(Shape::Circle({1.0, -0.3}, 0.29, 0), sq));
  EXPECT_TRUE(Overlap(Shape::Circle({1.0, -0.3}, 0.3, 0), sq));  // touching
  // Wholly inside each other.
  EXPECT_TRUE(Overlap(sq, Shape::Circle({1.0, 1.0}, 0.1, 0)));
  EXPECT_TRUE(Overlap(sq, Shape::Circle({1.0, 1.0}, 10.0, 0)));
  // In the notch of an L: clear of the walls, though inside its bounding box.
  EXPECT_FALSE(Overlap(LShape(), Shape::Circle({3.0, 3.0}, 0.9, 0)));
  EXPECT_TRUE(Overlap(LShape(), Shape::Circle({3.0, 3.0}, 1.01, 0)));
}

TEST(ShapesTest, RotatedSquaresSeparateAtTheAnalyticDistance) {
  // A unit square and the same square turned 45 degrees, centres d apart along x: they touch
  // at d = 0.5 + sqrt(2) / 2 (the diamond's corner meets the square's side).
  const double touch = 0.5 + std::sqrt(2.0) / 2.0;
  const Shape a = Shape::Box(Pose2(0, 0, 0), 1.0, 1.0, kStaticOwner);
  for (const double d : {touch - 1e-6, touch + 1e-6}) {
    const Shape b = Shape::Box(Pose2(d, 0.0, kPi / 4), 1.0, 1.0, 0);
    EXPECT_EQ(Overlap(a, b), d < touch) << "d = " << d;
    EXPECT_EQ(Overlap(b, a), d < touch) << "d = " << d;
  }
  // Edge to edge, exactly touching.
  EXPECT_TRUE(Overlap(Square(0, 0, 1, 1), Square(1, 0.5, 2, 2)));
  EXPECT_FALSE(Overlap(Square(0, 0, 1, 1), Square(1.001, 0.5, 2, 2)));
  // One inside the other.
  EXPECT_TRUE(Overlap(Square(0, 0, 10, 10), Square(4, 4, 5, 5)));
  EXPECT_TRUE(Overlap(Square(4, 4, 5, 5), Square(0, 0, 10, 10)));
}

TEST(ShapesTest, NonConvexPolygonOverlap) {
  const Shape l = LShape();
  // A box in the notch: the bounding boxes and the convex hull overlap, the shapes do not.
  EXPECT_FALSE(Overlap(l, Square(2.5, 2.5, 3.5, 3.5)));
  EXPECT_FALSE(Overlap(Square(2.5, 2.5, 3.5, 3.5), l));
  EXPECT_TRUE(Overlap(l, Square(1.5, 2.5, 3.5, 3.5)));  // pokes into the upper arm
  EXPECT_TRUE(Overlap(l, Square(2.0, 2.0, 3.5, 3.5)));  // touches the reflex corner
  EXPECT_TRUE(Overlap(l, Square(0.5, 0.5, 1.0, 1.0)));  // wholly inside
  EXPECT_TRUE(Overlap(Square(-1, -1, 5, 5), l));        // wholly around it
}

// Slow literal references, to compare the fast paths with on random shapes.
bool ReferenceSegmentsCross(const Vector2d& a, const Vector2d& b, const Vector2d& c,
                            const Vector2d& d) {
  // Solve a + s (b - a) = c + t (d - c); random inputs are never parallel.
  const Vector2d r = b - a;
  const Vector2d q = d - c;
  const double den = r.x() * q.y() - r.y() * q.x();
  const Vector2d w = c - a;
  const double s = (w.x() * q.y() - w.y() * q.x()) / den;
  const double t = (w.x() * r.y() - w.y() * r.x()) / den;
  return s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0;
}

bool ReferencePolygonOverlap(const Shape& a, const Shape& b) {
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    for (std::size_t j = 0; j < b.vertices.size(); ++j) {
      if (ReferenceSegmentsCross(a.vertices[i], a.vertices[(i + 1) % a.vertices.size()],
                                 b.vertices[j], b.vertices[(j + 1) % b.vertices.size()])) {
        return true;
      }
    }
  }
  return Contains(a, b.vertices.front()) || Contains(b, a.vertices.front());
}

// Box against circle in the box's frame: clamp the centre to the box, compare distances.
bool ReferenceBoxCircleOverlap(const Pose2& pose, double length, double width,
                               const Vector2d& center, double radius) {
  const Vector2d local = pose.Inverse() * center;
  const Vector2d nearest(std::clamp(local.x(), -length / 2, length / 2),
                         std::clamp(local.y(), -width / 2, width / 2));
  return (local - nearest).norm() <= radius;
}

TEST(ShapesTest, RandomBoxesAndCirclesMatchTheReferences) {
  const std::uint64_t seed = 20240611;
  SCOPED_TRACE("seed " + std::to_string(seed));
  Rng rng(seed);
  int overlaps = 0;
  for (int i = 0; i < 5000; ++i) {
    const Pose2 pa{rng.Uniform(-3, 3), rng.Uniform(-3, 3), rng.Uniform(-kPi, kPi)};
    const Pose2 pb{rng.Uniform(-3, 3), rng.Uniform(-3, 3), rng.Uniform(-kPi, kPi)};
    const double la = rng.Uniform(0.5, 5), wa = rng.Uniform(0.3, 2.5);
    const double lb = rng.Uniform(0.5, 5), wb = rng.Uniform(0.3, 2.5);
    const Shape a = Shape::Box(pa, la, wa, 0);
    const Shape b = Shape::Box(pb, lb, wb, 1);
    const bool expected = ReferencePolygonOverlap(a, b);
    overlaps += expected ? 1 : 0;
    ASSERT_EQ(Overlap(a, b), expected) << "case " << i;
    ASSERT_EQ(Overlap(b, a), expected) << "case " << i;

    const Vector2d c{rng.Uniform(-4, 4), rng.Uniform(-4, 4)};
    const double r = rng.Uniform(0.05, 1.5);
    ASSERT_EQ(Overlap(a, Shape::Circle(c, r, 2)), ReferenceBoxCircleOverlap(pa, la, wa, c, r))
        << "case " << i;

    const Vector2d p{rng.Uniform(-6, 6), rng.Uniform(-6, 6)};
    const Vector2d local = pa.Inverse() * p;
    ASSERT_EQ(Contains(a, p), std::abs(local.x()) <= la / 2 && std::abs(local.y()) <= wa / 2)
        << "case " << i;
  }
  // Both answers must be well represented for the comparison to mean anything.
  EXPECT_GT(overlaps, 1000);
  EXPECT_LT(overlaps, 4000);
}

TEST(ShapesTest, BoundingBoxes) {
  const Aabb c = BoundingBox(Shape::Circle({1, 2}, 0.5, 0));
  EXPECT_TRUE(c.min.isApprox(Vector2d(0.5, 1.5)));
  EXPECT_TRUE(c.max.isApprox(Vector2d(1.5, 2.5)));
  const Aabb l = BoundingBox(LShape());
  EXPECT_EQ(l.min, Vector2d(0, 0));
  EXPECT_EQ(l.max, Vector2d(4, 4));
  EXPECT_TRUE(l.Intersects(c));
  EXPECT_FALSE(l.Intersects(BoundingBox(Shape::Circle({5, 5}, 0.9, 0))));
}

}  // namespace
}  // namespace lookout::sim
