#include "lookout/eval/fusion_metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "lookout/core/random.h"
#include "lookout/fusion/fusion_engine.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/sim/simulator.h"
#include "lookout/stereo/range_bearing.h"

namespace lookout::eval {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

const Pose2 kLidarMount(2.2, 0.0, 0.0);

// One actor, one fused object whose errors are known: fused 0.3 m off, lidar 0.4 m, stereo 0.5.
TEST(FusionMetricsTest, HandMadeFrame) {
  const TrueObject truth{0, stereo::OrientedBox{Vector2d(20.0, 0.0), 0.0, 4.0, 2.0}};
  const Vector2d true_point(18.0, 0.0);  // the rear's middle, facing the lidar
  fusion::FusedObjectFrame fused;
  fused.mount = kLidarMount;
  fusion::FusedObject f;
  f.point_m = true_point + Vector2d(0.3, 0.0);
  f.point_covariance = Vector2d(0.09, 0.01).asDiagonal();  // NEES = 1
  f.sensor_count = 2;
  f.lidar_id = 5;
  f.stereo_id = 6;
  fused.objects = {f};
  fusion::FusedObject lidar_only = f;  // not scored: one sensor
  lidar_only.sensor_count = 1;
  lidar_only.stereo_id.reset();
  fused.objects.push_back(lidar_only);
  LidarObjectFrame lidar;
  lidar.objects.resize(1);
  lidar.objects[0].id = 5;
  lidar.objects[0].point_m = true_point + Vector2d(0.0, 0.4);
  stereo::StereoPoint s;
  s.id = 6;
  s.point.point_m = true_point - Vector2d(0.5, 0.0);
  FusionMetricsAccumulator metrics;
  metrics.AddFrame(fused, lidar, {&s, 1}, {&truth, 1});
  ASSERT_EQ(metrics.matched(), 1);
  EXPECT_NEAR(*metrics.PositionRmse(), 0.3, 1e-12);
  EXPECT_NEAR(*metrics.LidarOnlyRmse(), 0.4, 1e-12);
  EXPECT_NEAR(*metrics.StereoOnlyRmse(), 0.5, 1e-12);
  EXPECT_NEAR(*metrics.MeanNees(), 1.0, 1e-12);
  // N = 1: chi-square(2) quantiles 0.0506 and 7.3778 (tables).
  EXPECT_NEAR(metrics.MeanNeesBand()->low, 0.0506, 1e-4);
  EXPECT_NEAR(metrics.MeanNeesBand()->high, 7.3778, 1e-4);
  EXPECT_EQ(metrics.Values().at("fusion.position_rmse_m"), *metrics.PositionRmse());

  // A fused object beyond the match radius from every actor is not scored.
  fused.objects[0].point_m = true_point + Vector2d(2.5, 0.0);
  metrics.AddFrame(fused, lidar, {&s, 1}, {&truth, 1});
  EXPECT_EQ(metrics.matched(), 1);
}

TEST(FusionMetricsTest, NothingMatchedHasNoValues) {
  const FusionMetricsAccumulator metrics;
  EXPECT_FALSE(metrics.PositionRmse().has_value());
  EXPECT_EQ(metrics.Values().count("fusion.position_rmse_m"), 0u);
}

// Lidar objects made from the truth with noise of known covariance: range sigma 0.15 m and
// bearing sigma 0.01 rad from the lidar origin (a segment's middle from a few dozen returns),
// drawn exactly from the Cartesian covariance that the Jacobian gives.
LidarObjectFrame LidarObjectsFromTruth(const sim::TruthFrame& truth,
                                       const sim::LidarOptions& lidar_options, std::uint64_t seed,
                                       int frame_index) {
  LidarObjectFrame frame;
  frame.stamp = truth.stamp;
  frame.mount = Pose2(lidar_options.x_m, lidar_options.y_m, lidar_options.yaw_rad);
  frame.ego_pose = truth.ego.state.pose;
  Rng rng(DeriveSeed(seed, "test_lidar_objects", static_cast<std::uint64_t>(frame_index)));
  const std::vector<TrueObject> objects = TrueObjectsInVehicleFrame(truth);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const sim::ActorTruth& actor = truth.actors[i];
    if (actor.visible_fraction_lidar <= 0.0) continue;
    const auto front = stereo::FrontSegmentFacing(objects[i].footprint, frame.mount.translation);
    if (!front) continue;
    stereo::CartesianPoint exact{front->midpoint_m, Matrix2d::Identity()};
    stereo::RangeBearing polar = stereo::ToRangeBearing(exact, frame.mount);
    polar.covariance = Vector2d(0.15 * 0.15, 0.01 * 0.01).asDiagonal();
    const stereo::CartesianPoint with_covariance = stereo::ToCartesian(polar, frame.mount);
    const Matrix2d chol = with_covariance.covariance.llt().matrixL();
    LidarObject o;
    o.id = static_cast<std::uint32_t>(100 + actor.index);
    o.point_m = front->midpoint_m + chol * Vector2d{rng.Normal(), rng.Normal()};
    o.point_covariance = with_covariance.covariance;
    o.front_start_m = front->start_m;
    o.front_end_m = front->end_m;
    const Matrix2d to_vehicle = Pose2(0.0, 0.0, -truth.ego.state.pose.yaw).Rotation();
    o.velocity_mps =
        to_vehicle * actor.state.Velocity() + 0.5 * Vector2d{rng.Normal(), rng.Normal()};
    o.velocity_covariance = 0.25 * Matrix2d::Identity();
    o.class_pmf[static_cast<std::size_t>(actor.object_class)] = 1.0;
    o.dynamic = std::abs(actor.state.speed_mps) > 0.5;
    frame.objects.push_back(o);
  }
  return frame;
}

