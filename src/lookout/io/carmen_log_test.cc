#include "lookout/io/carmen_log.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

namespace fs = std::filesystem;

std::string PoseText(const Pose2& p) {
  return fmt::format("{:.10f} {:.10f} {:.10f}", p.x(), p.y(), p.yaw);
}

std::string Flaser(const Pose2& robot, double t, int beams = 4, double range = 2.0) {
  std::string line = fmt::format("FLASER {}", beams);
  for (int i = 0; i < beams; ++i) line += fmt::format(" {}", range);
  return line + fmt::format(" {} {} {:.6f} host {:.6f}\n", PoseText(robot), PoseText(robot), t, t);
}

std::string Odom(const Pose2& p, const std::string& time) {
  return fmt::format("ODOM {} 0 0 0 {} host {}\n", PoseText(p), time, time);
}

double Distance(const Pose2& a, const Pose2& b) { return (a.translation - b.translation).norm(); }

// A corrected log built as the Radish ones are (data README): the raw odometry raw[i] runs on an
// arc from an arbitrary start; after every third reading a scan is "processed" and given a
// corrected pose that differs from the odometry's prediction by a growing correction. Every ODOM
// line prints the last scan's corrected pose composed with the raw motion since that scan; each
// FLASER line is followed by an anchor ODOM line repeating its corrected pose, with a garbage
// time, then a NEFF line.
struct SyntheticLog {
  std::string text;
  std::vector<Pose2> raw;               // odometry readings, in the odometry's own frame
  std::vector<Pose2> reference;         // the corrected pose of each scan
  std::vector<std::size_t> scan_after;  // the reading each scan follows
  std::vector<Pose2> printed;           // the absolute pose each ordinary ODOM line prints
};

SyntheticLog MakeCorrectedLog(int readings) {
  SyntheticLog log;
  log.text = "# message formats defined: PARAM ODOM FLASER\nPARAM robot_use_laser on nohost 0\n";
  Pose2 raw(3.0, -2.0, 0.7);
  Pose2 corrected_at_scan;  // the SLAM result starts at the identity
  Pose2 raw_at_scan = raw;
  const std::vector<std::string> anchor_times = {"0", "-14.0587", "1.58116e-153", "4.29497e+09",
                                                 "nan"};
  for (int i = 0; i < readings; ++i) {
    if (i > 0) raw = raw * Pose2(0.4, 0.01, 0.05);
    log.raw.push_back(raw);
    const double t = 0.1 * (i + 1);
    const Pose2 printed = corrected_at_scan * (raw_at_scan.Inverse() * raw);
    log.text += Odom(printed, fmt::format("{:.6f}", t));
    log.printed.push_back(printed);
    if (i % 3 == 2) {
      const double k = static_cast<double>(log.reference.size() + 1);
      const Pose2 corrected = Pose2(0.05 * k, -0.04 * k, 0.01 * k) * printed;
      log.text += Flaser(corrected, t);
      log.text += Odom(corrected, anchor_times[log.reference.size() % anchor_times.size()]);
      log.text += "NEFF 30\n";
      log.reference.push_back(corrected);
      log.scan_after.push_back(static_cast<std::size_t>(i));
      corrected_at_scan = corrected;
      raw_at_scan = raw;
    }
  }
  return log;
}

void ExpectPoseNear(const Pose2& actual, const Pose2& expected, double tolerance,
                    const std::string& what) {
  EXPECT_NEAR(actual.x(), expected.x(), tolerance) << what;
  EXPECT_NEAR(actual.y(), expected.y(), tolerance) << what;
  EXPECT_NEAR(WrapAngle(actual.yaw - expected.yaw), 0.0, tolerance) << what;
}

