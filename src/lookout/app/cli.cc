#include "lookout/app/cli.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "lookout/app/output_files.h"
#include "lookout/app/replay.h"
#include "lookout/app/runner.h"
#include "lookout/app/slam_command.h"
#include "lookout/app/stage_benchmarks.h"
#include "lookout/core/input_error.h"
#include "lookout/eval/statistics.h"
#include "lookout/io/replay_log.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/sim/simulator.h"

namespace lookout::app {
namespace {

using nlohmann::json;

int DefaultThreads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

// Counts print as integers (151, not 151.0); JSON has no NaN or infinity, so those are null.
json NumberOrNull(double v) {
  if (!std::isfinite(v)) return nullptr;
  if (v == std::trunc(v) && std::fabs(v) < 9.0e15) return static_cast<std::int64_t>(v);
  return v;
}

json MetricsJson(const eval::ScenarioMetrics& m) {
  json values = json::object();
  for (const auto& [key, value] : m.values) values[key] = NumberOrNull(value);
  return {{"scenario", m.scenario}, {"metrics", std::move(values)}};
}

// The live progress line, on a terminal only: in a log it would be noise.
std::function<void(double, double)> ProgressLine(const std::string& name) {
  if (!isatty(STDERR_FILENO)) return nullptr;
  return [name](double t, double duration) {
    std::cerr << fmt::format("\r{}  t = {:6.2f} / {:.2f} s  {:3.0f} %", name, t, duration,
                             100.0 * t / duration)
              << std::flush;
  };
}

void ValidateThreads(int threads) {
  if (threads < 1) throw InputError("--threads", 0, "threads", "must be at least 1");
}

void PrintSummary(const RunResult& r, const std::string& source, const std::string& recording) {
  std::cout << fmt::format("scenario    {} ({})\n", r.scenario, source);
  std::cout << fmt::format("simulated   {:.2f} s\n", r.simulated_s);
  std::cout << fmt::format("frames      {} lidar, {} stereo, {} odometry\n", r.lidar_frames,
                           r.stereo_frames, r.odometry_frames);
  std::cout << "messages   ";
  for (const auto& [topic, count] : r.messages_per_topic) {
    std::cout << fmt::format(" {} {}", topic, count);
  }
  std::cout << "\n";
  std::cout << "contacts   ";
  if (r.contacts.empty()) std::cout << " none";
  for (const auto& [id, t] : r.contacts) std::cout << fmt::format(" {} at {:.2f} s", id, t);
  std::cout << "  (ground truth)\n";
  std::cout << "warnings   ";
  if (r.warnings.empty()) std::cout << " none";
  std::cout << "\n";
  for (std::size_t i = 0; i < r.warnings.size(); ++i) {
    const risk::WarningEvent& e = r.warnings[i];
    std::cout << fmt::format("  {:6.2f} s  {:<11}", ToSeconds(e.stamp), risk::ToString(e.level));
    if (e.object_id) {
      std::cout << fmt::format("  track {} ({})", *e.object_id, ToString(r.warning_classes[i]));
    }
    if (e.ttc_s) std::cout << fmt::format("  TTC {:.2f} s", *e.ttc_s);
    std::cout << "\n";
  }
  for (const std::string& w : r.stage_warnings) std::cerr << "lookout: warning: " << w << "\n";
  if (r.stage_warning_count > static_cast<std::int64_t>(r.stage_warnings.size())) {
    std::cerr << fmt::format(
        "lookout: warning: ... {} more\n",
        r.stage_warning_count - static_cast<std::int64_t>(r.stage_warnings.size()));
  }
  std::cout << fmt::format("wall time   {:.3f} s (sensor simulation {:.3f} s)\n", r.wall_s,
                           r.simulation_wall_s);
  std::cout << fmt::format("real time   {:.1f}x faster than real time\n",
                           r.simulated_s / r.wall_s);
  std::cout << fmt::format("recording   {}\n", recording);
}

// The pipeline's choices that the command line can make (docs/lidar-chain.md, docs/tracking.md,
// docs/risk.md).
struct PipelineChoices {
  std::string ego_pose = "odometry";
  std::string lidar_objects = "segmentation";
  std::string stereo_class = "on";
  std::string grid_scan_flow = "on";
  std::string grid_cluster_motion = "on";
  std::string grid_hidden_bodies = "on";
  std::string tracker = "mht";
  std::string risk_shape = "boxes";
  std::string pedestrian_model = "constant-velocity";
  std::string turn_hypotheses = "on";

