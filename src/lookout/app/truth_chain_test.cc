// The decomposition of the chain's losses: the tracking and risk stages on detections made from
// the simulator's truth with known noise (as FusionMetricsTest.EndToEndOnCatalogueScenarios does
// for fusion), scored exactly as `lookout eval` scores the real chain. What the two stages reach
// here is what they reach by themselves; the gap to the real chain's figures
// (docs/tracking-metrics.md, docs/risk.md) is what the grid, the camera and fusion lose.
//
// The detections: every actor that a sensor sees (visible fraction > 0) within its reach, as a
// fused object at the middle of the side facing the lidar (where both sensors report it), with
// 0.15 m of position noise and 0.5 m/s of velocity noise (standard deviations per axis, the
// covariances saying so), its true class, from both sensors when both see it (the camera's
// track id the actor's). Nothing else: no ghosts, no misses beyond occlusion.
//
// Suite name Catalogue*: ctest label `catalogue` (cmake/LookoutModule.cmake), left out of the
// sanitizer run.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "lookout/app/risk_scoring.h"
#include "lookout/app/risk_stage.h"
#include "lookout/app/runner.h"
#include "lookout/app/tracking_scoring.h"
#include "lookout/app/tracking_stage.h"
#include "lookout/core/random.h"
#include "lookout/eval/fusion_metrics.h"
#include "lookout/grid/grid_options.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/sim/simulator.h"
#include "lookout/stereo/oriented_box.h"

namespace lookout::app {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

constexpr double kPositionSigmaM = 0.15;
constexpr double kVelocitySigmaMps = 0.5;

// Two standard normal draws, y first, each in its own statement: the order GCC took when the
// table in docs/tracking-metrics.md was written (two draws in one call's arguments are
// unsequenced, and clang takes x first). Drawn the other way round, fast-car warns on these
// detections too (level 2, none on the truth), as near-miss does: the risk rule is sensitive to
// a 0.5 m/s velocity error on a 20 m/s car (docs/risk.md).
Vector2d NormalPair(Rng& rng) {
  const double y = rng.Normal();
  const double x = rng.Normal();
  return {x, y};
}

fusion::FusedObjectFrame FusedObjectsFromTruth(const sim::TruthFrame& truth,
                                               const sim::Scenario& scenario,
                                               const SensorReach& reach, Rng& rng) {
  const sim::LidarOptions& l = scenario.sensors.lidar;
  fusion::FusedObjectFrame frame;
  frame.stamp = truth.stamp;
  frame.mount = Pose2(l.x_m, l.y_m, l.yaw_rad);
  frame.ego_pose = truth.ego.state.pose;  // the odometry frame is the world here
  const std::vector<eval::TrueObject> objects = eval::TrueObjectsInVehicleFrame(truth);
  const Matrix2d to_vehicle = Pose2(0.0, 0.0, -truth.ego.state.pose.yaw).Rotation();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const sim::ActorTruth& actor = truth.actors[i];
    const Vector2d centre = objects[i].footprint.center_m;
    const bool lidar = actor.visible_fraction_lidar > 0.0 && reach.InLidarReach(centre);
    const bool camera = actor.visible_fraction_stereo > 0.0 && reach.InCameraReach(centre);
    if (!lidar && !camera) continue;
    const auto front = stereo::FrontSegmentFacing(objects[i].footprint, frame.mount.translation);
    if (!front) continue;
    fusion::FusedObject o;
    o.id = static_cast<std::uint32_t>(frame.objects.size());
    o.point_m = front->midpoint_m + kPositionSigmaM * NormalPair(rng);
    o.point_covariance = kPositionSigmaM * kPositionSigmaM * Matrix2d::Identity();
    o.velocity_mps = to_vehicle * actor.state.Velocity() +
                     kVelocitySigmaMps * NormalPair(rng);
    o.velocity_covariance = kVelocitySigmaMps * kVelocitySigmaMps * Matrix2d::Identity();
    o.front_start_m = front->start_m;
    o.front_end_m = front->end_m;
    o.class_pmf[static_cast<std::size_t>(actor.object_class)] = 1.0;
    o.dynamic = std::abs(actor.state.speed_mps) > 0.5;
    o.sensor_count = (lidar ? 1 : 0) + (camera ? 1 : 0);
    if (lidar) o.lidar_id = static_cast<std::uint32_t>(actor.index);
    if (camera) o.stereo_id = static_cast<std::uint32_t>(1000 + actor.index);
    frame.objects.push_back(o);
  }
  return frame;
}

