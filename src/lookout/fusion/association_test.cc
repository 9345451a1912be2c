#include "lookout/fusion/association.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>

#include "lookout/core/random.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

stereo::CartesianPoint Point(double x, double y, double variance) {
  return {Vector2d(x, y), variance * Matrix2d::Identity()};
}

FusionOptions NoDefinitionSlack() {
  FusionOptions options;
  options.point_definition_sigma_m = 0.0;
  return options;
}

TEST(AssociationTest, NearestInsideTheGateOnly) {
  const AssociationGate gate(NoDefinitionSlack());
  // sigma^2 = 0.5 + 0.5: the gate is sqrt(9.21) = 3.03 m.
  const std::vector<stereo::CartesianPoint> stereo = {Point(10, 0, 0.5), Point(30, 0, 0.5)};
  const std::vector<stereo::CartesianPoint> lidar = {Point(20, 0, 0.5), Point(11, 1, 0.5),
                                                     Point(10.5, 0, 0.5)};
  const auto pairs = AssociateStereoToLidar(stereo, lidar, gate);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].stereo, 0u);
  EXPECT_EQ(pairs[0].lidar, 2u);
  EXPECT_NEAR(pairs[0].distance_squared, 0.25, 1e-12);
}

// Two stereo objects whose nearest lidar object is the same one: one-to-one, and the pairing
// of least total distance (greedy nearest-first would pair s0-l0 and leave s1 alone).
TEST(AssociationTest, OneToOneAndOptimal) {
  const AssociationGate gate(NoDefinitionSlack());
  const std::vector<stereo::CartesianPoint> stereo = {Point(0.0, 0.0, 0.5),
                                                      Point(2.0, 0.0, 0.5)};
  const std::vector<stereo::CartesianPoint> lidar = {Point(0.9, 0.0, 0.5),
                                                     Point(-1.2, 0.0, 0.5)};
  const auto pairs = AssociateStereoToLidar(stereo, lidar, gate);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].lidar, 1u);  // s0 - l1: 1.44
  EXPECT_EQ(pairs[1].lidar, 0u);  // s1 - l0: 1.21 (greedy: s0-l0 0.81, then s1 has no partner)
}

// Walker A's camera object, its depth uncertain along the ray, and walker B's segment 0.9 m
// beyond it: in A's gate. A's own segment is missing (hidden), B's camera object too.
TEST(AssociationTest, AnotherCameraTracksPriorKeepsItsBody) {
  const AssociationGate gate(FusionOptions{});
  const stereo::CartesianPoint a_camera{Vector2d(20.0, 0.0), Vector2d(0.2, 0.0025).asDiagonal()};
  const std::vector<stereo::CartesianPoint> stereo = {a_camera};
  const std::vector<stereo::CartesianPoint> lidar = {Point(20.9, 0.1, 0.002)};
  ASSERT_EQ(AssociateStereoToLidar(stereo, lidar, gate).size(), 1u);  // paired afresh
  const PairPrior a{0, Point(20.0, 0.0, 0.01)};
  const PairPrior b{std::nullopt, Point(20.9, 0.1, 0.01)};  // B's camera object not in this frame
  // B's prior holds the segment and A's does not: not A's.
  EXPECT_TRUE(AssociateStereoToLidar(stereo, lidar, gate, std::vector<PairPrior>{a, b}).empty());
  // No other prior holds it: A's prior may be the one that was wrong, the pair stands.
  EXPECT_EQ(AssociateStereoToLidar(stereo, lidar, gate, std::vector<PairPrior>{a}).size(), 1u);
  // A's prior holds it too (the two walkers side by side): the pair stands.
  const PairPrior a_near{0, Point(20.8, 0.1, 0.01)};
  EXPECT_EQ(AssociateStereoToLidar(stereo, lidar, gate, std::vector<PairPrior>{a_near, b}).size(),
            1u);
}

TEST(AssociationTest, EmptyInputs) {
  const AssociationGate gate(FusionOptions{});
  EXPECT_TRUE(AssociateStereoToLidar({}, {Point(1, 1, 1)}, gate).empty());
  EXPECT_TRUE(AssociateStereoToLidar({Point(1, 1, 1)}, {}, gate).empty());
}

// Against a brute force over every partial one-to-one pairing of small random sets, scored as
// the solver is: the sum of d^2 over pairs plus gamma for each unpaired stereo object.
TEST(AssociationTest, MatchesBruteForce) {
  const std::uint64_t seed = 99;
  Rng rng(seed);
  const AssociationGate gate(FusionOptions{});
  for (int trial = 0; trial < 300; ++trial) {
    const auto n = static_cast<std::size_t>(rng.UniformIndex(5));
    const auto m = static_cast<std::size_t>(rng.UniformIndex(5));
    std::vector<stereo::CartesianPoint> stereo, lidar;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = rng.Uniform(0, 6), y = rng.Uniform(0, 6);
      stereo.push_back(Point(x, y, rng.Uniform(0.1, 1.0)));
    }
    for (std::size_t j = 0; j < m; ++j) {
      const double x = rng.Uniform(0, 6), y = rng.Uniform(0, 6);
      lidar.push_back(Point(x, y, rng.Uniform(0.01, 0.2)));
    }
    auto d2 = [&](std::size_t i, std::size_t j) {
      return gate.DistanceSquared(stereo[i].point_m, stereo[i].covariance, lidar[j].point_m,
                                  lidar[j].covariance);
    };
    double best = std::numeric_limits<double>::infinity();
    std::vector<bool> used(m, false);
    std::function<void(std::size_t, double)> search = [&](std::size_t i, double cost) {
      if (i == n) {
        best = std::min(best, cost);
        return;
      }
      search(i + 1, cost + gate.threshold());
      for (std::size_t j = 0; j < m; ++j) {
        if (used[j] || !gate.Accepts(d2(i, j))) continue;
        used[j] = true;
        search(i + 1, cost + d2(i, j));
        used[j] = false;
      }
    };
    search(0, 0.0);
    const auto pairs = AssociateStereoToLidar(stereo, lidar, gate);
    double cost = static_cast<double>(n - pairs.size()) * gate.threshold();
    std::vector<bool> lidar_used(m, false);
    for (const AssociationPair& p : pairs) {
      ASSERT_TRUE(gate.Accepts(p.distance_squared)) << "seed " << seed << ", trial " << trial;
      ASSERT_FALSE(lidar_used[p.lidar]) << "seed " << seed << ", trial " << trial;
      lidar_used[p.lidar] = true;
      cost += p.distance_squared;
    }
    EXPECT_NEAR(cost, best, 1e-9) << "seed " << seed << ", trial " << trial;
  }
}

}  // namespace
}  // namespace lookout::fusion