  PipelineOptions Options() const {
    PipelineOptions o;
    o.stereo_class.enabled = stereo_class == "on";
    o.grid_filter.scan_flow.enabled = grid_scan_flow == "on";
    o.grid_filter.cluster_motion.enabled = grid_cluster_motion == "on";
    o.grid_filter.hidden_bodies.enabled = grid_hidden_bodies == "on";
    o.ego_pose = ego_pose == "odometry" ? EgoPoseMode::kDeadReckoning
                                        : EgoPoseMode::kLidarLocalisation;
    o.lidar_objects =
        lidar_objects == "grid" ? LidarObjectSource::kGrid : LidarObjectSource::kSegmentation;
    // The names are checked by CLI11 (IsMember) before they get here.
    o.tracking_options.tracker = *ParseTrackerKind(tracker);
    o.risk_options.risk.shape = *risk::ParseCollisionShape(risk_shape);
    o.risk_options.risk.pedestrian_model = *risk::ParsePedestrianModel(pedestrian_model);
    o.risk_options.risk.turn_hypotheses = turn_hypotheses == "on";
    return o;
  }
};

void AddPipelineChoices(CLI::App* command, PipelineChoices& choices) {
  command
      ->add_option("--ego-pose", choices.ego_pose,
                   "The grid's ego pose: lidar (the lidar chain's localisation) or odometry "
                   "(dead reckoning)")
      ->check(CLI::IsMember({"lidar", "odometry"}));
  command
      ->add_option("--lidar-objects", choices.lidar_objects,
                   "Lidar objects for fusion: segmentation (the scan's segments, the default) or "
                   "grid (the grid's rigid clusters)")
      ->check(CLI::IsMember({"grid", "segmentation"}));
  command
      ->add_option("--stereo-class", choices.stereo_class,
                   "The camera's classes as evidence for the grid's class layer: on or off")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--grid-scan-flow", choices.grid_scan_flow,
                   "The grid's search for newly seen occupancy guided by the scan pair's "
                   "displacement (grid/scan_flow.h): on (the default) or off")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--grid-cluster-motion", choices.grid_cluster_motion,
                   "Each rigid cluster of the grid measured whole from the scan pair and its "
                   "velocity given to its cells (grid/cluster_motion.h): on (the default) or off")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--grid-hidden-bodies", choices.grid_hidden_bodies,
                   "A rigid body of the grid that goes into a shadow carried whole at its "
                   "velocity (grid/hidden_bodies.h): on (the default) or off")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--tracker", choices.tracker,
                   "The tracker: mht (Reid's MHT with the IMM) or gnn (the baseline); the GNN "
                   "also runs beside the MHT")
      ->check(CLI::IsMember({"mht", "gnn"}));
  command
      ->add_option("--risk-shape", choices.risk_shape,
                   "Collision footprints: boxes (vehicles as oriented boxes) or circles (the "
                   "paper's)")
      ->check(CLI::IsMember({"boxes", "circles"}));
  command
      ->add_option("--pedestrian-model", choices.pedestrian_model,
                   "Pedestrian prediction: constant-velocity (with a sampled spread) or "
                   "growing-circle (the paper's)")
      ->check(CLI::IsMember({"constant-velocity", "growing-circle"}));
  command
      ->add_option("--turn-hypotheses", choices.turn_hypotheses,
                   "Vehicles approaching a junction of the map also predicted turning onto the "
                   "crossing road: on or off (straight on only, the paper's)")
      ->check(CLI::IsMember({"on", "off"}));
}

