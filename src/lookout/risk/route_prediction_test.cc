#include "lookout/risk/route_prediction.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::risk {
namespace {

// East 20 m, then a right turn to the south for 20 m.
const std::vector<Eigen::Vector2d> kRightTurn = {{0.0, 0.0}, {20.0, 0.0}, {20.0, -20.0}};

TEST(RoutePredictionTest, ProjectsOntoTheNearestSegment) {
  EXPECT_NEAR(ProjectOntoRoute(kRightTurn, {5.0, 0.7}), 5.0, 1e-12);
  EXPECT_NEAR(ProjectOntoRoute(kRightTurn, {20.5, -8.0}), 28.0, 1e-12);
  EXPECT_NEAR(ProjectOntoRoute(kRightTurn, {-3.0, 0.0}), 0.0, 1e-12);
  EXPECT_NEAR(ProjectOntoRoute({{1.0, 1.0}}, {4.0, 5.0}), 0.0, 1e-12);
  EXPECT_TRUE(RoutePointAt(kRightTurn, 28.0).isApprox(Eigen::Vector2d(20.0, -8.0)));
  EXPECT_TRUE(RoutePointAt(kRightTurn, 99.0).isApprox(Eigen::Vector2d(20.0, -20.0)));
  EXPECT_TRUE(RoutePointAt(kRightTurn, -1.0).isApprox(Eigen::Vector2d(0.0, 0.0)));
}

// On the route, at 10 m/s: 1 s later 10 m along it, round the corner after 2 s; the end holds.
TEST(RoutePredictionTest, FollowsTheRouteAtConstantSpeedAndStopsAtItsEnd) {
  const auto p = PredictAlongRoute(kRightTurn, {5.0, 0.0}, 10.0, 0.0, 5.0, 0.1);
  ASSERT_EQ(p.size(), 51u);
  EXPECT_TRUE(p[0].isApprox(Eigen::Vector2d(5.0, 0.0)));
  EXPECT_NEAR((p[10] - Eigen::Vector2d(15.0, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((p[20] - Eigen::Vector2d(20.0, -5.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((p[50] - Eigen::Vector2d(20.0, -20.0)).norm(), 0.0, 1e-9);
}

// Braking at 2 m/s^2 from 4 m/s stops after 2 s and 4 m, and stays there.
TEST(RoutePredictionTest, ABrakingEgoStopsAndDoesNotReverse) {
  const auto p = PredictAlongRoute(kRightTurn, {0.0, 0.0}, 4.0, -2.0, 5.0, 0.1);
  EXPECT_NEAR(p[10].x(), 3.0, 1e-9);  // 4 t - t^2 at t = 1
  EXPECT_NEAR(p[20].x(), 4.0, 1e-9);
  EXPECT_NEAR(p[50].x(), 4.0, 1e-9);
}

// An ego 1 m beside its route starts where it is and rejoins the route: the offset fades.
TEST(RoutePredictionTest, AnOffsetFromTheRouteFades) {
  const auto p = PredictAlongRoute(kRightTurn, {5.0, 1.0}, 0.0, 0.0, 5.0, 0.1);
  EXPECT_NEAR(p[0].y(), 1.0, 1e-12);
  EXPECT_NEAR(p[10].y(), std::exp(-1.0), 1e-12);
  EXPECT_LT(p[50].y(), 0.01);
}

}  // namespace
}  // namespace lookout::risk
