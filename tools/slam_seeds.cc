// lookout_slam_seeds LOG... [--seeds FIRST-LAST] [--set NAME=VALUE]... [--segments N]
//
// How `lookout slam`'s figure moves with the seed of the particle filter: each CARMEN log is
// localised once per seed (the same run as `lookout slam LOG --seed S`), and its ATE against the
// log's corrected poses printed per seed, with the median, the worst and the mean, and the processor time's
// real-time factor. A Markdown table on stdout (docs/lidar-slam.md, "Seeds").
//
// --set changes one option of the localisation for the run (the names of slam_options.h,
// "filter.particle_count=60"): the sensitivity of the figure to the option, measured.
//
// --segments N: after each log's row, where along the trajectory the error of the first seed
// comes from: the scans cut into N spans of equal count, and for each the path length, the RMSE
// of the position error after the whole trajectory's rigid alignment, and the translation error
// of the 10 m relations that start in it (mean, and the worst with its two scans). A span whose relations are good and
// whose aligned error is large inherits a bend made before it.
//
// Exit codes as the CLI's: 2 with one line on stderr for a bad log or option, 1 otherwise.

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lookout/app/slam_command.h"
#include "lookout/core/input_error.h"
#include "lookout/eval/statistics.h"
#include "lookout/eval/trajectory_error.h"

namespace {

using lookout::InputError;
using lookout::lidar::SlamOptions;

// The options --set may change, by the name slam_options.h gives them.
std::map<std::string, std::function<void(SlamOptions&, double)>> Settable() {
  std::map<std::string, std::function<void(SlamOptions&, double)>> m;
  m["filter.particle_count"] = [](SlamOptions& o, double v) { o.filter.particle_count = static_cast<int>(v); };
  m["filter.particle_refine_iterations"] = [](SlamOptions& o, double v) { o.filter.particle_refine_iterations = static_cast<int>(v); };
  m["filter.refine_with_prior"] = [](SlamOptions& o, double v) { o.filter.refine_with_prior = v != 0.0; };
  m["filter.weight_prior_share"] = [](SlamOptions& o, double v) { o.filter.weight_prior_share = v; };
  m["filter.resample_ess_share"] = [](SlamOptions& o, double v) { o.filter.resample_ess_share = v; };
  m["matcher.point_spacing_m"] = [](SlamOptions& o, double v) { o.matcher.point_spacing_m = v; };
  m["matcher.max_points"] = [](SlamOptions& o, double v) { o.matcher.max_points = static_cast<int>(v); };
  m["matcher.sigma_m"] = [](SlamOptions& o, double v) { o.matcher.sigma_m = v; };
  m["matcher.effective_beams"] = [](SlamOptions& o, double v) { o.matcher.effective_beams = v; };
  m["matcher.search_xy_base_m"] = [](SlamOptions& o, double v) { o.matcher.search_xy_base_m = v; };
  m["matcher.search_xy_per_m"] = [](SlamOptions& o, double v) { o.matcher.search_xy_per_m = v; };
  m["matcher.search_yaw_base_rad"] = [](SlamOptions& o, double v) { o.matcher.search_yaw_base_rad = v; };
  m["matcher.search_yaw_per_rad"] = [](SlamOptions& o, double v) { o.matcher.search_yaw_per_rad = v; };
  m["matcher.search_yaw_per_m"] = [](SlamOptions& o, double v) { o.matcher.search_yaw_per_m = v; };
  m["matcher.max_search_xy_m"] = [](SlamOptions& o, double v) { o.matcher.max_search_xy_m = v; };
  m["matcher.max_search_yaw_rad"] = [](SlamOptions& o, double v) { o.matcher.max_search_yaw_rad = v; };
  m["matcher.search_yaw_edge_extend"] = [](SlamOptions& o, double v) { o.matcher.search_yaw_edge_extend = v; };
  m["matcher.coarse_sigma_m"] = [](SlamOptions& o, double v) { o.matcher.coarse_sigma_m = v; };
  m["matcher.gauss_newton_iterations"] = [](SlamOptions& o, double v) { o.matcher.gauss_newton_iterations = static_cast<int>(v); };
  m["motion.alpha1"] = [](SlamOptions& o, double v) { o.motion.alpha1 = v; };
  m["motion.alpha2"] = [](SlamOptions& o, double v) { o.motion.alpha2 = v; };
  m["motion.alpha3"] = [](SlamOptions& o, double v) { o.motion.alpha3 = v; };
  m["motion.alpha4"] = [](SlamOptions& o, double v) { o.motion.alpha4 = v; };
  m["map.cell_size_m"] = [](SlamOptions& o, double v) { o.map.cell_size_m = v; };
  m["map.log_odds_hit"] = [](SlamOptions& o, double v) { o.map.log_odds_hit = static_cast<float>(v); };
  m["map.log_odds_miss"] = [](SlamOptions& o, double v) { o.map.log_odds_miss = static_cast<float>(v); };
  m["map.field_max_distance_m"] = [](SlamOptions& o, double v) { o.map.field_max_distance_m = v; };
  return m;
}

std::string LogName(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  for (const std::string suffix : {".gz", ".log", ".clf", "-corrected"}) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) name.resize(name.size() - suffix.size());
  }
  return name;
}

