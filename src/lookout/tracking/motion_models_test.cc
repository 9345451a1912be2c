#include "lookout/tracking/motion_models.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

TEST(MotionModels, ConstantVelocityMovesOnAStraightLine) {
  const Eigen::Vector4d x(1.0, 2.0, 3.0, -4.0);
  const Transition t = Propagate(ConstantVelocity(1.0), x, 0.5);
  EXPECT_TRUE(t.x.isApprox(Eigen::Vector4d(2.5, 0.0, 3.0, -4.0)));
}

TEST(MotionModels, ConstantAccelerationFollowsAParabola) {
  Eigen::VectorXd x(6);
  x << 0.0, 0.0, 1.0, 0.0, 2.0, -1.0;
  const Transition t = Propagate(ConstantAcceleration(1.0), x, 3.0);
  // x = v t + a t^2 / 2, v = v0 + a t.
  EXPECT_NEAR(t.x(kX), 3.0 + 9.0, 1e-12);
  EXPECT_NEAR(t.x(kY), -4.5, 1e-12);
  EXPECT_NEAR(t.x(kVx), 7.0, 1e-12);
  EXPECT_NEAR(t.x(kVy), -3.0, 1e-12);
  EXPECT_EQ(t.x(kAx), 2.0);
}

// A target at speed v turning at w runs on a circle of radius v / w: after a quarter period it
// has turned 90 degrees and moved by (r, r) from the start, for a left turn heading east.
TEST(MotionModels, CoordinatedTurnRunsOnTheAnalyticCircle) {
  const double v = 10.0, w = 0.2, r = v / w;
  const double quarter = std::numbers::pi / 2.0 / w;
  for (const int steps : {1, 7}) {
    Eigen::VectorXd x = Eigen::Vector4d(0.0, 0.0, v, 0.0);
    for (int i = 0; i < steps; ++i) x = Propagate(CoordinatedTurn(w, 1.0), x, quarter / steps).x;
    EXPECT_NEAR(x(kX), r, 1e-9);
    EXPECT_NEAR(x(kY), r, 1e-9);
    EXPECT_NEAR(x(kVx), 0.0, 1e-9);
    EXPECT_NEAR(x(kVy), v, 1e-9);
    // A right turn mirrors it.
    Eigen::VectorXd y = Eigen::Vector4d(0.0, 0.0, v, 0.0);
    for (int i = 0; i < steps; ++i) y = Propagate(CoordinatedTurn(-w, 1.0), y, quarter / steps).x;
    EXPECT_NEAR(y(kY), -r, 1e-9);
  }
}

TEST(MotionModels, TurnWithAVanishingRateIsConstantVelocity) {
  EXPECT_TRUE(CoordinatedTurnMatrix(1e-12, 2.0).isApprox(ConstantVelocityMatrix(2.0), 1e-10));
  EXPECT_TRUE(CoordinatedTurnMatrix(1e-5, 2.0).isApprox(ConstantVelocityMatrix(2.0), 1e-4));
}

// The EKF Jacobian of the turn-rate model against central differences of f.
TEST(MotionModels, TurnRateJacobianMatchesFiniteDifferences) {
  const MotionModel model = CoordinatedTurnRate(1.0, 1e-3);
  for (const double w : {0.3, -0.05, 0.0, 1e-9}) {
    Eigen::VectorXd x(5);
    x << 3.0, -2.0, 7.0, 4.0, w;
    const Transition t = Propagate(model, x, 2.5);
    Eigen::MatrixXd numeric(5, 5);
    const double h = 1e-6;
    for (int k = 0; k < 5; ++k) {
      Eigen::VectorXd up = x, down = x;
      up(k) += h;
      down(k) -= h;
      numeric.col(k) = (Propagate(model, up, 2.5).x - Propagate(model, down, 2.5).x) / (2.0 * h);
    }
    EXPECT_TRUE(t.F.isApprox(numeric, 1e-6)) << "w = " << w << "\n" << t.F << "\n\n" << numeric;
  }
}

// Q = integral over [0, dt] of F(s) G q G' F(s)' ds, by a fine midpoint sum: the slow literal
// reference of the closed forms.
TEST(MotionModels, ProcessNoiseIsTheIntegralOfTheDrivingNoise) {
  const double dt = 1.7, q = 0.8;
  const int n = 20000;
  Eigen::Matrix4d cv = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 6, 6> ca = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < n; ++i) {
    const double s = (static_cast<double>(i) + 0.5) * dt / n;
    Eigen::Matrix<double, 4, 2> g4 = Eigen::Matrix<double, 4, 2>::Zero();
    g4(0, 0) = g4(1, 1) = s;
    g4(2, 0) = g4(3, 1) = 1.0;
    cv += g4 * q * g4.transpose() * (dt / n);
    Eigen::Matrix<double, 6, 2> g6 = Eigen::Matrix<double, 6, 2>::Zero();
    g6(0, 0) = g6(1, 1) = s * s / 2.0;
    g6(2, 0) = g6(3, 1) = s;
    g6(4, 0) = g6(5, 1) = 1.0;
    ca += g6 * q * g6.transpose() * (dt / n);
  }
  EXPECT_TRUE(WhiteAccelerationNoise(dt, q).isApprox(cv, 1e-7));
  EXPECT_TRUE(WhiteJerkNoise(dt, q).isApprox(ca, 1e-7));
}

TEST(MotionModels, StateComponentsNameTheCanonicalState) {
  EXPECT_EQ(StateSize(MotionKind::kConstantVelocity), 4);
  EXPECT_EQ(StateSize(MotionKind::kConstantAcceleration), 6);
  EXPECT_EQ(StateSize(MotionKind::kCoordinatedTurn), 4);
  EXPECT_EQ(StateComponents(MotionKind::kCoordinatedTurnRate).back(), kOmega);
}

TEST(MotionModels, ValidateNamesTheField) {
  try {
    CoordinatedTurn(0.0, 1.0).Validate("opts", "imm.models[2]");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "imm.models[2].turn_rate_rad_s");
  }
  EXPECT_THROW(ConstantVelocity(-1.0).Validate("opts", "m"), InputError);
  EXPECT_NO_THROW(CoordinatedTurn(0.1, 1.0).Validate("opts", "m"));
}

}  // namespace
}  // namespace lookout::tracking