int Run(const std::string& scenario_path, std::string out_dir, int threads,
        std::optional<double> snapshot_s, double snapshot_max_speed_mps,
        const PipelineOptions& pipeline_options) {
  ValidateThreads(threads);
  const sim::Scenario scenario =
      scenario_path.empty() ? io::LoadDefaultScenario() : io::LoadScenarioFile(scenario_path);
  // Every input is checked before anything is written.
  if (snapshot_s && (!std::isfinite(*snapshot_s) || *snapshot_s < 0.0 ||
                     *snapshot_s > scenario.duration_s)) {
    throw InputError(
        "--snapshot", 0, "snapshot",
        fmt::format("must be a time within the scenario, 0 to {} s", scenario.duration_s));
  }
  if (!std::isfinite(snapshot_max_speed_mps) || snapshot_max_speed_mps <= 0.0) {
    throw InputError("--snapshot-max-speed", 0, "snapshot-max-speed", "must be a speed > 0 m/s");
  }
  if (out_dir.empty()) out_dir = (std::filesystem::path("lookout-out") / scenario.name).string();
  EnsureOutputDirectory(out_dir, "--out");
  const std::string recording = (std::filesystem::path(out_dir) / "recording.mcap").string();
  const std::string metrics_path = (std::filesystem::path(out_dir) / "metrics.json").string();

  Pipeline pipeline(ForSensors(pipeline_options, scenario.sensors));
  RunOptions options;
  options.threads = threads;
  options.recording_path = recording;
  options.snapshot_s = snapshot_s;
  options.snapshot_dir = out_dir;
  options.snapshot_max_speed_mps = snapshot_max_speed_mps;
  options.progress = ProgressLine(scenario.name);
  const RunResult result = RunScenario(scenario, pipeline, options);
  if (options.progress) std::cerr << "\n";
  WriteFileAtomically(metrics_path, MetricsJson(result.metrics).dump(2) + "\n");
  PrintSummary(result, scenario.source, recording);
  for (const std::string& png : result.snapshots) std::cout << fmt::format("snapshot    {}\n", png);
  return 0;
}

int Eval(const std::vector<std::string>& paths, const std::string& json_path, int threads,
         const PipelineOptions& pipeline_options) {
  ValidateThreads(threads);
  // Every file is checked before anything runs: a bad one refuses the whole command.
  std::vector<sim::Scenario> scenarios;
  scenarios.reserve(paths.size());
  for (const std::string& p : paths) scenarios.push_back(io::LoadScenarioFile(p));

  std::vector<eval::ScenarioMetrics> results;
  json list = json::array();
  for (const sim::Scenario& s : scenarios) {
    Pipeline pipeline(ForSensors(pipeline_options, s.sensors));
    RunOptions options;
    options.threads = threads;
    const RunResult r = RunScenario(s, pipeline, options);
    list.push_back(MetricsJson(r.metrics));
    results.push_back(r.metrics);
  }

  json summary = json::object();
  for (const auto& [key, k] : eval::Summarise(results)) {
    summary[key] = {{"count", k.count},
                    {"mean", NumberOrNull(k.mean)},
                    {"min", NumberOrNull(k.min)},
                    {"max", NumberOrNull(k.max)}};
  }
  const json document = {{"scenarios", std::move(list)}, {"summary", std::move(summary)}};

  // The human-readable table, on stderr so stdout can carry the JSON.
  for (const eval::ScenarioMetrics& m : results) {
    std::cerr << fmt::format("{:<28}", m.scenario);
    for (const auto& [key, value] : m.values) std::cerr << fmt::format("  {} {:.4g}", key, value);
    std::cerr << "\n";
  }
  if (json_path.empty()) {
    std::cout << document.dump(2) << "\n";
  } else {
    WriteFileAtomically(json_path, document.dump(2) + "\n");
  }
  return 0;
}

struct ReplayCommandOptions {
  std::string log_path;
  std::string out_dir;
  std::string json_path;
  io::ReplayLogOptions topics;
  int threads = DefaultThreads();
  PipelineOptions pipeline;
};

json ReplayJson(const io::ReplayLog& log, const eval::ScenarioMetrics& metrics) {
  json document = MetricsJson(metrics);
  document["source"] = log.source;
  document["format"] = io::LogFormatName(log.format);
  json counts = json::object();
  for (const auto& [name, n] : log.counts) counts[name] = n;
  document["degradations"] = std::move(counts);
  return document;
}

