#include "lookout/stereo/depth_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "lookout/sim/stereo_sensor.h"

namespace lookout::stereo {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

TEST(StereoDepthModelTest, DepthSigmaGrowsWithDepthSquared) {
  const StereoDepthModel model;
  // z^2 sigma_d / (f B) = 35^2 * 0.25 / 240 = 1.27604 m, with a 2 cm floor in quadrature.
  EXPECT_NEAR(model.DepthSigma(35.0), std::hypot(1225.0 * 0.25 / 240.0, 0.02), 1e-12);
  EXPECT_NEAR(model.DepthSigma(35.0), 1.2762, 1e-4);
  // Without the floor, doubling the depth multiplies the sigma by four.
  StereoDepthModel no_floor;
  no_floor.position_sigma_floor_m = 1e-12;
  EXPECT_NEAR(no_floor.DepthSigma(30.0) / no_floor.DepthSigma(15.0), 4.0, 1e-9);
  EXPECT_NEAR(model.DepthSigma(0.0), 0.02, 1e-15);
}

TEST(StereoDepthModelTest, CovarianceIsAlongAndAcrossTheRay) {
  const StereoDepthModel model;
  const Vector2d p(20.0, 20.0 * std::tan(0.5));
  const Matrix2d cov = model.PointCovariance(p);
  const Vector2d along = p.normalized();
  const Vector2d across(-along.y(), along.x());
  const double sigma_along = model.DepthSigma(p.x()) * p.norm() / p.x();
  EXPECT_NEAR(along.dot(cov * along), sigma_along * sigma_along, 1e-12);
  EXPECT_NEAR(across.dot(cov * across), std::pow(model.AcrossRaySigma(p), 2), 1e-12);
  EXPECT_NEAR(along.dot(cov * across), 0.0, 1e-12);
}

// The model must be the simulator's: the same covariance for the same parameters.
TEST(StereoDepthModelTest, MatchesTheSimulatorsNoiseModel) {
  const StereoDepthModel model;
  const sim::StereoNoiseModel simulator;
  for (const Vector2d& p : {Vector2d(3.0, 0.0), Vector2d(12.0, -5.0), Vector2d(34.0, 20.0),
                            Vector2d(25.0, 1.0)}) {
    const Matrix2d expected = simulator.CenterCovariance(p);
    EXPECT_LT((model.PointCovariance(p) - expected).norm(), 1e-12 * (1.0 + expected.norm()))
        << "at " << p.transpose();
  }
  EXPECT_EQ(model.focal_length_px, simulator.focal_length_px);
  EXPECT_EQ(model.baseline_m, simulator.baseline_m);
  EXPECT_EQ(model.disparity_sigma_px, simulator.disparity_sigma_px);
  EXPECT_EQ(model.bearing_sigma_rad, simulator.bearing_sigma_rad);
  EXPECT_EQ(model.position_sigma_floor_m, simulator.position_sigma_floor_m);
}

TEST(StereoDepthModelTest, ValidateNamesTheField) {
  StereoDepthModel model;
  model.baseline_m = 0.0;
  try {
    model.Validate();
    FAIL() << "accepted a zero baseline";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("baseline_m"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(StereoDepthModel().Validate());
}

}  // namespace
}  // namespace lookout::stereo