// The tracking.*, tracking_baseline.* and risk.* keys of one scenario on truth-made detections.
std::map<std::string, double> RunOnTruth(const std::string& name) {
  const sim::Scenario scenario =
      io::LoadScenarioFile(std::string(LOOKOUT_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
  const sim::Simulator simulator(scenario);
  const sim::SensorLog log = simulator.Run(1);
  const grid::GridOptions grid_options;
  const SensorReach reach = SensorReach::Of(
      scenario.sensors, 0.5 * grid_options.width_cells * grid_options.cell_size_m);
  const sim::StereoOptions& s = scenario.sensors.stereo;
  const Pose2 camera_mount(s.x_m, s.y_m, s.yaw_rad);

  TrackingStage tracking(ForSensors(PipelineOptions{}, scenario.sensors).tracking_options);
  RiskStage risk;
  risk.SetRoute(scenario.ego.path);
  risk.SetCarriageways(CarriagewaysOf(scenario.world, Pose2{}));
  std::vector<std::pair<std::string, double>> contacts;
  for (std::size_t i = 0; i < scenario.actors.size(); ++i) {
    if (const auto& t = simulator.contact_times_s()[i]) {
      contacts.emplace_back(scenario.actors[i].id, *t);
    }
  }
  TrackingScorer tracking_scorer(Pose2{}, reach);
  RiskScorer risk_scorer(Pose2{}, risk.options(), scenario.ego.path,
                         CarriagewaysOf(scenario.world, Pose2{}), scenario.expect, contacts);
  Rng rng(DeriveSeed(scenario.seed, "truth_chain_test", 0));
  std::size_t next_odometry = 0;
  for (std::size_t k = 0; k < log.truth.size(); ++k) {
    const sim::TruthFrame& truth = log.truth[k];
    while (next_odometry < log.odometry.size() &&
           log.odometry[next_odometry].stamp <= truth.stamp) {
      risk.OnOdometry(log.odometry[next_odometry++]);
    }
    const fusion::FusedObjectFrame frame = FusedObjectsFromTruth(truth, scenario, reach, rng);
    // The scan of the same stamp tells the trackers where the lidar could see.
    tracking.Step(frame, camera_mount, &log.lidar[k]);
    risk.Step(frame.stamp, frame.ego_pose, tracking.tracks());
    tracking_scorer.Observe(truth, tracking.tracks(), &tracking.baseline_tracks());
    risk_scorer.Observe(truth, tracking.tracks(), risk.last_assessment());
  }
  std::map<std::string, double> metrics;
  tracking_scorer.Report(metrics);
  risk_scorer.Report(risk.events(), metrics);
  return metrics;
}

std::string Figure(const std::map<std::string, double>& m, const std::string& key) {
  const auto it = m.find(key);
  if (it == m.end()) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", it->second);
  return buffer;
}

// With the detections the real chain would have if the grid, the camera and fusion were
// perfect. Printed for every scenario (the table of docs/tracking-metrics.md, "The tracker and
// risk by themselves"); asserted where the stages alone reach the goals (2026-12-03), so that a
// change that loses them fails here:
//   - tracking (MOTA and IDF1 >= 0.9): all but two. crowd (walkers glimpsed, then hidden behind
//     buildings for longer than a track coasts, still counted as truths) and intersafe-fig8 (its
//     cyclist behind a building) fall short with perfect detections too. occluded-pedestrian
//     reaches it since the trackers see where the scan could see (tracks coast through
//     occlusion), straight-crossing-path since tracking is scored up to the contact;
//   - risk (a warning exactly when the true states give one): all but near-miss, where the
//     tracks' velocity error (0.5 m/s of detection noise, filtered) turns the near miss into a
//     predicted contact.
struct Case {
  const char* name;
  bool tracker_meets_goal;
  bool warns_as_the_truth;
};

TEST(CatalogueTruthChainTest, TrackerAndRiskOnTruthMadeDetections) {
  const std::vector<Case> cases = {
      {"child-behind-parked-car", true, true}, {"crowd", false, true},
      {"cyclist-crossing", true, true},        {"fast-car", true, true},
      {"intersafe-fig8", false, true},         {"intersafe-fig9", true, true},
      {"left-turn-across-path", true, true},   {"near-miss", true, false},
      {"occluded-pedestrian", true, true},     {"pushchair-group", true, true},
      {"right-turn-cyclist", true, true},      {"static-world-drive", true, true},
      {"straight-crossing-path", true, true}};
  std::cout << "| scenario | MOTA | IDF1 | ID sw. | GOSPA m | GNN MOTA | GNN IDF1 | GNN GOSPA m "
               "| false track frames | max level | lead time s | ideal max level | TTC MAE s "
               "| met |\n";
  for (const Case& c : cases) {
    const std::map<std::string, double> m = RunOnTruth(c.name);
    std::cout << "| " << c.name;
    for (const char* key :
         {"tracking.mota", "tracking.idf1", "tracking.id_switches", "tracking.gospa_m",
          "tracking_baseline.mota", "tracking_baseline.idf1", "tracking_baseline.gospa_m",
          "tracking.false_positives", "risk.max_level", "risk.lead_time_s",
          "risk.ideal_max_level", "risk.ttc_mae_s", "risk.expectation_met"}) {
      std::cout << " | " << Figure(m, key);
    }
    std::cout << " |\n";
    if (c.tracker_meets_goal && m.count("tracking.mota")) {
      EXPECT_GE(m.at("tracking.mota"), 0.9) << c.name;
      EXPECT_GE(m.at("tracking.idf1"), 0.9) << c.name;
    }
    ASSERT_TRUE(m.count("risk.max_level") && m.count("risk.ideal_max_level")) << c.name;
    if (c.warns_as_the_truth) {
      EXPECT_EQ(m.at("risk.max_level") == 2, m.at("risk.ideal_max_level") == 2) << c.name;
    }
  }
}

}  // namespace
}  // namespace lookout::app
