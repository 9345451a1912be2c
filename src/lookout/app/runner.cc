#include "lookout/app/runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include <tbb/task_arena.h>

#include "lookout/app/grid_recording.h"
#include "lookout/app/grid_scoring.h"
#include "lookout/app/lidar_hit_scoring.h"
#include "lookout/app/lidar_object_scoring.h"
#include "lookout/app/localisation_scoring.h"
#include "lookout/app/risk_scoring.h"
#include "lookout/app/tracking_scoring.h"
#include "lookout/eval/fusion_metrics.h"
#include "lookout/eval/statistics.h"
#include "lookout/io/grid_images.h"
#include "lookout/io/png_writer.h"
#include "lookout/sim/simulator.h"
#include "lookout/sim/world_builder.h"

namespace lookout::app {
namespace {

// The grid at one instant as PNG images: occupancy, the speed map of the paper's Fig. 6
// (hue = direction, brightness = speed), and the most likely class of each occupied cell.
std::vector<std::string> WriteSnapshot(const grid::ExtendedGrid& grid, const RunOptions& options,
                                       TimeNs stamp) {
  const eval::GridBelief b = BeliefOf(grid);
  const std::string stem =
      fmt::format("{}/snapshot-{:.2f}s", options.snapshot_dir, ToSeconds(stamp));
  const std::vector<std::string> files = {stem + "-occupancy.png", stem + "-speed.png",
                                          stem + "-class.png"};
  io::WritePng(files[0], io::RenderOccupancy(b.geometry, b.occupancy));
  io::SpeedMapOptions speed;
  speed.max_speed_mps = options.snapshot_max_speed_mps;
  io::WritePng(files[1], io::RenderSpeedMap(b.geometry, b.velocity_x_mps, b.velocity_y_mps,
                                            b.occupancy, b.velocity_confidence, speed));
  const std::vector<io::GridLayer8> layers = GridLayersToRecord(grid);
  const auto class_layer = std::find_if(layers.begin(), layers.end(),
                                        [](const io::GridLayer8& l) { return l.name == "class"; });
  io::WritePng(files[2], io::RenderClassMap(b.geometry, class_layer->values, b.occupancy));
  return files;
}

RunResult RunInArena(const sim::Scenario& scenario, Pipeline& pipeline, const RunOptions& options) {
  const WallClock::time_point run_start = WallClock::now();
  RunResult result;
  result.scenario = scenario.name;
  result.simulated_s = scenario.duration_s;

  const sim::Simulator simulator(scenario);
  for (std::size_t i = 0; i < scenario.actors.size(); ++i) {
    if (const auto& t = simulator.contact_times_s()[i]) {
      result.contacts.emplace_back(scenario.actors[i].id, *t);
    }
  }
  const WallClock::time_point sim_start = WallClock::now();
  const sim::SensorLog log = simulator.Run(options.threads);
  result.simulation_wall_s = SecondsSince(sim_start);
  result.lidar_frames = static_cast<std::int64_t>(log.lidar.size());
  result.stereo_frames = static_cast<std::int64_t>(log.stereo.size());
  result.odometry_frames = static_cast<std::int64_t>(log.odometry.size());

  // The odometry frame (where the grid lives) is the ego's true pose at the first reading.
  const Pose2 world_from_odom = simulator.ego_trajectory().At(0.0).pose;
  std::optional<GridScorer> grid_scorer;
  std::optional<LidarObjectScorer> object_scorer;
  std::optional<eval::FusionMetricsAccumulator> fusion_scorer;
  if (pipeline.fusion()) fusion_scorer.emplace();
  if (pipeline.grid()) {
    grid_scorer.emplace(world_from_odom, simulator.static_world(),
                        scenario.sensors.lidar.max_range_m);
  }
  if (pipeline.lidar_objects_available()) object_scorer.emplace(world_from_odom);
  // The lidar chain's localisation, and the dead reckoning beside it.
  std::optional<LocalisationScorer> lidar_pose_scorer, odometry_pose_scorer;
  std::optional<LidarHitScorer> hit_scorer;
  if (pipeline.lidar_chain()) {
    lidar_pose_scorer.emplace(world_from_odom, "localisation.");
    odometry_pose_scorer.emplace(world_from_odom, "localisation.dead_reckoning_");
    hit_scorer.emplace();
  }
  // The window in which an actor counts for the objects' recall: the grid's (objects can
  // come only from there), or without the grid one of the same size about the ego.
  const grid::ScrollingGridGeometry default_window{grid::GridOptions{}};
  // The ego's intended route: the scenario's ego path, as a navigation system would give it, in
  // the odometry frame (where the risk stage works).
  std::vector<Eigen::Vector2d> route_odom;
  for (const Eigen::Vector2d& p : scenario.ego.path) {
    route_odom.push_back(world_from_odom.Inverse() * p);
  }
  pipeline.SetEgoRoute(route_odom);
  pipeline.SetCarriageways(CarriagewaysOf(scenario.world, world_from_odom.Inverse()));
  pipeline.SetBuildings(
      Transformed(sim::BuildingOutlines(scenario.world), world_from_odom.Inverse()));
  std::optional<TrackingScorer> tracking_scorer;
  if (pipeline.tracking()) {
    const grid::GridOptions grid_options;
    tracking_scorer.emplace(world_from_odom,
                            SensorReach::Of(scenario.sensors, 0.5 * grid_options.width_cells *
                                                                  grid_options.cell_size_m));
  }
  std::optional<RiskScorer> risk_scorer;
  if (pipeline.risk()) {
    risk_scorer.emplace(world_from_odom, pipeline.risk()->options(), scenario.ego.path,
                        CarriagewaysOf(scenario.world, Pose2{}), scenario.expect,
                        result.contacts);
  }
  std::map<std::uint32_t, ObjectClass> warned_classes;  // track id -> class, for the summary
  bool snapshot_due = options.snapshot_s.has_value() && pipeline.grid() != nullptr;
  const TimeNs snapshot_at = options.snapshot_s ? FromSeconds(*options.snapshot_s) : 0;

  std::optional<io::Recorder> recorder;
  if (options.recording_path) {
    recorder.emplace(*options.recording_path);
    const sim::LidarOptions& l = scenario.sensors.lidar;
    const sim::StereoOptions& s = scenario.sensors.stereo;
    recorder->WriteStaticWorld(0, simulator.static_world());
    recorder->WriteMounts(0, Pose2(l.x_m, l.y_m, l.yaw_rad), Pose2(s.x_m, s.y_m, s.yaw_rad));
    if (pipeline.grid()) {
      recorder->WriteTransform(0, io::frames::kWorld, io::frames::kOdom,
                               simulator.ego_trajectory().At(0.0).pose);
    }
  }

  const auto after_cycle = [&](const LidarCycle& cycle) {
    const sim::TruthFrame& truth = log.truth[cycle.index];
    const TimeNs stamp = cycle.scan->stamp;
    if (grid_scorer) grid_scorer->Observe(*pipeline.grid(), truth);
    if (object_scorer && cycle.objects) {
      GridGeometry window;
      if (pipeline.grid()) {
        window = pipeline.grid()->grid().geometry().WindowGeometry();
      } else {
        window = default_window.WindowGeometry();
        window.origin_m = cycle.objects->ego_pose.translation -
                          0.5 * window.cell_size_m * Eigen::Vector2d(window.width, window.height);
      }
      object_scorer->Observe(*cycle.objects, truth, window);
    }
    const fusion::FusedObjectFrame* fused = pipeline.fused_objects();
    if (fusion_scorer && cycle.objects && fused && fused->stamp == stamp) {
      // The lidar objects with the covariance fusion gave them, so that fusion.lidar_nees_mean
      // scores what was fused.
      fusion_scorer->AddFrame(*fused, pipeline.fusion()->lidar_as_fused(),
                              pipeline.fusion()->stereo_at_lidar_time(),
                              eval::TrueObjectsInVehicleFrame(truth));
    }
    if (const LidarChainStage* chain = pipeline.lidar_chain()) {
      const Pose2& true_ego = truth.ego.state.pose;
      const bool processed = chain->last_stamp() && *chain->last_stamp() == stamp;
      lidar_pose_scorer->Observe(processed ? chain->last_state() : std::nullopt, true_ego);
      odometry_pose_scorer->Observe(chain->dead_reckoning().PoseAt(stamp), true_ego);
      if (processed) hit_scorer->Observe(chain->last_hits(), truth);
    }
    const TrackingStage* tracking = pipeline.tracking();
    const RiskStage* risk = pipeline.risk();
    if (tracking && tracking->last_stamp() == cycle.scan->stamp) {
      tracking_scorer->Observe(truth, tracking->tracks(),
                               tracking->baseline() ? &tracking->baseline_tracks() : nullptr);
      if (risk && risk->last_stamp() == cycle.scan->stamp) {
        risk_scorer->Observe(truth, tracking->tracks(), risk->last_assessment());
        if (!risk->events().empty() && risk->events().back().stamp == cycle.scan->stamp) {
          if (const auto id = risk->events().back().object_id) {
            for (const tracking::Track& t : tracking->tracks()) {
              if (t.id == *id) warned_classes[*id] = t.object_class;
            }
          }
        }
      }
    }
    if (snapshot_due && cycle.scan->stamp >= snapshot_at) {
      result.snapshots =
          WriteSnapshot(pipeline.grid()->grid(), options, cycle.scan->stamp);
      snapshot_due = false;
    }
    if (recorder) recorder->Write(truth);
    if (options.progress) options.progress(ToSeconds(cycle.scan->stamp), scenario.duration_s);
  };
  MessageLoopOptions loop_options;
  loop_options.recorder = recorder ? &*recorder : nullptr;
  loop_options.after_cycle = after_cycle;
  const MessageLoopResult loop =
      RunMessageLoop(SensorStreams{log.lidar, log.stereo, log.odometry}, pipeline, loop_options);

  result.messages_per_topic = loop.messages_per_topic;
  // Scoring, snapshots and progress are not the pipeline's time.
  result.wall_s = SecondsSince(run_start) - loop.after_cycle_s;
  result.metrics.scenario = scenario.name;
  result.metrics.values["timing.frames"] = static_cast<double>(result.lidar_frames);
  result.metrics.values["timing.pipeline_ms_median"] = eval::Median(loop.step_ms);
  result.metrics.values["timing.realtime_factor"] = scenario.duration_s / result.wall_s;
  if (grid_scorer) grid_scorer->Report(result.metrics.values, *pipeline.grid());
  if (object_scorer) object_scorer->Report(result.metrics.values);
  if (fusion_scorer) {
    for (const auto& [name, value] : fusion_scorer->Values()) result.metrics.values[name] = value;
  }
  if (tracking_scorer) tracking_scorer->Report(result.metrics.values);
  if (const TrackingStage* tracking = pipeline.tracking()) {
    if (!tracking->step_ms().empty()) {
      result.metrics.values["timing.tracking_ms_median"] = eval::Median(tracking->step_ms());
    }
    if (!tracking->baseline_step_ms().empty()) {
      result.metrics.values["timing.tracking_baseline_ms_median"] =
          eval::Median(tracking->baseline_step_ms());
    }
    result.stage_warnings = tracking->warnings();
    result.stage_warning_count = tracking->warning_count();
  }
  if (const RiskStage* risk = pipeline.risk()) {
    risk_scorer->Report(risk->events(), result.metrics.values);
    if (!risk->step_ms().empty()) {
      result.metrics.values["timing.risk_ms_median"] = eval::Median(risk->step_ms());
    }
    result.warnings = risk->events();
    for (const risk::WarningEvent& e : result.warnings) {
      const auto c = e.object_id ? warned_classes.find(*e.object_id) : warned_classes.end();
      result.warning_classes.push_back(c != warned_classes.end() ? c->second
                                                                 : ObjectClass::kUnknown);
    }
  }
  for (const auto* scorer : {&lidar_pose_scorer, &odometry_pose_scorer}) {
    if (*scorer) (*scorer)->Report(result.metrics.values);
  }
  if (hit_scorer) hit_scorer->Report(result.metrics.values);
  const LidarChainStage* chain = pipeline.lidar_chain();
  if (chain && !chain->localise_ms().empty()) {
    auto& v = result.metrics.values;
    v["lidar_chain.localise_ms_median"] = eval::Median(chain->localise_ms());
    v["lidar_chain.hits_ms_median"] = eval::Median(chain->hits_ms());
    v["lidar_chain.segment_ms_median"] = eval::Median(chain->segment_ms());
    v["lidar_chain.refused_scans"] = static_cast<double>(chain->refused_scans());
    v["lidar_chain.skipped_scans"] = static_cast<double>(chain->skipped_scans());
  }
  // The extraction time of the objects the pipeline uses.
  if (pipeline.lidar_objects_available()) {
    const std::vector<double>& extract_ms =
        pipeline.object_source() == LidarObjectSource::kSegmentation
            ? chain->segment_ms()
            : pipeline.grid()->objects_ms();
    if (!extract_ms.empty()) {
      result.metrics.values["lidar_objects.extract_ms_median"] = eval::Median(extract_ms);
    }
  }
  return result;
}

}  // namespace

RunResult RunScenario(const sim::Scenario& scenario, Pipeline& pipeline,
                      const RunOptions& options) {
  // Every parallel loop of the run (simulator and stages) shares this many threads; the
  // output does not depend on the number (each loop writes distinct cells in a fixed order).
  tbb::task_arena arena(options.threads);
  RunResult result;
  arena.execute([&] { result = RunInArena(scenario, pipeline, options); });
  return result;
}

risk::Carriageways CarriagewaysOf(const sim::World& world, const Pose2& frame_from_world) {
  if (world.preset != "four_way") return {};
  const double length = 2.0 * sim::kFourWayBlockExtentM;
  const double width = 2.0 * sim::kFourWayRoadHalfWidthM;
  const Eigen::Vector2d centre = frame_from_world * Eigen::Vector2d::Zero();
  return {risk::Footprint::Box(centre, frame_from_world.yaw, length, width),
          risk::Footprint::Box(centre, frame_from_world.yaw + 0.5 * kPi, length, width)};
}

PipelineOptions ForSensors(PipelineOptions options, const sim::Sensors& sensors) {
  options.tracking_options.detections.camera_fov_rad = sensors.stereo.fov_rad;
  options.tracking_options.detections.camera_max_depth_m = sensors.stereo.max_depth_m;
  return options;
}

}  // namespace lookout::app
