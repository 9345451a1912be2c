#include "lookout/app/slam_command.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "lookout/app/output_files.h"
#include "lookout/core/input_error.h"
#include "lookout/eval/relation_error.h"
#include "lookout/eval/trajectory_error.h"
#include "lookout/eval/trajectory_io.h"

namespace lookout::app {

std::vector<lidar::SlamRecord> SlamRecordsOf(const io::CarmenLog& log) {
  std::vector<lidar::SlamRecord> records;
  records.reserve(log.records.size());
  for (const io::CarmenRecord& r : log.records) records.push_back({r.t_s, r.odometry, r.scan});
  return records;
}

lidar::SlamOptions CarmenSlamOptions() {
  lidar::SlamOptions options;
  options.motion.kind = lidar::MotionModelKind::kDifferentialDrive;
  // The robots' odometry is poor (steps of 1 m with errors of tenths of a metre and radian),
  // so the motion model's spread is wide, and the estimate along a corridor's axis, where the
  // scans do not decide, is the particles' weighted mean: its Monte Carlo noise falls with the
  // square root of their number. 100 particles against the vehicle's 30 took the worst ATE over
  // seeds 1-5 on aces from 0.86 to 0.19 m (docs/lidar-slam.md, "Seeds").
  options.filter.particle_count = 100;
  // Their odometry's heading errors sometimes pass the search's heading window (csail's scan
  // 292: 0.18 rad against 0.17): a best heading on the window's edge extends the window to
  // twice its width. Over seeds 1-5 csail's worst ATE 0.242 -> 0.207 m, the other goal logs
  // within 1 cm (docs/lidar-slam.md, "Seeds").
  options.matcher.search_yaw_edge_extend = 2.0;
  return options;
}

ScanPairs PairsAtScans(const io::CarmenLog& log, const lidar::SlamResult& result) {
  ScanPairs pairs;
  std::size_t scan = 0;
  for (const io::CarmenRecord& r : log.records) {
    if (!r.scan) continue;
    if (scan < result.scan_states.size() && r.reference_pose &&
        result.scan_states[scan].stamp == FromSeconds(r.t_s)) {
      pairs.estimate.push_back(result.scan_states[scan].pose);
      pairs.reference.push_back(*r.reference_pose);
    }
    ++scan;
  }
  return pairs;
}

eval::AbsoluteTrajectoryError ReferenceError(const io::CarmenLog& log,
                                             const lidar::SlamResult& result) {
  const ScanPairs pairs = PairsAtScans(log, result);
  if (pairs.estimate.size() < 2) return {};
  return eval::AbsoluteErrorOfPairs(pairs.estimate, pairs.reference);
}

eval::RelationError ReferenceRelationError(const io::CarmenLog& log,
                                           const lidar::SlamResult& result,
                                           double min_travel_m) {
  const ScanPairs pairs = PairsAtScans(log, result);
  if (pairs.estimate.size() < 2) return {};
  eval::Trajectory2 estimate;
  eval::Trajectory2 reference;
  for (std::size_t i = 0; i < pairs.estimate.size(); ++i) {
    estimate.push_back({static_cast<double>(i), pairs.estimate[i]});
    reference.push_back({static_cast<double>(i), pairs.reference[i]});
  }
  eval::RelationGeneratorOptions generator;
  generator.min_travel_m = min_travel_m;
  return eval::ComputeRelationError(estimate, eval::GenerateRelations(reference, generator));
}

io::Image8 MapImage(const lidar::MapRaster& map) {
  const int w = std::max(1, map.geometry.width);
  const int h = std::max(1, map.geometry.height);
  io::Image8 image = io::Image8::Filled(w, h, io::PixelFormat::kGray8, 128);
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      const double l = static_cast<double>(
          map.log_odds[static_cast<std::size_t>(map.geometry.LinearIndex({x, y}))]);
      const double p_occupied = 1.0 / (1.0 + std::exp(-l));
      // Row 0 of the picture is the map's top (largest y).
      image.pixels[image.Offset(x, h - 1 - y)] =
          static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - p_occupied)));
    }
  }
  return image;
}

