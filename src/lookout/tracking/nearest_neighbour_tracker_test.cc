#include "lookout/tracking/nearest_neighbour_tracker.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"
#include "lookout/core/chi_square.h"

namespace lookout::tracking {
namespace {

TrackerOptions Options() {
  TrackerOptions o;
  o.imm = FourModelImm(0.5, 0.05, 0.1, 0.5, 0.9);
  o.measurement_std_m = 2.0;
  return o;
}

ImmState Start(const TrackerOptions& o) {
  return InitImm(o.imm, {Eigen::Vector4d(0, 0, 10, 0), Eigen::Vector4d(4, 4, 1, 1).asDiagonal()},
                 {kX, kY, kVx, kVy}, 1.0, 0);
}

TEST(NearestNeighbourTracker, TakesTheNearestDetectionInsideTheGate) {
  const TrackerOptions o = Options();
  Eigen::MatrixXd z(2, 3);
  z << 13.0, 10.5, 200.0,  //
      0.0, 0.5, 0.0;
  const TrackStep step = TrackScan(o, Start(o), kNanosPerSecond, z);
  ASSERT_TRUE(step.associated);
  EXPECT_EQ(step.detection, 1);
  const MeasurementPrediction p =
      PredictMeasurement(PredictTo(o.imm, Start(o), kNanosPerSecond), o.R()).combined;
  EXPECT_NEAR(step.nis, NormalisedSquare(z.col(1) - p.z, p.S), 1e-12);
  EXPECT_EQ(step.state.time, kNanosPerSecond);
}

TEST(NearestNeighbourTracker, WithNothingInTheGateKeepsThePrediction) {
  const TrackerOptions o = Options();
  const ImmState start = Start(o);
  const ImmState predicted = PredictTo(o.imm, start, kNanosPerSecond);
  const MeasurementPrediction p = PredictMeasurement(predicted, o.R()).combined;
  // Just outside the 99 % gate along x.
  const double edge = std::sqrt(ChiSquareQuantile(0.99, 2.0) * p.S(0, 0) + 1e-9) * 1.001;
  Eigen::MatrixXd z(2, 1);
  z << p.z(0) + edge, p.z(1);
  const TrackStep step = TrackScan(o, start, kNanosPerSecond, z);
  EXPECT_FALSE(step.associated);
  EXPECT_EQ(step.state.modes[0].mean, predicted.modes[0].mean);
  EXPECT_EQ(step.state.probabilities, predicted.probabilities);
  // Just inside, it is taken.
  z(0, 0) = p.z(0) + edge / 1.002;
  EXPECT_TRUE(TrackScan(o, start, kNanosPerSecond, z).associated);
}

TEST(NearestNeighbourTracker, SkipsAndCountsNonFiniteDetections) {
  const TrackerOptions o = Options();
  Eigen::MatrixXd z(2, 3);
  z << std::numeric_limits<double>::quiet_NaN(), 10.0, std::numeric_limits<double>::infinity(),
      0.0, 0.0, 0.0;
  const TrackStep step = TrackScan(o, Start(o), kNanosPerSecond, z);
  EXPECT_EQ(step.skipped_non_finite, 2U);
  EXPECT_EQ(step.detection, 1);
  EXPECT_TRUE(step.state.modes[0].mean.allFinite());
}

TEST(NearestNeighbourTracker, SkipsAScanOlderThanTheState) {
  const TrackerOptions o = Options();
  Eigen::MatrixXd z(2, 1);
  z << 10.0, 0.0;
  const TrackStep now = TrackScan(o, Start(o), kNanosPerSecond, z);
  const TrackStep back = TrackScan(o, now.state, kNanosPerSecond / 2, z);
  EXPECT_TRUE(back.skipped_out_of_order);
  EXPECT_FALSE(back.associated);
  EXPECT_EQ(back.state.time, kNanosPerSecond);
  EXPECT_EQ(back.state.modes[1].mean, now.state.modes[1].mean);
  // The same time again is no step back: a second scan at one instant is still used.
  EXPECT_FALSE(TrackScan(o, now.state, kNanosPerSecond, z).skipped_out_of_order);
}

TEST(NearestNeighbourTracker, ValidateNamesTheField) {
  TrackerOptions o = Options();
  o.gate_probability = 1.0;
  try {
    o.Validate("cfg", "tracker");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "tracker.gate_probability");
  }
}

}  // namespace
}  // namespace lookout::tracking
