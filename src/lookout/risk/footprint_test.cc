#include "lookout/risk/footprint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>
#include <numbers>

#include "lookout/core/random.h"

namespace lookout::risk {
namespace {

// The slow literal reference: for two convex sets the signed distance is minus the least
// overlap of their projections over every direction (the separating axis theorem in its
// general form: apart, the widest gap between projections is the distance; overlapping, the
// least overlap is the penetration depth). The overlap is a piecewise smooth function of the
// direction whose least value can sit at a kink, so a grid of directions errs to first order:
// a coarse grid finds the basins, and a fine grid about the best two finds their bottoms.
double ReferenceSeparation(const Footprint& a, const Footprint& b) {
  const auto half_extent = [](const Footprint& f, const Eigen::Vector2d& n) {
    const Eigen::Vector2d u(std::cos(f.yaw_rad), std::sin(f.yaw_rad));
    const Eigen::Vector2d v(-u.y(), u.x());
    return f.half_length_m * std::abs(u.dot(n)) + f.half_width_m * std::abs(v.dot(n)) +
           f.radius_m;
  };
  const auto overlap = [&](double theta) {
    const Eigen::Vector2d n(std::cos(theta), std::sin(theta));
    return half_extent(a, n) + half_extent(b, n) - std::abs((b.centre_m - a.centre_m).dot(n));
  };
  constexpr int kCoarse = 3600, kFine = 4000;
  constexpr double kStep = std::numbers::pi / kCoarse;
  std::vector<std::pair<double, double>> minima;  // (overlap, direction) of coarse local minima
  std::vector<double> coarse(kCoarse);
  for (int k = 0; k < kCoarse; ++k) coarse[static_cast<std::size_t>(k)] = overlap(k * kStep);
  for (int k = 0; k < kCoarse; ++k) {
    const auto at = [&](int i) {
      return coarse[static_cast<std::size_t>((i + kCoarse) % kCoarse)];
    };
    if (at(k) <= at(k - 1) && at(k) <= at(k + 1)) minima.emplace_back(at(k), k * kStep);
  }
  std::sort(minima.begin(), minima.end());
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < std::min<std::size_t>(minima.size(), 2); ++m) {
    for (int k = -kFine; k <= kFine; ++k) {
      least = std::min(least, overlap(minima[m].second + kStep * k / kFine));
    }
  }
  return -least;
}

TEST(FootprintTest, BoxesSideBySideAreTheirGapApart) {
  // Two cars in adjacent lanes, 3.5 m apart, widths 1.9 and 1.8: 1.65 m between their sides.
  const Footprint ego = Footprint::Box({0.0, 0.0}, 0.0, 4.6, 1.9);
  const Footprint car = Footprint::Box({1.0, 3.5}, std::numbers::pi, 4.5, 1.8);
  EXPECT_NEAR(Separation(ego, car), 1.65, 1e-12);
  // Their circles of half the diagonal (2.47 and 2.42 m) overlap.
  const Footprint ego_circle = Footprint::Circle({0.0, 0.0}, ego.BoundingRadius());
  const Footprint car_circle = Footprint::Circle({1.0, 3.5}, car.BoundingRadius());
  EXPECT_LT(Separation(ego_circle, car_circle), 0.0);
}

TEST(FootprintTest, CornerToCornerIsTheirDiagonalDistance) {
  const Footprint a = Footprint::Box({0.0, 0.0}, 0.0, 2.0, 2.0);
  const Footprint b = Footprint::Box({5.0, 6.0}, 0.0, 2.0, 2.0);
  EXPECT_NEAR(Separation(a, b), std::hypot(3.0, 4.0), 1e-12);
  // A square turned by 45 degrees points its corner at the other's side.
  const Footprint diamond = Footprint::Box({5.0, 0.0}, std::numbers::pi / 4.0, 2.0, 2.0);
  EXPECT_NEAR(Separation(a, diamond), 4.0 - std::sqrt(2.0), 1e-12);
}

TEST(FootprintTest, OverlapIsMinusThePenetrationDepth) {
  const Footprint a = Footprint::Box({0.0, 0.0}, 0.0, 4.0, 2.0);
  const Footprint b = Footprint::Box({3.0, 0.5}, 0.0, 4.0, 2.0);
  EXPECT_NEAR(Separation(a, b), -1.0, 1e-12);  // 1 m of overlap along x, 1.5 m along y
  // Margins add to the depth.
  const Footprint rounded = Footprint::Box({3.0, 0.5}, 0.0, 4.0, 2.0, 0.2);
  EXPECT_NEAR(Separation(a, rounded), -1.2, 1e-12);
}

TEST(FootprintTest, CircleAndBox) {
  const Footprint car = Footprint::Box({0.0, 0.0}, std::numbers::pi / 2.0, 4.5, 1.8);
  // A walker 2 m beside the car's long side (x = 0.9), then off its front corner.
  EXPECT_NEAR(Separation(car, Footprint::Circle({2.9 + 0.3, 0.0}, 0.3)), 2.0, 1e-12);
  EXPECT_NEAR(Separation(car, Footprint::Circle({0.9 + 3.0, 2.25 + 4.0}, 0.3)), 5.0 - 0.3, 1e-12);
  EXPECT_NEAR(Separation(car, Footprint::Circle({0.5, 0.0}, 0.3)), -0.4 - 0.3, 1e-12);
  // Two circles: centre distance minus the radii.
  EXPECT_NEAR(Separation(Footprint::Circle({0.0, 0.0}, 1.0), Footprint::Circle({3.0, 4.0}, 1.5)),
              2.5, 1e-12);
}

// Random boxes, circles and margins against the literal reference.
TEST(FootprintTest, MatchesTheReferenceOnRandomPairs) {
  constexpr std::uint64_t kSeed = 20261202;
  Rng rng(kSeed);
  const auto random_footprint = [&rng] {
    const bool circle = rng.Uniform(0.0, 1.0) < 0.25;
    const Eigen::Vector2d centre{rng.Uniform(-4.0, 4.0), rng.Uniform(-4.0, 4.0)};
    if (circle) return Footprint::Circle(centre, rng.Uniform(0.1, 1.5));
    const double yaw_rad = rng.Uniform(-4.0, 4.0), length_m = rng.Uniform(0.3, 6.0);
    const double width_m = rng.Uniform(0.3, 3.0), margin_m = rng.Uniform(0.0, 0.5);
    return Footprint::Box(centre, yaw_rad, length_m, width_m, margin_m);
  };
  int overlapping = 0;
  for (int i = 0; i < 200; ++i) {
    const Footprint a = random_footprint(), b = random_footprint();
    const double s = Separation(a, b);
    // The fine grid's spacing (pi / 3600 / 4000) times the footprints' size (under 15 m)
    // bounds the reference's error to about 3e-6 m.
    EXPECT_NEAR(s, ReferenceSeparation(a, b), 1e-5) << "pair " << i << ", seed " << kSeed;
    EXPECT_EQ(Overlap(a, b, Eigen::Vector2d::Zero()), s <= 0.0) << "pair " << i;
    const Eigen::Vector2d offset{rng.Uniform(-3.0, 3.0), rng.Uniform(-3.0, 3.0)};
    Footprint moved = b;
    moved.centre_m += offset;
    EXPECT_EQ(Overlap(a, b, offset), Separation(a, moved) <= 0.0) << "pair " << i;
    if (s <= 0.0) ++overlapping;
  }
  EXPECT_GT(overlapping, 25) << "the draws should overlap often enough to test depths";
}

}  // namespace
}  // namespace lookout::risk