void PrintReplaySummary(const io::ReplayLog& log, const ReplayResult& r,
                        const std::string& recording, const std::string& metrics_path) {
  std::cout << fmt::format("log         {} ({}, {:.2f} s)\n", log.source,
                           io::LogFormatName(log.format), log.duration_s);
  for (const std::string& input : log.inputs) std::cout << fmt::format("read        {}\n", input);
  std::cout << fmt::format("frames      {} lidar, {} stereo, {} odometry\n", r.lidar_frames,
                           r.stereo_frames, r.odometry_frames);
  std::cout << "degraded   ";
  if (log.counts.empty()) std::cout << " nothing";
  for (const auto& [name, n] : log.counts) std::cout << fmt::format(" {} {}", name, n);
  const auto value = [&](const std::string& key) -> std::optional<double> {
    const auto it = r.metrics.values.find(key);
    if (it == r.metrics.values.end()) return std::nullopt;
    return it->second;
  };
  if (const auto skipped = value("replay.scans_without_pose"); skipped && *skipped > 0) {
    std::cout << fmt::format(" scans_without_pose {}", *skipped);
  }
  std::cout << "\n";
  std::cout << "messages   ";
  for (const auto& [topic, count] : r.messages_per_topic) {
    std::cout << fmt::format(" {} {}", topic, count);
  }
  std::cout << "\n";
  if (const auto n = value("people.grid.positions")) {
    std::cout << fmt::format(
        "people      {} annotated positions ({}): {:.1f} % with a dynamic grid object within "
        "0.5 m, {:.1f} % with any\n",
        *n, log.people_frame, 100.0 * value("people.grid.dynamic_share").value_or(0.0),
        100.0 * value("people.grid.any_share").value_or(0.0));
  }
  if (const auto n = value("people.segmentation.positions")) {
    std::cout << fmt::format(
        "people      {} annotated positions: {:.1f} % with a dynamic segment (lidar chain) within "
        "0.5 m, {:.1f} % with any\n",
        *n, 100.0 * value("people.segmentation.dynamic_share").value_or(0.0),
        100.0 * value("people.segmentation.any_share").value_or(0.0));
  }
  for (const auto& [prefix, name] : {std::pair{"people.tracking", "tracks"},
                                     std::pair{"people.tracking_baseline", "baseline"}}) {
    const auto mota = value(std::string(prefix) + ".mota");
    if (!mota) continue;
    const auto motp = value(std::string(prefix) + ".motp_m");
    std::cout << fmt::format(
        "{:<11} MOTA {:.1f} %, MOTP {}, {} id switches, {} false, {} missed of {} annotated in "
        "the benchmark's sector (0.75 m; Leigh et al.'s trackers: MOTA 10.2-11.2 %, MOTP "
        "0.15-0.17 m)\n",
        name, 100.0 * *mota, motp ? fmt::format("{:.2f} m", *motp) : std::string("-"),
        value(std::string(prefix) + ".id_switches").value_or(0.0),
        value(std::string(prefix) + ".false_positives").value_or(0.0),
        value(std::string(prefix) + ".misses").value_or(0.0),
        value("people.grid.sector_positions").value_or(0.0));
  }
  if (const auto ate = value("localisation.ate_rmse_m")) {
    std::cout << fmt::format(
        "ate         {:.3f} m RMSE, heading {:.2f} deg RMSE: the pipeline's ego pose against the "
        "log's reference poses (rigid alignment)\n",
        *ate, value("localisation.heading_rmse_deg").value_or(0.0));
  }
  std::cout << fmt::format("wall time   {:.3f} s\n", r.wall_s);
  if (r.duration_s > 0.0) {
    std::cout << fmt::format("real time   {:.1f}x faster than real time\n",
                             r.duration_s / r.wall_s);
  }
  std::cout << fmt::format("recording   {}\n", recording);
  if (!metrics_path.empty()) std::cout << fmt::format("metrics     {}\n", metrics_path);
}