TEST(CarmenLogTest, RebuildsRawOdometryFromACorrectedLog) {
  const SyntheticLog synthetic = MakeCorrectedLog(30);
  const CarmenLog log = ParseCarmenLog(synthetic.text, "synthetic.log");
  EXPECT_EQ(log.skipped_lines, 0u);
  EXPECT_EQ(log.anchor_lines, synthetic.reference.size());
  EXPECT_EQ(log.ignored_lines, synthetic.reference.size());  // the NEFF lines
  ASSERT_EQ(log.records.size(), synthetic.raw.size() + synthetic.reference.size());
  EXPECT_EQ(log.ScanCount(), synthetic.reference.size());

  const Pose2 start_inverse = synthetic.raw.front().Inverse();
  std::size_t reading = 0;
  std::size_t scan = 0;
  for (const CarmenRecord& record : log.records) {
    if (record.scan) {
      // The scan was taken at the reading before it.
      ASSERT_LT(scan, synthetic.reference.size());
      const std::size_t at = synthetic.scan_after[scan];
      ExpectPoseNear(record.odometry, start_inverse * synthetic.raw[at], 1e-8,
                     fmt::format("scan {}", scan));
      ASSERT_TRUE(record.reference_pose.has_value());
      ExpectPoseNear(*record.reference_pose, synthetic.reference[scan], 1e-9,
                     fmt::format("reference of scan {}", scan));
      EXPECT_DOUBLE_EQ(record.t_s, 0.1 * static_cast<double>(at + 1));
      EXPECT_EQ(record.source, CarmenSource::kFrontLaser);
      ++scan;
    } else {
      ExpectPoseNear(record.odometry, start_inverse * synthetic.raw[reading], 1e-8,
                     fmt::format("reading {}", reading));
      EXPECT_FALSE(record.reference_pose.has_value());
      EXPECT_DOUBLE_EQ(record.t_s, 0.1 * static_cast<double>(reading + 1));
      ++reading;
    }
  }
  EXPECT_EQ(reading, synthetic.raw.size());
  EXPECT_EQ(log.time_reversals, 0u);  // the anchors' garbage times are never read
}

TEST(CarmenLogTest, TheSyntheticCorrectionIsLargeEnoughToMatter) {
  // Guards the test above: reading the absolute ODOM poses (both start at the identity) must
  // give a clearly different trajectory, or that test could pass for a wrong reader.
  const SyntheticLog synthetic = MakeCorrectedLog(30);
  const Pose2 truth = synthetic.raw.front().Inverse() * synthetic.raw.back();
  EXPECT_NEAR(Distance(synthetic.printed.front(), Pose2()), 0.0, 1e-12);
  EXPECT_GT(Distance(truth, synthetic.printed.back()), 1.0);
}

TEST(CarmenLogTest, OdomAfterAScanWithAnotherPoseIsAnOrdinaryReading) {
  // A raw (uncorrected) log: the ODOM line after a FLASER is a new reading, not an anchor.
  std::string text;
  text += Odom(Pose2(1, 1, 0), "1.0");
  text += Flaser(Pose2(1, 1, 0), 1.0);
  text += Odom(Pose2(2, 1, 0), "1.1");
  text += Odom(Pose2(2, 2, kPi / 2), "1.2");
  const CarmenLog log = ParseCarmenLog(text, "raw.log");
  EXPECT_EQ(log.anchor_lines, 0u);
  ASSERT_EQ(log.records.size(), 4u);
  ExpectPoseNear(log.records[1].odometry, Pose2(), 1e-12, "scan");
  ExpectPoseNear(log.records[2].odometry, Pose2(1, 0, 0), 1e-9, "second reading");
  ExpectPoseNear(log.records[3].odometry, Pose2(1, 1, kPi / 2), 1e-9, "third reading");
  EXPECT_EQ(log.scans_without_odometry, 0u);
}

TEST(CarmenLogTest, ScansWithNoOdometryBetweenThemAreCounted) {
  std::string text;
  text += Flaser(Pose2(0, 0, 0), 0.0);
  text += Odom(Pose2(0, 0, 0), "0");
  text += Flaser(Pose2(1, 0, 0), 0.0);
  text += Odom(Pose2(1, 0, 0), "0");
  text += Flaser(Pose2(2, 0, 0), 0.0);
  const CarmenLog log = ParseCarmenLog(text, "gaps.log");
  EXPECT_EQ(log.anchor_lines, 2u);
  EXPECT_EQ(log.scans_without_odometry, 2u);
  for (const CarmenRecord& r : log.records) ExpectPoseNear(r.odometry, Pose2(), 0.0, "no motion");
}