// The --segments table of one run (see the top of the file).
std::string Segments(const lookout::io::CarmenLog& log, const lookout::lidar::SlamResult& result,
                     int segments) {
  const lookout::app::ScanPairs pairs = lookout::app::PairsAtScans(log, result);
  const std::size_t n = pairs.estimate.size();
  if (n < 2) return {};
  const lookout::Pose2 align =
      lookout::eval::AbsoluteErrorOfPairs(pairs.estimate, pairs.reference).alignment;
  // Each scan's relation: to the first scan at least 10 m further along the reference path.
  std::vector<double> path(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    path[i] = path[i - 1] +
              (pairs.reference[i].translation - pairs.reference[i - 1].translation).norm();
  }
  std::string out = "\n| scans | path (m) | aligned error RMSE (m) | 10 m relations: mean (m) | worst (m) | worst between scans |\n|---|---:|---:|---:|---:|---:|\n";
  std::size_t j = 0;
  for (int k = 0; k < segments; ++k) {
    const std::size_t begin = n * static_cast<std::size_t>(k) / static_cast<std::size_t>(segments);
    const std::size_t end = n * static_cast<std::size_t>(k + 1) / static_cast<std::size_t>(segments);
    if (begin >= end) continue;
    double squared = 0.0, relation_sum = 0.0, relation_worst = 0.0;
    std::size_t worst_from = begin, worst_to = begin;
    int relations = 0;
    for (std::size_t i = begin; i < end; ++i) {
      squared += ((align * pairs.estimate[i]).translation - pairs.reference[i].translation).squaredNorm();
      j = std::max(j, i + 1);
      while (j < n && path[j] - path[i] < 10.0) ++j;
      if (j >= n) continue;
      const lookout::Pose2 truth = pairs.reference[i].Inverse() * pairs.reference[j];
      const lookout::Pose2 estimate = pairs.estimate[i].Inverse() * pairs.estimate[j];
      const double e = (truth.Inverse() * estimate).translation.norm();
      relation_sum += e;
      if (e > relation_worst) {
        relation_worst = e;
        worst_from = i;
        worst_to = j;
      }
      ++relations;
    }
    out += fmt::format("| {}-{} | {:.0f} | {:.3f} | {} | {} | {} |\n", begin, end - 1,
                       path[end - 1] - path[begin],
                       std::sqrt(squared / static_cast<double>(end - begin)),
                       relations ? fmt::format("{:.3f}", relation_sum / relations) : "-",
                       relations ? fmt::format("{:.3f}", relation_worst) : "-",
                       relations ? fmt::format("{}-{}", worst_from, worst_to) : "-");
  }
  return out + "\n";
}

// The whole of `text` as a number, or an InputError naming the flag (a usage error: exit 2, where
// std::stoi's exception would have exited 1 as a failure of the run).
template <typename T>
T ParseNumber(const std::string& flag, const std::string& text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) throw InputError(flag, 0, text, "not a number");
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> logs;
    int first_seed = 1, last_seed = 5, segments = 0;
    SlamOptions options = lookout::app::CarmenSlamOptions();
    const auto settable = Settable();
    std::vector<std::string> settings;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--seeds" && i + 1 < argc) {
        const std::string v = argv[++i];
        if (std::sscanf(v.c_str(), "%d-%d", &first_seed, &last_seed) != 2 || first_seed > last_seed) {
          throw InputError("--seeds", 0, "seeds", "expected FIRST-LAST, as 1-5");
        }
      } else if (a == "--segments" && i + 1 < argc) {
        segments = ParseNumber<int>("--segments", argv[++i]);
        if (segments < 1) throw InputError("--segments", 0, "segments", "expected a count >= 1");
      } else if (a == "--set" && i + 1 < argc) {
        const std::string v = argv[++i];
        const std::size_t eq = v.find('=');
        const auto it = settable.find(v.substr(0, eq));
        if (eq == std::string::npos || it == settable.end()) {
          throw InputError("--set", 0, v.substr(0, eq), "not an option --set knows");
        }
        it->second(options, ParseNumber<double>("--set", v.substr(eq + 1)));
        settings.push_back(v);
      } else {
        logs.push_back(a);
      }
    }
    options.Validate("--set");
    if (!settings.empty()) std::printf("options changed: %s\n\n", fmt::format("{}", fmt::join(settings, ", ")).c_str());
    std::string header = "| log |";
    std::string rule = "|---|";
    for (int s = first_seed; s <= last_seed; ++s) {
      header += fmt::format(" seed {} |", s);
      rule += "---:|";
    }
    std::printf("%s median | worst | mean | real time (processor) |\n%s---:|---:|---:|---:|\n", header.c_str(), rule.c_str());
    for (const std::string& path : logs) {
      const lookout::io::CarmenLog log = lookout::io::ReadCarmenLog(path);
      const std::vector<lookout::lidar::SlamRecord> records = lookout::app::SlamRecordsOf(log);
      std::string row = "| " + LogName(path) + " |";
      double worst = 0.0, sum = 0.0, cpu = 0.0;
      std::vector<double> ates;
      std::string spans;
      for (int s = first_seed; s <= last_seed; ++s) {
        options.filter.seed = static_cast<std::uint64_t>(s);
        const std::clock_t start = std::clock();
        const lookout::lidar::SlamResult result = lookout::lidar::RunSlam(records, options);
        cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
        const double ate = lookout::app::ReferenceError(log, result).ate_rmse_m;
        if (segments > 0 && s == first_seed) spans = Segments(log, result, segments);
        worst = std::max(worst, ate);
        sum += ate;
        ates.push_back(ate);
        row += fmt::format(" {:.3f} |", ate);
        std::fflush(stdout);
      }
      const int n = last_seed - first_seed + 1;
      const double duration = log.records.back().t_s - log.records.front().t_s;
      row += fmt::format(" {:.3f} | {:.3f} | {:.3f} |", lookout::eval::Median(ates), worst, sum / n);
      row += duration > 0.0 ? fmt::format(" {:.0f}x |", duration * n / cpu) : std::string(" - |");
      std::printf("%s\n%s", row.c_str(), spans.c_str());
      std::fflush(stdout);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "lookout_slam_seeds: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lookout_slam_seeds: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
