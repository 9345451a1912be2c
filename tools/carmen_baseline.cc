// lookout_carmen_baseline LOG...
//
// The dead-reckoning baseline of CARMEN logs: for each log, the raw odometry rebuilt by the
// importer (carmen_log.h) is scored against the log's corrected poses, at every scan, as a
// Markdown table on stdout (docs/carmen.md). This is what a localisation must beat: the error
// of using the odometry alone.
//
// Scans are paired by their order, not by their time stamps: in five of the Radish logs the
// stamps are all equal, all zero or garbage (docs/carmen.md), and both poses of a pair come from
// the same line anyway. The trajectories handed to the eval functions are therefore stamped with
// the scan's index.
//
// Exit codes as the CLI's: 2 with one line on stderr for a bad log, 1 for any other failure.

#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "lookout/core/input_error.h"
#include "lookout/eval/relation_error.h"
#include "lookout/eval/trajectory_error.h"
#include "lookout/io/carmen_log.h"

namespace {

using lookout::RadToDeg;
using lookout::eval::Trajectory2;

// "aces" from ".../aces-corrected.log.gz".
std::string LogName(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  for (const std::string suffix : {".gz", ".log", ".clf", "-corrected"}) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) {
      name.resize(name.size() - suffix.size());
    }
  }
  return name;
}

std::string Row(const std::filesystem::path& path) {
  const lookout::io::CarmenLog log = lookout::io::ReadCarmenLog(path);
  Trajectory2 odometry;
  Trajectory2 reference;
  double path_m = 0.0;
  for (const lookout::io::CarmenRecord& record : log.records) {
    if (!record.scan || !record.reference_pose) continue;
    const auto index = static_cast<double>(reference.size());
    if (!reference.empty()) {
      path_m += (record.reference_pose->translation - reference.back().pose.translation).norm();
    }
    odometry.push_back({index, record.odometry});
    reference.push_back({index, *record.reference_pose});
  }
  const lookout::eval::AbsoluteTrajectoryError ate =
      lookout::eval::ComputeAbsoluteTrajectoryError(odometry, reference);
  lookout::eval::RelationGeneratorOptions ten_metres;
  ten_metres.min_travel_m = 10.0;
  const lookout::eval::RelationError relation = lookout::eval::ComputeRelationError(
      odometry, lookout::eval::GenerateRelations(reference, ten_metres));
  return fmt::format(
      "| {} | {} | {:.0f} | {:.2f} | {:.1f} | {:.3f} ± {:.3f} | {:.2f} ± {:.2f} | {} |\n",
      LogName(path), reference.size(), path_m, ate.ate_rmse_m, RadToDeg(ate.heading_rmse_rad),
      relation.translation_mean_m, relation.translation_std_m, RadToDeg(relation.rotation_mean_rad),
      RadToDeg(relation.rotation_std_rad), log.scans_without_odometry);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs("usage: lookout_carmen_baseline LOG...\n", stderr);
    return 2;
  }
  // The whole table or nothing: a bad log stops the tool before it prints.
  std::string table =
      "| log | scans | reference path (m) | ATE RMSE (m) | heading RMSE (deg) | "
      "10 m relations: translation (m) | rotation (deg) | scans without odometry |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  try {
    for (int i = 1; i < argc; ++i) table += Row(argv[i]);
  } catch (const lookout::InputError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  fmt::print("{}", table);
  return 0;
}