TEST(CarmenLogTest, FrontLaserGeometryFollowsRep117) {
  // 180 beams span -90..+90 deg when no PARAM says otherwise.
  std::string text = "FLASER 180";
  for (int i = 0; i < 180; ++i) {
    const char* reading = i == 0   ? "-1"
                          : i == 1 ? "nan"
                          : i == 2 ? "0"
                          : i == 3 ? "50"
                          : i == 4 ? "49.9"
                                   : "3.25";
    text += fmt::format(" {}", reading);
  }
  text += " 0 0 0 0 0 0 12.5 host 12.5\n";
  const CarmenLog log = ParseCarmenLog(text, "beams.log");
  ASSERT_EQ(log.ScanCount(), 1u);
  const LidarScan& scan = *log.records[0].scan;
  // 180 beams without a parameter: 1 deg apart (the scanner's resolution), -89.5 .. +89.5 deg.
  EXPECT_NEAR(scan.angle_min_rad, DegToRad(-89.5), 1e-12);
  EXPECT_NEAR(scan.angle_increment_rad, DegToRad(1.0), 1e-12);
  EXPECT_NEAR(scan.BeamAngle(179), DegToRad(89.5), 1e-12);
  EXPECT_EQ(scan.stamp, 12'500'000'000);
  EXPECT_TRUE(std::isnan(scan.ranges_m[0]));                            // negative
  EXPECT_TRUE(std::isnan(scan.ranges_m[1]));                            // NaN
  EXPECT_TRUE(std::isnan(scan.ranges_m[2]));                            // zero
  EXPECT_EQ(scan.ranges_m[3], std::numeric_limits<float>::infinity());  // the log's maximum
  EXPECT_EQ(scan.ranges_m[4], std::numeric_limits<float>::infinity());  // within 0.2 m of it
  EXPECT_EQ(scan.ranges_m[5], 3.25f);
  EXPECT_DOUBLE_EQ(scan.max_range_m, 50.0);
  EXPECT_EQ(scan.mount.translation, Eigen::Vector2d::Zero());

  CarmenReadOptions options;
  options.max_range_m = 80.0;
  const CarmenLog far = ParseCarmenLog(text, "beams.log", options);
  EXPECT_EQ(far.records[0].scan->ranges_m[3], 50.0f);
  EXPECT_DOUBLE_EQ(far.records[0].scan->max_range_m, 80.0);
}

std::string FlaserOfBeams(int beams) {
  std::string line = fmt::format("FLASER {}", beams);
  for (int i = 0; i < beams; ++i) line += " 1";
  return line + " 0 0 0 0 0 0 1 host 1\n";
}

TEST(CarmenLogTest, FieldOfViewAndMountComeFromParams) {
  {
    const CarmenLog log = ParseCarmenLog(
        "PARAM laser_front_laser_fov 100 nohost 0\nPARAM robot_frontlaser_offset 0.0 nohost 0\n"
        "PARAM robot_frontlaser_offset -0.04 nohost 0\n" +
            FlaserOfBeams(101),
        "fov.log");
    const LidarScan& scan = *log.records.at(0).scan;
    EXPECT_NEAR(scan.angle_min_rad, DegToRad(-50), 1e-12);
    EXPECT_NEAR(scan.angle_increment_rad, DegToRad(1), 1e-12);
    EXPECT_DOUBLE_EQ(scan.mount.x(), -0.04);  // the last value of a repeated PARAM
    EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "-0.04");
  }
  {
    // csail writes the field of view in radians.
    const CarmenLog log = ParseCarmenLog(
        "PARAM laser_front_laser_fov 3.14159 1.0 b21 1.0\n" + FlaserOfBeams(361), "rad.log");
    EXPECT_NEAR(log.records.at(0).scan->angle_min_rad, -3.14159 / 2, 1e-12);
  }
  {
    const CarmenLog log = ParseCarmenLog(
        "PARAM laser_front_laser_resolution 0.5 nohost 0\n" + FlaserOfBeams(361), "res.log");
    EXPECT_NEAR(log.records.at(0).scan->angle_min_rad, -kPi / 2, 1e-12);
    EXPECT_NEAR(log.records.at(0).scan->angle_increment_rad, DegToRad(0.5), 1e-12);
  }
  // Without a parameter, the resolution by the beam count as CARMEN's tools read these logs:
  // 1 deg for 180 and 181 beams, 0.5 deg for 360 and 361, else 180 deg over the beams.
  for (const auto& [beams, step_deg] : std::vector<std::pair<int, double>>{
           {180, 1.0}, {181, 1.0}, {360, 0.5}, {361, 0.5}, {91, 2.0}}) {
    const CarmenLog log = ParseCarmenLog(FlaserOfBeams(beams), "count.log");
    const LidarScan& scan = *log.records.at(0).scan;
    EXPECT_NEAR(scan.angle_increment_rad, DegToRad(step_deg), 1e-12) << beams << " beams";
    EXPECT_NEAR(scan.angle_min_rad, -0.5 * DegToRad(step_deg) * (beams - 1), 1e-12) << beams;
  }
}

