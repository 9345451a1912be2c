#include "lookout/sim/stereo_sensor.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "lookout/core/random.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr int kDraws = 10000;
constexpr std::uint64_t kSeed = 2024;  // printed by SCOPED_TRACE in every statistical test

StereoTarget TargetAt(const Vector2d& center, int index = 0,
                      ObjectClass object_class = ObjectClass::kCar) {
  StereoTarget t;
  t.actor_index = index;
  t.object_class = object_class;
  t.pose = Pose2(center, 0.3);
  t.velocity_mps = Vector2d(4.0, -1.0);
  t.length_m = 4.5;
  t.width_m = 1.8;
  t.visible_fraction = 1.0;
  return t;
}

StereoOptions Noiseless() {
  StereoOptions o;
  o.miss_rate = 0.0;
  o.false_rate = 0.0;
  o.class_accuracy = 1.0;
  return o;
}

// Frame k of a camera at the world origin looking along +x.
StereoFrame Frame(const StereoOptions& options, const StereoNoiseModel& model,
                  const std::vector<StereoTarget>& targets, int k,
                  const Pose2& camera = Pose2()) {
  return MakeStereoFrame(options, model, TimeNs{k} * 50'000'000, k, camera, targets,
                         DeriveSeed(kSeed, "stereo", static_cast<std::uint64_t>(k)));
}

struct Moments {
  double mean = 0.0;
  double sigma = 0.0;
};

Moments Of(const std::vector<double>& xs) {
  Moments m;
  for (const double x : xs) m.mean += x;
  m.mean /= static_cast<double>(xs.size());
  for (const double x : xs) m.sigma += (x - m.mean) * (x - m.mean);
  m.sigma = std::sqrt(m.sigma / static_cast<double>(xs.size() - 1));
  return m;
}

TEST(StereoNoiseModelTest, DefaultsMatchTheStereoFormula) {
  const StereoNoiseModel model;
  EXPECT_NO_THROW(model.Validate());
  // z^2 sigma_d / (f B), with the 2 cm floor in quadrature.
  EXPECT_NEAR(model.DepthSigma(35.0), std::hypot(35.0 * 35.0 * 0.25 / 240.0, 0.02), 1e-12);
  EXPECT_NEAR(model.DepthSigma(35.0), 1.276, 1e-3);
  EXPECT_NEAR(model.DepthSigma(5.0), std::hypot(0.026, 0.02), 1e-3);
  // On the optical axis the covariance is diag(depth, lateral).
  const Eigen::Matrix2d c = model.CenterCovariance({20.0, 0.0});
  EXPECT_NEAR(c(0, 0), std::pow(model.DepthSigma(20.0), 2), 1e-12);
  EXPECT_NEAR(c(1, 1), std::pow(20.0 * 0.002, 2) + 0.02 * 0.02, 1e-12);
  EXPECT_NEAR(c(0, 1), 0.0, 1e-12);
  // Off axis it is rotated: the large axis points along the line of sight.
  const Vector2d p(20.0, 10.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(model.CenterCovariance(p));
  EXPECT_NEAR(std::abs(eig.eigenvectors().col(1).dot(p.normalized())), 1.0, 1e-9);
  StereoNoiseModel bad;
  bad.baseline_m = 0.0;
  EXPECT_THROW(bad.Validate(), std::invalid_argument);
}

TEST(StereoSensorTest, DepthAndLateralSpreadMatchTheModel) {
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  const StereoNoiseModel model;
  for (const double depth : {5.0, 15.0, 25.0, 34.0}) {
    SCOPED_TRACE(::testing::Message() << "depth " << depth);
    const std::vector<StereoTarget> targets = {TargetAt({depth, 0.0})};
    std::vector<double> dx, dy;
    for (int k = 0; k < kDraws; ++k) {
      const StereoFrame f = Frame(Noiseless(), model, targets, k);
      ASSERT_EQ(f.objects.size(), 1u);
      dx.push_back(f.objects[0].center_m.x() - depth);
      dy.push_back(f.objects[0].center_m.y());
    }
    const double lateral_sigma = std::hypot(depth * model.bearing_sigma_rad,
                                            model.position_sigma_floor_m);
    EXPECT_NEAR(Of(dx).sigma, model.DepthSigma(depth), 0.1 * model.DepthSigma(depth));
    EXPECT_NEAR(Of(dy).sigma, lateral_sigma, 0.1 * lateral_sigma);
    EXPECT_NEAR(Of(dx).mean, 0.0, 4.0 * model.DepthSigma(depth) / std::sqrt(kDraws));
    EXPECT_NEAR(Of(dy).mean, 0.0, 4.0 * lateral_sigma / std::sqrt(kDraws));
  }
}

TEST(StereoSensorTest, NeesOfTheReportedCovariancesIsChiSquare) {
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  const StereoNoiseModel model;
  // Off axis and at several depths, so the rotation of the covariance is exercised too.
  const std::vector<StereoTarget> targets = {
      TargetAt({30.0, 15.0}, 0), TargetAt({8.0, -4.0}, 1), TargetAt({20.0, 0.0}, 2)};
  const Pose2 camera(3.0, -2.0, 0.7);  // targets are given in the camera frame below
  std::vector<StereoTarget> world_targets = targets;
  for (StereoTarget& t : world_targets) {
    t.pose = Pose2(camera * t.pose.translation, camera.yaw + t.pose.yaw);
  }
  double center_nees = 0.0, yaw_nees = 0.0, speed_nees = 0.0;
  int n = 0;
  for (int k = 0; k < kDraws; ++k) {
    const StereoFrame f = Frame(Noiseless(), model, world_targets, k, camera);
    ASSERT_EQ(f.objects.size(), targets.size());
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const StereoObject& o = f.objects[i];
      const Vector2d e = o.center_m - targets[i].pose.translation;
      center_nees += e.dot(o.center_covariance.inverse() * e);
      const double yaw_error = WrapAngle(o.yaw_rad - targets[i].pose.yaw);
      yaw_nees += yaw_error * yaw_error / o.yaw_variance;
      // World velocity (4, -1) seen in camera axes.
      const Vector2d v = camera.Rotation().transpose() * targets[i].velocity_mps;
      const Vector2d ev(o.speed_longitudinal_mps - v.x(), o.speed_lateral_mps - v.y());
      speed_nees += ev.squaredNorm() / o.speed_variance;
      ++n;
    }
  }
  // chi-square(2) has mean 2 and variance 4: the mean of 30,000 is within 0.05 at 4 sigma.
  EXPECT_NEAR(center_nees / n, 2.0, 0.05);
  EXPECT_NEAR(yaw_nees / n, 1.0, 0.04);
  EXPECT_NEAR(speed_nees / n, 2.0, 0.05);
}

