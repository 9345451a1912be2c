// lookout_fusion_errors SCENARIO... [--lidar-objects grid|segmentation] [--csv FILE]
//
// What each sensor's point gets wrong, against the truth (docs/fusion.md, "The two sources
// measured"): every scenario runs through the pipeline as `lookout eval` runs it, and at each
// lidar cycle every lidar object and every stereo point (at the lidar stamp) is matched one to
// one to a true actor's front point (eval::MatchToTruth, 2 m), whether or not fusion paired it.
// Each error is split along the ray from the lidar's origin to the true point and across it,
// and set against the object's own covariance (NEES, 2 for an honest one).
//
// Printed: per scenario and source, then per source over all scenarios by class, range and the
// share of the actor the lidar sees, a Markdown table of: count, mean error along and across the
// ray (the bias), their standard deviations (the spread), the reported sigma along and across
// (the root of the mean reported variance), and the mean NEES. --csv writes one row per matched
// object for a closer look.
//
// Exit codes as the CLI's: 2 with one line on stderr for a bad scenario or option.

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lookout/app/message_loop.h"
#include "lookout/app/pipeline.h"
#include "lookout/core/input_error.h"
#include "lookout/eval/fusion_metrics.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/sim/simulator.h"

namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using lookout::ObjectClass;

struct Sample {
  std::string scenario;
  std::string source;  // "lidar" or "stereo"
  double t_s = 0.0;
  int actor = 0;
  ObjectClass object_class = ObjectClass::kUnknown;
  double range_m = 0.0;        // of the true point from the lidar
  double visible_lidar = 0.0;  // the actor's visible fraction for the lidar
  double speed_mps = 0.0;
  bool paired = false;         // fused with an object of the other sensor
  double along_m = 0.0;        // error along the ray (positive: further than the truth)
  double across_m = 0.0;
  double var_along = 0.0;      // the object's own covariance in the same axes
  double var_across = 0.0;
  double nees = 0.0;
};

struct Summary {
  int n = 0;
  double sum_along = 0.0, sum_across = 0.0, sum2_along = 0.0, sum2_across = 0.0;
  double sum_var_along = 0.0, sum_var_across = 0.0, sum_nees = 0.0;

  void Add(const Sample& s) {
    ++n;
    sum_along += s.along_m;
    sum_across += s.across_m;
    sum2_along += s.along_m * s.along_m;
    sum2_across += s.across_m * s.across_m;
    sum_var_along += s.var_along;
    sum_var_across += s.var_across;
    sum_nees += s.nees;
  }
  std::string Row(const std::string& label) const {
    const double k = n;
    const double mean_a = sum_along / k, mean_c = sum_across / k;
    const double sd_a = std::sqrt(std::max(0.0, sum2_along / k - mean_a * mean_a));
    const double sd_c = std::sqrt(std::max(0.0, sum2_across / k - mean_c * mean_c));
    return fmt::format("| {} | {} | {:+.3f} | {:+.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.2f} |",
                       label, n, mean_a, mean_c, sd_a, sd_c, std::sqrt(sum_var_along / k),
                       std::sqrt(sum_var_across / k), sum_nees / k);
  }
};

constexpr const char* kHeader =
    "| {} | n | bias along m | bias across m | sd along m | sd across m | sigma along m | "
    "sigma across m | NEES |\n|---|---|---|---|---|---|---|---|---|";

Sample Score(const Vector2d& point, const Matrix2d& covariance, const Vector2d& truth,
             const Vector2d& lidar_origin) {
  Sample s;
  const Vector2d ray = (truth - lidar_origin).normalized();
  const Vector2d normal(-ray.y(), ray.x());
  const Vector2d e = point - truth;
  s.range_m = (truth - lidar_origin).norm();
  s.along_m = e.dot(ray);
  s.across_m = e.dot(normal);
  s.var_along = ray.dot(covariance * ray);
  s.var_across = normal.dot(covariance * normal);
  s.nees = e.dot(covariance.inverse() * e);
  return s;
}

std::string RangeBin(double r) {
  if (r < 10.0) return "0-10 m";
  if (r < 20.0) return "10-20 m";
  if (r < 30.0) return "20-30 m";
  return "30+ m";
}

std::string VisibleBin(double v) {
  if (v < 0.5) return "seen < 50 %";
  if (v < 0.9) return "seen 50-90 %";
  return "seen >= 90 %";
}