int Replay(const ReplayCommandOptions& o) {
  ValidateThreads(o.threads);
  CheckOutputFilePath(o.json_path, "--json");
  // The whole log is read and checked before anything is written.
  const io::ReplayLog log = io::ReadReplayLog(o.log_path, o.topics);
  const std::string out_dir =
      o.out_dir.empty() ? (std::filesystem::path("lookout-out") / log.name).string() : o.out_dir;
  EnsureOutputDirectory(out_dir, "--out");
  for (const std::string& w : log.warnings) std::cerr << "lookout: warning: " << w << "\n";
  const std::string recording = (std::filesystem::path(out_dir) / "recording.mcap").string();

  PipelineOptions pipeline_options = o.pipeline;
  // A real scanner's beam without a return is not yet evidence of empty space here: on the
  // leg-tracker bag clearing along such beams made 296-331 false tracks of the segments
  // (docs/replay.md); the simulator's lidar, whose empty beams are empty, keeps it.
  pipeline_options.lidar_chain_options.no_return_clear_m = 0.0;
  Pipeline pipeline(pipeline_options);
  ReplayOptions options;
  options.threads = o.threads;
  options.recording_path = recording;
  options.progress = ProgressLine(log.name);
  const ReplayResult result = RunReplay(log, pipeline, options);
  if (options.progress) std::cerr << "\n";

  const std::string document = ReplayJson(log, result.metrics).dump(2) + "\n";
  std::string metrics_path;
  if (!log.people.empty() || !log.reference.empty()) {
    metrics_path = (std::filesystem::path(out_dir) / "metrics.json").string();
    WriteFileAtomically(metrics_path, document);
  }
  if (!o.json_path.empty()) WriteFileAtomically(o.json_path, document);
  PrintReplaySummary(log, result, recording, metrics_path);
  return 0;
}

// sim.realtime_factor: the default scenario's sensors, one thread, median of five runs.
double SimRealtimeFactor() {
  const sim::Simulator simulator(io::LoadDefaultScenario());
  std::vector<double> factors;
  for (int i = 0; i < 5; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const sim::SensorLog log = simulator.Run(1);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    factors.push_back(simulator.scenario().duration_s / wall);
  }
  return eval::Median(factors);
}

// pipeline.realtime_factor: the whole run of the default scenario (simulation and every stage
// that has landed, no recording), median of three runs.
double PipelineRealtimeFactor() {
  const sim::Scenario scenario = io::LoadDefaultScenario();
  std::vector<double> factors;
  for (int i = 0; i < 3; ++i) {
    Pipeline pipeline(PipelineOptions{});
    RunOptions options;
    options.threads = DefaultThreads();
    factors.push_back(RunScenario(scenario, pipeline, options).metrics.values.at(
        "timing.realtime_factor"));
  }
  return eval::Median(factors);
}