TEST(StereoSensorTest, ClassAccuracyAndConfusion) {
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  StereoOptions options = Noiseless();
  options.class_accuracy = 0.9;
  const std::vector<StereoTarget> targets = {TargetAt({15.0, 2.0}, 0, ObjectClass::kPedestrian)};
  std::array<int, kAllObjectClasses.size()> counts{};
  for (int k = 0; k < kDraws; ++k) {
    const StereoFrame f = Frame(options, StereoNoiseModel{}, targets, k);
    ASSERT_EQ(f.objects.size(), 1u);
    ++counts[static_cast<std::size_t>(f.objects[0].object_class)];
  }
  const double accuracy =
      counts[static_cast<std::size_t>(ObjectClass::kPedestrian)] / static_cast<double>(kDraws);
  EXPECT_NEAR(accuracy, 0.9, 0.09);
  EXPECT_NEAR(accuracy, 0.9, 0.012);  // 4 binomial sigmas
  // The other five classes share the rest evenly: 2 % each.
  for (const ObjectClass c : kAllObjectClasses) {
    if (c == ObjectClass::kPedestrian) continue;
    EXPECT_NEAR(counts[static_cast<std::size_t>(c)] / static_cast<double>(kDraws), 0.02, 0.006)
        << ToString(c);
  }
}

TEST(StereoSensorTest, MissRate) {
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  StereoOptions options = Noiseless();
  options.miss_rate = 0.05;
  const std::vector<StereoTarget> targets = {TargetAt({15.0, 2.0})};
  int missed = 0;
  for (int k = 0; k < kDraws; ++k) {
    missed += Frame(options, StereoNoiseModel{}, targets, k).objects.empty() ? 1 : 0;
  }
  EXPECT_NEAR(missed / static_cast<double>(kDraws), 0.05, 0.009);  // 4 binomial sigmas
}

TEST(StereoSensorTest, FalseObjectsArePoissonInsideTheField) {
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  StereoOptions options = Noiseless();
  options.false_rate = 0.5;
  const StereoNoiseModel model;
  int count = 0;
  for (int k = 0; k < kDraws; ++k) {
    const StereoFrame f = Frame(options, model, {}, k);
    for (const StereoObject& o : f.objects) {
      ++count;
      EXPECT_GE(o.id, kFalseObjectIdBase);
      EXPECT_EQ(o.history, 1u);
      // The true position is inside the field; the reported one is within the noise of it.
      EXPECT_GT(o.center_m.x(), model.false_min_depth_m - 5.0 * model.DepthSigma(35.0));
      EXPECT_LT(o.center_m.x(), options.max_depth_m + 5.0 * model.DepthSigma(35.0));
      EXPECT_LT(std::abs(std::atan2(o.center_m.y(), o.center_m.x())),
                0.5 * options.fov_rad + 0.02);
      EXPECT_GE(o.length_m, model.false_length_min_m);
      EXPECT_LE(o.width_m, model.false_width_max_m);
    }
  }
  // Poisson: mean 0.5, variance 0.5 per frame.
  EXPECT_NEAR(count / static_cast<double>(kDraws), 0.5, 4.0 * std::sqrt(0.5 / kDraws));
}