TEST(CarmenLogTest, RearLaserLooksBackwards) {
  std::string text =
      "PARAM robot_rearlaser_offset 0.3 nohost 0\nRLASER 3 1 2 3 0 0 0 4 5 0.5 7 host 7\n";
  const CarmenLog log = ParseCarmenLog(text, "rear.log");
  ASSERT_EQ(log.records.size(), 1u);
  const CarmenRecord& r = log.records[0];
  EXPECT_EQ(r.source, CarmenSource::kRearLaser);
  EXPECT_DOUBLE_EQ(r.scan->mount.x(), -0.3);
  EXPECT_NEAR(std::abs(r.scan->mount.yaw), kPi, 1e-12);
  // A beam straight ahead of the rear laser points behind the vehicle.
  const Eigen::Vector2d p = r.scan->mount * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), -1.3, 1e-12);
  ExpectPoseNear(*r.reference_pose, Pose2(4, 5, 0.5), 0.0, "rear reference");
}

TEST(CarmenLogTest, RobotLaserCarriesItsOwnGeometry) {
  // type start fov res max acc mode n r.. m e.. laser(3) robot(3) tv rv fwd side turn t host t
  const std::string text =
      "ROBOTLASER1 0 -1.5 3.0 0.75 8.0 0.01 0 5 1 2 8 9 -3 2 10 20 "
      "1.1 2.0 0.5 1.0 2.0 0.5 0 0 0.3 0.2 1 42.5 host 42.5\n";
  const CarmenLog log = ParseCarmenLog(text, "robot.log");
  ASSERT_EQ(log.skipped_lines, 0u) << log.warnings.front();
  const LidarScan& scan = *log.records.at(0).scan;
  EXPECT_EQ(log.records[0].source, CarmenSource::kRobotLaser);
  EXPECT_DOUBLE_EQ(scan.angle_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, 0.75);
  EXPECT_DOUBLE_EQ(scan.max_range_m, 8.0);
  ASSERT_EQ(scan.ranges_m.size(), 5u);
  EXPECT_EQ(scan.ranges_m[1], 2.0f);
  EXPECT_EQ(scan.ranges_m[2], std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(scan.ranges_m[4]));
  // The laser sits 0.1 m ahead of the robot (heading 0.5 rad), looking the same way.
  EXPECT_NEAR(scan.mount.x(), 0.1 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(scan.mount.y(), -0.1 * std::sin(0.5), 1e-12);
  EXPECT_NEAR(scan.mount.yaw, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(log.records[0].t_s, 42.5);
}

// ---------------------------------------------------------------------------------------------
// Bad input

struct BadLine {
  std::string line;
  std::string field;
};

TEST(CarmenLogTest, MalformedLinesAreSkippedWithTheirLineOrRefusedWhenStrict) {
  const std::vector<BadLine> cases = {
      {"ODOM 1 2", "theta"},
      {"ODOM 1 two 3 0 0 0 5 h 5", "y"},
      {"ODOM 1 2 inf 0 0 0 5 h 5", "theta"},
      {"ODOM 1 2 3 0 0 0", "ipc_timestamp"},
      {"ODOM 1 2 3 0 0 0 nan h 5", "ipc_timestamp"},
      {"ODOM 1 2 3 0 0 0 1e300 h 5", "ipc_timestamp"},
      {"ODOM 1 2 3 x 0 0 5 h 5", "tv"},
      {"ODOM 1e300 2 3 0 0 0 5 h 5", "x"},
      {"FLASER", "num_readings"},
      {"FLASER -3 1 2", "num_readings"},
      {"FLASER 99999999999 1 2", "num_readings"},
      {"FLASER 1 1 0 0 0 0 0 0 1 h 1", "num_readings"},
      {"FLASER 3 1 2 3 0 0 0 0 0", "ipc_timestamp"},
      {"FLASER 3 1 x 3 0 0 0 0 0 0 1 h 1", "range[1]"},
      {"FLASER 3 1 2 3 0 0 0 0 nan 0 1 h 1", "odom_y"},
      {"ROBOTLASER1 0 -1.5 3.0 0.75 -8.0 0.01 0 1 1 0 0 0 0 0 0 0 0 0 0 0 0 1 h 1",
       "maximum_range"},
      {"ROBOTLASER1 0 -1.5 3.0 0.75 8.0 0.01 0 1 1 9 0", "num_remissions"},
      {"PARAM lonely", "value"},
  };
  for (const BadLine& c : cases) {
    const std::string text = "PARAM a b\n" + c.line + "\nODOM 0 0 0 0 0 0 1 h 1\n";
    const CarmenLog log = ParseCarmenLog(text, "bad.log");
    EXPECT_EQ(log.skipped_lines, 1u) << c.line;
    ASSERT_EQ(log.warnings.size(), 1u) << c.line;
    EXPECT_TRUE(log.warnings[0].starts_with(fmt::format("bad.log:2: {}: ", c.field)))
        << c.line << " -> " << log.warnings[0];
    EXPECT_EQ(log.records.size(), 1u) << c.line;  // the good line after it is read

    CarmenReadOptions strict;
    strict.strict = true;
    try {
      ParseCarmenLog(text, "bad.log", strict);
      ADD_FAILURE() << "strict read accepted: " << c.line;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "bad.log");
      EXPECT_EQ(e.line(), 2) << c.line;
      EXPECT_EQ(e.field(), c.field) << c.line;
    }
  }
}

TEST(CarmenLogTest, BadParamValueIsReportedOnItsLine) {
  const std::string text = "\nPARAM robot_frontlaser_offset abc nohost 0\n" + FlaserOfBeams(3);
  const CarmenLog log = ParseCarmenLog(text, "param.log");
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_TRUE(log.warnings[0].starts_with("param.log:2: robot_frontlaser_offset: "))
      << log.warnings[0];
  EXPECT_EQ(log.records.at(0).scan->mount.x(), 0.0);
  CarmenReadOptions strict;
  strict.strict = true;
  EXPECT_THROW(ParseCarmenLog(text, "param.log", strict), InputError);
}

TEST(CarmenLogTest, WarningsAreCappedButEveryBadLineIsCounted) {
  std::string text;
  for (int i = 0; i < 100; ++i) text += "ODOM garbage\n";
  const CarmenLog log = ParseCarmenLog(text, "many.log");
  EXPECT_EQ(log.skipped_lines, 100u);
  EXPECT_EQ(log.warnings.size(), kMaxCarmenWarnings);
  EXPECT_TRUE(log.records.empty());
}

TEST(CarmenLogTest, CommentsBlankLinesAndOtherMessages) {
  const CarmenLog log = ParseCarmenLog(
      "# comment\n\n   \r\nNEFF 30\nTRUEPOS 1 2 3\nODOM 0 0 0 0 0 0 2 h 2\r\nODOM 0 0 0 0 0 0 1 h "
      "1",
      "misc.log");
  EXPECT_EQ(log.ignored_lines, 2u);
  EXPECT_EQ(log.skipped_lines, 0u);
  ASSERT_EQ(log.records.size(), 2u);
  EXPECT_EQ(log.records[1].line, 7);  // the last line has no newline
  EXPECT_EQ(log.time_reversals, 1u);
}

TEST(CarmenLogTest, OptionsAreValidated) {
  CarmenReadOptions options;
  options.max_range_m = -1.0;
  EXPECT_THROW(ParseCarmenLog("", "x.log", options), InputError);
  options.max_range_m = 0.0;
  options.max_range_tolerance_m = std::nan("");
  EXPECT_THROW(ParseCarmenLog("", "x.log", options), InputError);
}

// ---------------------------------------------------------------------------------------------
// The Radish logs of ../shared/data/carmen

fs::path CarmenDir() { return fs::path(LOOKOUT_SOURCE_DIR) / ".." / "shared" / "data" / "carmen"; }

TEST(CarmenLogTest, EveryRadishLogLoads) {
  // FLASER lines per log, counted with grep; each is followed by its anchor.
  const std::map<std::string, std::size_t> expected_scans = {
      {"acapulco", 861},         {"aces", 440},
      {"belgioioso", 395},       {"csail", 406},
      {"edmonton", 340},         {"fhw", 488},
      {"freiburg-079", 4791},    {"freiburg-101", 292},
      {"freiburg-campus", 2008}, {"infinite-corridor", 1941},
      {"orebro", 237},           {"seattle", 241}};
  for (const auto& [name, scans] : expected_scans) {
    const fs::path path = CarmenDir() / (name + "-corrected.log.gz");
    ASSERT_TRUE(fs::exists(path)) << path;
    const CarmenLog log = ReadCarmenLog(path);
    std::size_t no_return = 0;
    std::size_t beams = 0;
    for (const CarmenRecord& r : log.records) {
      if (!r.scan) continue;
      beams += r.scan->ranges_m.size();
      for (const float range : r.scan->ranges_m) no_return += std::isinf(range) ? 1u : 0u;
    }
    fmt::print(
        "{:<18} records {:>6}  scans {:>5}  beams/scan {:>3}  anchors {:>5}  no-return {:>5.1f} %  "
        "scans without odometry {:>3}  time reversals {:>3}\n",
        name, log.records.size(), log.ScanCount(), beams / log.ScanCount(), log.anchor_lines,
        100.0 * static_cast<double>(no_return) / static_cast<double>(beams),
        log.scans_without_odometry, log.time_reversals);
    EXPECT_EQ(log.skipped_lines, 0u)
        << name << ": " << (log.warnings.empty() ? "" : log.warnings[0]);
    EXPECT_EQ(log.ScanCount(), scans) << name;
    EXPECT_EQ(log.anchor_lines, scans) << name;
    EXPECT_GT(log.records.size(), scans) << name;
  }
}

TEST(CarmenLogTest, RebuiltDeadReckoningDriftsByMetresOnARealLog) {
  // freiburg-101: rebuilt from the increments, the odometry drifts by tens of metres from the
  // corrected poses; read the wrong way (chained across the anchors) it would follow them.
  const CarmenLog log = ReadCarmenLog(CarmenDir() / "freiburg-101-corrected.log.gz");
  const CarmenRecord* first = nullptr;
  double max_error_m = 0.0;
  double path_m = 0.0;
  const Pose2* previous = nullptr;
  for (const CarmenRecord& r : log.records) {
    if (!r.scan) continue;
    if (previous) path_m += Distance(*previous, *r.reference_pose);
    previous = &*r.reference_pose;
    if (!first) first = &r;
    // Both trajectories start together: the odometry is put where the reference starts.
    const Pose2 dead_reckoning = *first->reference_pose * first->odometry.Inverse() * r.odometry;
    max_error_m = std::max(max_error_m, Distance(dead_reckoning, *r.reference_pose));
  }
  fmt::print(
      "freiburg-101: dead reckoning drifts up to {:.1f} m from the reference over {:.0f} m\n",
      max_error_m, path_m);
  EXPECT_GT(max_error_m, 20.0);
  EXPECT_LT(max_error_m, 200.0);
}

}  // namespace
}  // namespace lookout::io