int Bench(const std::string& json_path) {
  // The grid on the default scenario's junction at t = 4 s (the oncoming car turning in front
  // of the ego, which has driven 44 m: tracked structure and newly revealed occupancy).
  const GridCycleFigures grid = MeasureGridCycle(io::LoadDefaultScenario(), 4.0, 15, 3);
  const json figures = {{"sim.realtime_factor", SimRealtimeFactor()},
                        {"grid.cycle_ms_median", grid.cycle_ms_median},
                        {"grid.reference_speedup", grid.reference_speedup},
                        {"grid.motion_ms_median", grid.motion_ms_median},
                        {"grid.reference_ms_median", grid.reference_ms_median},
                        {"tracking.mht_step_ms_median", MeasureMhtStepMs(30, 10, 10, 3, 51)},
                        {"risk.step_ms_median", MeasureRiskStepMs(30, 1000, 21)},
                        {"pipeline.realtime_factor", PipelineRealtimeFactor()}};
  for (const auto& [key, value] : figures.items()) {
    std::cerr << fmt::format("{:<28} {}\n", key, value.dump());
  }
  if (json_path.empty()) {
    std::cout << figures.dump(2) << "\n";
  } else {
    WriteFileAtomically(json_path, figures.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int RunCli(int argc, char** argv) {
  CLI::App cli{"Lookout: perception and collision warning at intersections"};
  cli.require_subcommand(1);

  std::string run_scenario, run_out;
  int threads = DefaultThreads();
  CLI::App* run = cli.add_subcommand(
      "run", "Simulate a scenario (the built-in default when none is given) and run the pipeline");
  run->add_option("scenario", run_scenario, "Scenario YAML file");
  run->add_option("--out", run_out, "Output directory (default lookout-out/NAME)");
  run->add_option("--threads", threads, "Worker threads (the output does not depend on it)");
  std::optional<double> snapshot_s;
  run->add_option("--snapshot", snapshot_s,
                  "Write PNGs of the grid (occupancy, speed map, class map) at T s");
  double snapshot_max_speed_mps = 20.0;
  run->add_option("--snapshot-max-speed", snapshot_max_speed_mps,
                  "Speed (m/s) at which the snapshot's speed map is full bright (default 20)");
  PipelineChoices choices;
  AddPipelineChoices(run, choices);

  std::vector<std::string> eval_scenarios;
  std::string eval_json;
  CLI::App* eval_cmd = cli.add_subcommand("eval", "Run and score scenarios; JSON report");
  eval_cmd->add_option("scenarios", eval_scenarios, "Scenario YAML files")->required();
  eval_cmd->add_option("--json", eval_json, "Write the JSON report here instead of stdout");
  eval_cmd->add_option("--threads", threads, "Worker threads (the output does not depend on it)");
  AddPipelineChoices(eval_cmd, choices);

  std::string bench_json;
  CLI::App* bench = cli.add_subcommand("bench", "Headline performance figures (JSON)");
  bench->add_option("--json", bench_json, "Write the JSON here instead of stdout");

  ReplayCommandOptions replay_options;
  CLI::App* replay = cli.add_subcommand(
      "replay", "Run the pipeline on a recorded log: CARMEN, ROS1 bag (or its .zip), MCAP");
  replay->add_option("log", replay_options.log_path, "The log (.log, .clf, .gz, .bag, .zip, .mcap)")
      ->required();
  replay->add_option("--out", replay_options.out_dir,
                     "Output directory (default lookout-out/NAME)");
  replay->add_option("--json", replay_options.json_path, "Also write the metrics JSON here");
  replay->add_option("--scan-topic", replay_options.topics.scan_topic,
                     "The laser scan topic, when the log has several");
  replay->add_option("--odom-topic", replay_options.topics.odom_topic,
                     "The odometry topic, when the log has several");
  replay->add_option("--truth-topic", replay_options.topics.truth_topic,
                     "The ground-truth topic (leg_tracker/Person), when the log has several");
  replay->add_option("--threads", replay_options.threads,
                     "Worker threads (the output does not depend on it)");
  PipelineChoices replay_choices;
  AddPipelineChoices(replay, replay_choices);

  SlamCommandOptions slam_options;
  CLI::App* slam = cli.add_subcommand(
      "slam", "Lidar localisation and local mapping of a CARMEN log (raw odometry and scans)");
  slam->add_option("log", slam_options.log_path, "CARMEN log (plain or gzip)")->required();
  slam->add_option("--trajectory", slam_options.trajectory_path,
                   "Write the trajectory here: lines 't x y theta', one per odometry reading "
                   "and one per scan");
  slam->add_option("--map", slam_options.map_path, "Write the map here as a PNG");
  slam->add_flag("--odometry-only", slam_options.odometry_only,
                 "Dead reckoning alone: the baseline that shows what the scans add");
  slam->add_option("--seed", slam_options.seed,
                   "Seed of the particle filter's random draws (the same seed, the same bytes)");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version are successes; any other parse error is a bad option: exit 2.
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (run->parsed()) {
      return Run(run_scenario, run_out, threads, snapshot_s, snapshot_max_speed_mps,
                 choices.Options());
    }
    if (eval_cmd->parsed()) {
      return Eval(eval_scenarios, eval_json, threads, choices.Options());
    }
    if (bench->parsed()) return Bench(bench_json);
    if (slam->parsed()) return RunSlamCommand(slam_options);
    if (replay->parsed()) {
      replay_options.pipeline = replay_choices.Options();
      return Replay(replay_options);
    }
  } catch (const InputError& e) {
    std::cerr << "lookout: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lookout: error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}

}  // namespace lookout::app