void RunOne(const lookout::sim::Scenario& scenario, lookout::app::LidarObjectSource source,
            std::vector<Sample>& out) {
  namespace app = lookout::app;
  namespace eval = lookout::eval;
  app::PipelineOptions options;
  options.lidar_objects = source;
  options.tracking = false;  // nothing here reads the tracks
  app::Pipeline pipeline(options);
  if (pipeline.fusion() == nullptr) throw std::logic_error("the pipeline runs no fusion");
  const lookout::fusion::FusionEngine& engine = *pipeline.fusion();
  const lookout::sim::Simulator simulator(scenario);
  const lookout::sim::SensorLog log = simulator.Run(1);
  app::MessageLoopOptions loop;
  loop.after_cycle = [&](const app::LidarCycle& cycle) {
    const lookout::fusion::FusedObjectFrame* fused = pipeline.fused_objects();
    if (!cycle.objects || !fused || fused->stamp != cycle.scan->stamp) return;
    const lookout::sim::TruthFrame& truth = log.truth[cycle.index];
    const std::vector<eval::TrueObject> objects = eval::TrueObjectsInVehicleFrame(truth);
    const Vector2d origin = fused->mount.translation;
    const std::vector<Vector2d> true_points = eval::TrueFrontPoints(objects, origin);
    std::map<std::uint32_t, bool> lidar_paired, stereo_paired;
    for (const auto& f : fused->objects) {
      if (f.lidar_id) lidar_paired[*f.lidar_id] = f.sensor_count == 2;
      if (f.stereo_id) stereo_paired[*f.stereo_id] = f.sensor_count == 2;
    }
    const auto add = [&](const char* name, const std::vector<Vector2d>& points,
                         const std::vector<Matrix2d>& covariances,
                         const std::vector<bool>& paired) {
      const std::vector<int> match = eval::MatchToTruth(points, true_points, 2.0);
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (match[i] < 0) continue;
        const auto j = static_cast<std::size_t>(match[i]);
        Sample s = Score(points[i], covariances[i], true_points[j], origin);
        const lookout::sim::ActorTruth& actor = truth.actors[j];
        s.scenario = scenario.name;
        s.source = name;
        s.t_s = lookout::ToSeconds(cycle.scan->stamp);
        s.actor = actor.index;
        s.object_class = actor.object_class;
        s.visible_lidar = actor.visible_fraction_lidar;
        s.speed_mps = std::abs(actor.state.speed_mps);
        s.paired = paired[i];
        out.push_back(s);
      }
    };
    std::vector<Vector2d> points;
    std::vector<Matrix2d> covariances;
    std::vector<bool> paired;
    // As fused: with the covariance fusion gave each (the camera's class where it paired).
    for (const lookout::LidarObject& o : engine.lidar_as_fused().objects) {
      points.push_back(o.point_m);
      covariances.push_back(o.point_covariance);
      paired.push_back(lidar_paired[o.id]);
    }
    add("lidar", points, covariances, paired);
    points.clear();
    covariances.clear();
    paired.clear();
    for (const lookout::stereo::StereoPoint& p : engine.stereo_at_lidar_time()) {
      points.push_back(p.point.point_m);
      covariances.push_back(p.point.covariance);
      paired.push_back(stereo_paired[p.id]);
    }
    add("stereo", points, covariances, paired);
  };
  app::RunMessageLoop(app::SensorStreams{log.lidar, log.stereo, log.odometry}, pipeline, loop);
}

void PrintGrouped(const std::vector<Sample>& samples, const std::string& title,
                  const std::function<std::string(const Sample&)>& key) {
  for (const char* source : {"lidar", "stereo"}) {
    std::map<std::string, Summary> groups;
    Summary all;
    for (const Sample& s : samples) {
      if (s.source != source) continue;
      groups[key(s)].Add(s);
      all.Add(s);
    }
    if (all.n == 0) continue;
    std::printf("\n%s objects by %s\n\n", source, title.c_str());
    std::puts(fmt::format(fmt::runtime(kHeader), title).c_str());
    for (const auto& [label, summary] : groups) std::puts(summary.Row(label).c_str());
    std::puts(all.Row("all").c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> paths;
    std::optional<std::string> csv;
    auto source = lookout::app::LidarObjectSource::kGrid;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--lidar-objects" && i + 1 < argc) {
        const std::string v = argv[++i];
        if (v == "grid") {
          source = lookout::app::LidarObjectSource::kGrid;
        } else if (v == "segmentation") {
          source = lookout::app::LidarObjectSource::kSegmentation;
        } else {
          throw lookout::InputError("command line", 0, "--lidar-objects",
                                    "must be grid or segmentation");
        }
      } else if (arg == "--csv" && i + 1 < argc) {
        csv = argv[++i];
      } else {
        paths.push_back(arg);
      }
    }
    if (paths.empty()) {
      std::fputs("usage: lookout_fusion_errors SCENARIO... [--lidar-objects grid|segmentation] "
                 "[--csv FILE]\n", stderr);
      return 2;
    }
    std::vector<Sample> samples;
    for (const std::string& p : paths) RunOne(lookout::io::LoadScenarioFile(p), source, samples);
    PrintGrouped(samples, "scenario", [](const Sample& s) { return s.scenario; });
    PrintGrouped(samples, "class", [](const Sample& s) {
      return std::string(lookout::ToString(s.object_class));
    });
    PrintGrouped(samples, "range", [](const Sample& s) { return RangeBin(s.range_m); });
    PrintGrouped(samples, "visible", [](const Sample& s) { return VisibleBin(s.visible_lidar); });
    PrintGrouped(samples, "paired", [](const Sample& s) {
      return std::string(s.paired ? "paired" : "alone");
    });
    if (csv) {
      std::ofstream f(*csv);
      f << "scenario,source,t_s,actor,class,range_m,visible_lidar,speed_mps,paired,along_m,"
           "across_m,var_along,var_across,nees\n";
      for (const Sample& s : samples) {
        f << fmt::format("{},{},{:.3f},{},{},{:.3f},{:.3f},{:.3f},{},{:.4f},{:.4f},{:.6f},{:.6f},"
                         "{:.3f}\n",
                         s.scenario, s.source, s.t_s, s.actor, lookout::ToString(s.object_class),
                         s.range_m, s.visible_lidar, s.speed_mps, s.paired ? 1 : 0, s.along_m,
                         s.across_m, s.var_along, s.var_across, s.nees);
      }
    }
    return 0;
  } catch (const lookout::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lookout_fusion_errors: %s\n", e.what());
    return 1;
  }
}