struct EndToEnd {
  FusionMetricsAccumulator metrics;
  fusion::FusionStats stats;
};

EndToEnd RunScenario(const std::string& name) {
  const sim::Scenario scenario =
      io::LoadScenarioFile(std::string(LOOKOUT_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
  const sim::Simulator simulator(scenario);
  const sim::SensorLog log = simulator.Run(2);
  // The lidar objects here are the true front points with noise of known covariance: they
  // carry none of the definition errors the lidar point model adds (lidar_point_model.h).
  fusion::FusionOptions options;
  options.lidar_point.round_body = false;
  fusion::FusionEngine engine(options);
  EndToEnd result;
  std::size_t next_stereo = 0;
  for (std::size_t k = 0; k < log.truth.size(); ++k) {
    const sim::TruthFrame& truth = log.truth[k];
    // The latest stereo frame at or before the lidar stamp.
    while (next_stereo < log.stereo.size() && log.stereo[next_stereo].stamp <= truth.stamp) {
      ++next_stereo;
    }
    const StereoFrame latest = next_stereo > 0 ? log.stereo[next_stereo - 1] : StereoFrame{};
    const LidarObjectFrame lidar =
        LidarObjectsFromTruth(truth, scenario.sensors.lidar, scenario.seed, static_cast<int>(k));
    const fusion::FusedObjectFrame fused = engine.Fuse(lidar, latest);
    const std::vector<TrueObject> objects = TrueObjectsInVehicleFrame(truth);
    result.metrics.AddFrame(fused, lidar, engine.stereo_at_lidar_time(), objects);
  }
  result.stats = engine.stats();
  return result;
}

// End to end on catalogue scenarios: the simulator's real stereo objects fused with lidar
// objects of known noise. Fusion must beat both sensors alone, and its covariance must be
// consistent with its errors (mean NEES inside its 95 % band).
TEST(FusionMetricsTest, EndToEndOnCatalogueScenarios) {
  for (const std::string name :
       {"intersafe-fig8", "occluded-pedestrian", "pushchair-group", "right-turn-cyclist"}) {
    const EndToEnd run = RunScenario(name);
    const FusionMetricsAccumulator& m = run.metrics;
    ASSERT_GE(m.matched(), 50) << name;
    const NeesBand band = *m.MeanNeesBand();
    std::string report = name + ": matched " + std::to_string(m.matched()) + ", fused " +
                         std::to_string(*m.PositionRmse()) + " m, lidar " +
                         std::to_string(*m.LidarOnlyRmse()) + " m, stereo " +
                         std::to_string(*m.StereoOnlyRmse()) + " m, NEES " +
                         std::to_string(*m.MeanNees()) + " in [" + std::to_string(band.low) + ", " +
                         std::to_string(band.high) + "], pairs " + std::to_string(run.stats.pairs) +
                         ", stereo frames used " + std::to_string(run.stats.stereo_frames_used);
    std::cout << report << "\n";
    EXPECT_LT(*m.PositionRmse(), *m.LidarOnlyRmse()) << report;
    EXPECT_LT(*m.PositionRmse(), *m.StereoOnlyRmse()) << report;
    EXPECT_GE(*m.MeanNees(), band.low) << report;
    EXPECT_LE(*m.MeanNees(), band.high) << report;
  }
}

}  // namespace
}  // namespace lookout::eval