TEST(StereoSensorTest, ReportsOnlyVisibleActorsInTheField) {
  const StereoOptions options = Noiseless();
  const double half_fov = 0.5 * options.fov_rad;
  std::vector<StereoTarget> targets = {
      TargetAt({20.0, 0.0}, 0),                                        // seen
      TargetAt({20.0 * std::cos(half_fov - 1e-3), 20.0 * std::sin(half_fov - 1e-3)}, 1),
      TargetAt({20.0 * std::cos(half_fov + 1e-3), 20.0 * std::sin(half_fov + 1e-3)}, 2),
      TargetAt({35.0, 0.0}, 3),                                        // at max depth: seen
      TargetAt({35.01, 0.0}, 4),                                       // beyond
      TargetAt({-5.0, 0.0}, 5),                                        // behind
      TargetAt({10.0, 1.0}, 6)};                                       // occluded
  targets[6].visible_fraction = 0.0;
  const StereoFrame f = Frame(options, StereoNoiseModel{}, targets, 3);
  std::vector<std::uint32_t> ids;
  for (const StereoObject& o : f.objects) ids.push_back(o.id);
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{1, 2, 4}));
  for (const StereoObject& o : f.objects) {
    EXPECT_EQ(o.history, 1u);
    EXPECT_DOUBLE_EQ(o.length_m, 4.5);
    EXPECT_DOUBLE_EQ(o.width_m, 1.8);
  }
}

TEST(StereoSensorTest, SpeedIsGroundVelocityInCameraAxes) {
  StereoNoiseModel exact;
  exact.speed_sigma_mps = 0.0;
  exact.speed_sigma_per_depth_per_s = 0.0;
  exact.yaw_sigma_rad = 0.0;
  // A camera looking north; a car 10 m north of it driving east at 5 m/s, heading 0.
  const Pose2 camera(0.0, 0.0, kPi / 2.0);
  StereoTarget car = TargetAt({0.0, 10.0});
  car.pose.yaw = 0.0;
  car.velocity_mps = Vector2d(5.0, 0.0);
  const StereoFrame f = Frame(Noiseless(), exact, {car}, 0, camera);
  ASSERT_EQ(f.objects.size(), 1u);
  EXPECT_NEAR(f.objects[0].speed_longitudinal_mps, 0.0, 1e-12);
  EXPECT_NEAR(f.objects[0].speed_lateral_mps, -5.0, 1e-12);  // to the camera's right
  EXPECT_NEAR(f.objects[0].yaw_rad, -kPi / 2.0, 1e-12);
  EXPECT_NEAR(f.objects[0].center_m.x(), 10.0, 0.2);
}

TEST(StereoSensorTest, ActorNoiseDoesNotDependOnOtherActors) {
  const std::vector<StereoTarget> one = {TargetAt({12.0, 1.0}, 4)};
  const std::vector<StereoTarget> two = {TargetAt({20.0, -3.0}, 1), TargetAt({12.0, 1.0}, 4)};
  const StereoFrame a = Frame(StereoOptions{}, StereoNoiseModel{}, one, 7);
  const StereoFrame b = Frame(StereoOptions{}, StereoNoiseModel{}, two, 7);
  const auto find = [](const StereoFrame& f) {
    for (const StereoObject& o : f.objects) {
      if (o.id == 5u) return o.center_m;
    }
    return Vector2d(-1.0, -1.0);
  };
  EXPECT_EQ(find(a), find(b));
}

TEST(StereoSensorTest, FanCoversTheFieldAtTheModelResolution) {
  const StereoOptions options;
  const Fan fan = StereoFan(options, StereoNoiseModel{}, Pose2(1.0, 2.0, 0.5));
  EXPECT_EQ(fan.count, 701);  // 70 deg at 0.1 deg, both ends included
  EXPECT_NEAR(fan.BeamAngle(0), 0.5 - 0.5 * options.fov_rad, 1e-12);
  EXPECT_NEAR(fan.BeamAngle(700), 0.5 + 0.5 * options.fov_rad, 1e-12);
  EXPECT_NEAR(fan.max_range_m, 35.0 / std::cos(0.5 * options.fov_rad), 1e-12);
}

}  // namespace
}  // namespace lookout::sim
