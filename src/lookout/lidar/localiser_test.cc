#include "lookout/lidar/localiser.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/random.h"
#include "lookout/lidar/lidar_test_support.h"
#include "lookout/lidar/scan_matcher.h"
#include "lookout/lidar/slam.h"

namespace lookout::lidar {
namespace {

// A simulated drive: the vehicle goes round an ellipse in the hall (radius of curvature at
// least 4.1 m, drivable by the bicycle model), one scan per metre; the odometry is the truth's
// increments with a 3 % scale error on turning, 2 % on distance, and random noise, so dead
// reckoning drifts.
struct Drive {
  std::vector<Pose2> truth;
  std::vector<Pose2> odometry;
  std::vector<LidarScan> scans;
};

Drive SimulateDrive(std::uint64_t seed, int laps_tenths) {
  const std::vector<sim::Shape> world = testing::Hall();
  Rng rng(seed);
  Drive d;
  const double a = 12.0;
  const double b = 7.0;
  double s = 0.0;
  Pose2 odometry;
  const int steps = laps_tenths * 6;  // about 60 one-metre steps per lap
  for (int k = 0; k <= steps; ++k) {
    const Eigen::Vector2d p(a * std::cos(s), b * std::sin(s));
    const Eigen::Vector2d v(-a * std::sin(s), b * std::cos(s));
    const Pose2 truth(p, std::atan2(v.y(), v.x()));
    if (k > 0) {
      const Pose2 inc = d.truth.back().Inverse() * truth;
      const Pose2 noisy{inc.x() * 1.02 + rng.Normal(0.0, 0.02), inc.y() + rng.Normal(0.0, 0.01),
                        inc.yaw * 1.03 + rng.Normal(0.0, 0.01)};
      odometry = odometry * noisy;
    } else {
      odometry = truth;  // the odometry frame starts at the true pose
    }
    d.truth.push_back(truth);
    d.odometry.push_back(odometry);
    d.scans.push_back(testing::CastScan(world, truth, FromSeconds(0.5 * k)));
    s += 1.0 / v.norm();  // about one metre along the path
  }
  return d;
}

SlamOptions TestOptions(MotionModelKind kind) {
  SlamOptions o;
  o.map.window_cells = 1024;
  o.motion.kind = kind;
  return o;
}

double Rmse(const std::vector<Pose2>& a, const std::vector<Pose2>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum += (a[i].translation - b[i].translation).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

TEST(LidarLocaliser, BeatsDeadReckoningOnASimulatedDrive) {
  const std::uint64_t seed = 404;
  const Drive drive = SimulateDrive(seed, 15);
  for (const MotionModelKind kind :
       {MotionModelKind::kBicycle, MotionModelKind::kDifferentialDrive}) {
    LidarLocaliser localiser(TestOptions(kind));
    std::vector<Pose2> estimate;
    for (std::size_t k = 0; k < drive.scans.size(); ++k) {
      const std::optional<EgoState> state = localiser.AddScan(drive.scans[k], drive.odometry[k]);
      ASSERT_TRUE(state.has_value());
      estimate.push_back(state->pose);
    }
    const double dead_reckoning = Rmse(drive.odometry, drive.truth);
    const double localised = Rmse(estimate, drive.truth);
    // The stated margin: under 6 cm, and at least ten times better than dead reckoning.
    EXPECT_LT(localised, 0.06) << "seed " << seed << " kind " << static_cast<int>(kind);
    EXPECT_LT(localised * 10.0, dead_reckoning)
        << "seed " << seed << " dead reckoning " << dead_reckoning << " localised " << localised;
  }
}

TEST(LidarLocaliser, SameSeedSameBytes) {
  const Drive drive = SimulateDrive(7, 3);
  std::vector<double> runs[2];
  for (auto& out : runs) {
    LidarLocaliser localiser(TestOptions(MotionModelKind::kBicycle));
    for (std::size_t k = 0; k < drive.scans.size(); ++k) {
      const EgoState s = *localiser.AddScan(drive.scans[k], drive.odometry[k]);
      out.insert(out.end(), {s.pose.x(), s.pose.y(), s.pose.yaw, s.covariance(0, 0)});
    }
  }
  EXPECT_EQ(runs[0], runs[1]);
}

TEST(LidarLocaliser, StateCarriesSpeedYawRateAndParticleCovariance) {
  const Drive drive = SimulateDrive(11, 3);
  LidarLocaliser localiser(TestOptions(MotionModelKind::kBicycle));
  EgoState last;
  for (std::size_t k = 0; k < drive.scans.size(); ++k) {
    last = *localiser.AddScan(drive.scans[k], drive.odometry[k]);
  }
  // One metre per half second along the ellipse.
  EXPECT_NEAR(last.speed_mps, 2.0, 0.2);
  const Pose2 step = drive.truth[drive.truth.size() - 2].Inverse() * drive.truth.back();
  EXPECT_NEAR(last.yaw_rate_radps, step.yaw / 0.5, 0.05);
  const ParticleEstimate e = EstimateFromParticles(localiser.particles());
  EXPECT_EQ(last.covariance, e.covariance);
  EXPECT_TRUE(last.covariance.isApprox(last.covariance.transpose()));
  EXPECT_GE(last.covariance.diagonal().minCoeff(), 0.0);
}

TEST(LidarLocaliser, PoseAtComposesTheLatestScanWithOdometry) {
  const Drive drive = SimulateDrive(3, 1);
  LidarLocaliser localiser(TestOptions(MotionModelKind::kDifferentialDrive));
  EXPECT_FALSE(localiser.PoseAt(0).has_value());
  const EgoState first = *localiser.AddScan(drive.scans[0], drive.odometry[0]);
  EXPECT_EQ(localiser.PoseAt(drive.scans[0].stamp)->pose.x(), first.pose.x());
  // Odometry 0.2 s later: 0.4 m further along x of the vehicle.
  const Pose2 later_odometry = drive.odometry[0] * Pose2(0.4, 0.0, 0.1);
  ASSERT_TRUE(localiser.AddOdometry(drive.scans[0].stamp + FromSeconds(0.2), later_odometry));
  const std::optional<EgoState> mid = localiser.PoseAt(drive.scans[0].stamp + FromSeconds(0.1));
  ASSERT_TRUE(mid.has_value());
  const Pose2 expected = first.pose * Pose2(0.2, 0.0, 0.05);
  EXPECT_NEAR(mid->pose.x(), expected.x(), 1e-9);
  EXPECT_NEAR(mid->pose.y(), expected.y(), 1e-9);
  EXPECT_NEAR(mid->pose.yaw, expected.yaw, 1e-9);
  // Beyond max_extrapolation_s past the newest odometry: refused.
  EXPECT_FALSE(localiser.PoseAt(drive.scans[0].stamp + FromSeconds(1.0)).has_value());
  // Time going backwards is refused and counted.
  EXPECT_FALSE(localiser.AddOdometry(0, drive.odometry[0]));
  EXPECT_EQ(localiser.rejected_count(), 1);
  const EgoPoseSource& source = localiser;
  EXPECT_TRUE(source.PoseAt(drive.scans[0].stamp).has_value());
}

TEST(RunSlam, OneTrajectoryPosePerRecordAndOdometryOnlyIsTheOdometry) {
  const Drive drive = SimulateDrive(5, 2);
  std::vector<SlamRecord> records;
  for (std::size_t k = 0; k < drive.scans.size(); ++k) {
    const double t = 0.5 * static_cast<double>(k);
    if (k > 0) {  // an odometry reading halfway between scans
      const Pose2 inc = drive.odometry[k - 1].Inverse() * drive.odometry[k];
      records.push_back({t - 0.25, drive.odometry[k - 1] *
                                       Pose2(0.5 * inc.x(), 0.5 * inc.y(), 0.5 * inc.yaw), {}});
    }
    records.push_back({t, drive.odometry[k], drive.scans[k]});
  }
  records.push_back({0.1, Pose2(), {}});  // time going backwards: refused
  const SlamOptions options = TestOptions(MotionModelKind::kBicycle);
  const SlamResult odometry = RunSlam(records, options, true);
  ASSERT_EQ(odometry.trajectory.size(), records.size() - 1);
  EXPECT_EQ(odometry.records_refused, 1);
  for (std::size_t i = 0; i + 1 < records.size(); ++i) {
    EXPECT_EQ(odometry.trajectory[i].t_s, records[i].t_s);
    EXPECT_NEAR(odometry.trajectory[i].pose.x(), records[i].odometry.x(), 1e-12);
  }
  const SlamResult slam = RunSlam(records, options, false);
  ASSERT_EQ(slam.trajectory.size(), records.size() - 1);
  EXPECT_EQ(slam.scans_used, static_cast<std::int64_t>(drive.scans.size()));
  std::vector<Pose2> at_scans;
  for (const EgoState& s : slam.scan_states) at_scans.push_back(s.pose);
  EXPECT_LT(Rmse(at_scans, drive.truth), 0.05);
  EXPECT_GT(slam.map.geometry.width, 100);
}

}  // namespace
}  // namespace lookout::lidar

namespace lookout::lidar {
namespace {

// LocaliseScan then MapScan with every return is AddScan, pose for pose; mapping only part of
// a scan changes what the next scan is matched against, and a MapScan for a scan that was not
// localised does nothing.
TEST(LidarLocaliser, LocaliseThenMapIsAddScan) {
  const Drive drive = SimulateDrive(9, 2);
  LidarLocaliser whole(TestOptions(MotionModelKind::kBicycle));
  LidarLocaliser halves(TestOptions(MotionModelKind::kBicycle));
  LidarLocaliser half_mapped(TestOptions(MotionModelKind::kBicycle));
  bool differs = false;
  for (std::size_t k = 0; k < drive.scans.size(); ++k) {
    const LidarScan& scan = drive.scans[k];
    const EgoState a = *whole.AddScan(scan, drive.odometry[k]);
    const EgoState b = *halves.LocaliseScan(scan, drive.odometry[k]);
    const std::vector<Eigen::Vector2d> all = ExtractScanPoints(scan, MatcherOptions{}).all;
    halves.MapScan(scan, all, {});
    EXPECT_EQ(a.pose.x(), b.pose.x());
    EXPECT_EQ(a.pose.y(), b.pose.y());
    EXPECT_EQ(a.pose.yaw, b.pose.yaw);
    const EgoState c = *half_mapped.LocaliseScan(scan, drive.odometry[k]);
    const std::vector<Eigen::Vector2d> first_half(
        all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2));
    half_mapped.MapScan(scan, first_half, {});
    differs = differs || c.pose.x() != a.pose.x();
  }
  EXPECT_TRUE(differs);
  const std::int64_t inserted = halves.map().scans_inserted();
  LidarScan stale = drive.scans.back();
  stale.stamp += FromSeconds(1.0);  // never localised
  halves.MapScan(stale, ExtractScanPoints(stale, MatcherOptions{}).all, {});
  EXPECT_EQ(halves.map().scans_inserted(), inserted);
}

}  // namespace
}  // namespace lookout::lidar