int RunSlamCommand(const SlamCommandOptions& options) {
  CheckOutputFilePath(options.trajectory_path, "--trajectory");
  CheckOutputFilePath(options.map_path, "--map");
  if (!options.map_path.empty() && std::filesystem::path(options.map_path).extension() != ".png") {
    throw InputError(options.map_path, 0, "--map", "must name a .png file");
  }
  const io::CarmenLog log = io::ReadCarmenLog(options.log_path);
  if (log.ScanCount() == 0) {
    throw InputError(options.log_path, 0, "FLASER", "the log holds no laser scan");
  }
  const std::vector<lidar::SlamRecord> records = SlamRecordsOf(log);

  lidar::SlamOptions slam_options = CarmenSlamOptions();
  slam_options.filter.seed = options.seed;
  // Wall and processor time: on a shared machine the processor time is the figure that says
  // what one core does (the run is single-threaded).
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const lidar::SlamResult result = lidar::RunSlam(records, slam_options, options.odometry_only);
  const double cpu_s =
      static_cast<double>(std::clock() - cpu_start) / static_cast<double>(CLOCKS_PER_SEC);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  eval::Trajectory2 trajectory;
  trajectory.reserve(result.trajectory.size());
  for (const lidar::TrajectoryPoint& p : result.trajectory) trajectory.push_back({p.t_s, p.pose});
  if (!options.trajectory_path.empty()) eval::WriteTrajectory(options.trajectory_path, trajectory);
  if (!options.map_path.empty()) io::WritePng(options.map_path, MapImage(result.map));

  const double duration_s = log.records.back().t_s - log.records.front().t_s;
  std::cout << fmt::format("log         {} ({} records, {} scans, {} lines skipped)\n",
                           options.log_path, log.records.size(), log.ScanCount(),
                           log.skipped_lines);
  std::cout << fmt::format("mode        {}\n",
                           options.odometry_only ? "odometry only (dead reckoning)"
                                                 : fmt::format("particle filter, {} particles",
                                                               slam_options.filter.particle_count));
  std::cout << fmt::format("scans used  {} ({} records refused)\n", result.scans_used,
                           result.records_refused);
  std::cout << fmt::format(
      "wall time   {:.3f} s, processor {:.3f} s (localisation and mapping, log read excluded)\n",
      wall_s, cpu_s);
  if (std::isfinite(duration_s) && duration_s > 0.0) {
    std::cout << fmt::format(
        "real time   {:.1f}x faster than real time (log {:.1f} s; {:.1f}x by processor time)\n",
        duration_s / wall_s, duration_s, duration_s / std::max(cpu_s, 1e-9));
  } else {
    std::cout << "real time   unknown (the log's times do not span an interval)\n";
  }
  if (const eval::AbsoluteTrajectoryError ate = ReferenceError(log, result); ate.matched >= 2) {
    std::cout << fmt::format(
        "ate         {:.3f} m RMSE, heading {:.2f} deg RMSE, against the log's reference poses "
        "({} scans, rigid alignment)\n",
        ate.ate_rmse_m, RadToDeg(ate.heading_rmse_rad), ate.matched);
  }
  if (const eval::RelationError rel = ReferenceRelationError(log, result); rel.used > 0) {
    std::cout << fmt::format(
        "relations   {:.3f} +- {:.3f} m, {:.2f} +- {:.2f} deg (mean +- deviation over {} "
        "relations of 10 m of reference path, Kuemmerle et al.)\n",
        rel.translation_mean_m, rel.translation_std_m, RadToDeg(rel.rotation_mean_rad),
        RadToDeg(rel.rotation_std_rad), rel.used);
  }
  if (!options.trajectory_path.empty()) {
    std::cout << fmt::format("trajectory  {}\n", options.trajectory_path);
  }
  if (!options.map_path.empty()) std::cout << fmt::format("map         {}\n", options.map_path);
  return 0;
}

}  // namespace lookout::app
