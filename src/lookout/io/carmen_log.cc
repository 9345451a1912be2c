#include "lookout/io/carmen_log.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <system_error>
#include <utility>

#include "lookout/core/input_error.h"
#include "lookout/core/time.h"
#include "lookout/io/gzip_file.h"

namespace lookout::io {
namespace {

// An anchor ODOM line repeats the laser line's pose as printed by the same printf.
constexpr double kAnchorTolerance = 1e-5;
// The largest |time| whose nanoseconds fit in TimeNs (int64), with a margin.
constexpr double kMaxAbsTimeS = 9.2e9;
// Poses further out are nonsense (10,000 km), and chaining them could overflow to infinity.
constexpr double kMaxAbsCoordinateM = 1e7;

using Tokens = std::vector<std::string_view>;

void Tokenize(std::string_view line, Tokens& tokens) {
  tokens.clear();
  std::size_t i = 0;
  const auto blank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

// A malformed line: what InputError would say about it.
struct LineError {
  std::string field;
  std::string problem;
};

// Reads the fields of one line by index, naming the field in its error.
class Fields {
 public:
  explicit Fields(const Tokens& tokens) : tokens_(tokens) {}

  std::size_t size() const { return tokens_.size(); }

  void Require(std::size_t count, std::string_view what) const {
    if (tokens_.size() < count) {
      throw LineError{std::string(what), fmt::format("missing: the line has {} fields, {} needs {}",
                                                     tokens_.size(), tokens_[0], count)};
    }
  }

  // Any number the text holds, NaN and infinities included.
  double Number(std::size_t i, std::string_view field) const {
    double value = 0.0;
    const std::string_view s = tokens_[i];
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size()) {
      throw LineError{std::string(field), fmt::format("not a number: '{}'", s)};
    }
    return value;
  }

  double Finite(std::size_t i, std::string_view field) const {
    const double value = Number(i, field);
    if (!std::isfinite(value)) throw LineError{std::string(field), "not a finite number"};
    return value;
  }

  double Time(std::size_t i, std::string_view field) const {
    const double value = Finite(i, field);
    if (std::abs(value) > kMaxAbsTimeS) {
      throw LineError{std::string(field), fmt::format("time {} s is out of range", value)};
    }
    return value;
  }

  double Coordinate(std::size_t i, std::string_view field) const {
    const double value = Finite(i, field);
    if (std::abs(value) > kMaxAbsCoordinateM) {
      throw LineError{std::string(field), fmt::format("{} m is out of range", value)};
    }
    return value;
  }

  std::size_t Count(std::size_t i, std::string_view field, std::size_t max) const {
    std::size_t value = 0;
    const std::string_view s = tokens_[i];
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size()) {
      throw LineError{std::string(field), fmt::format("not a count: '{}'", s)};
    }
    if (value > max) {
      throw LineError{std::string(field),
                      fmt::format("{} is more than the line's {} remaining fields", value, max)};
    }
    return value;
  }

  Pose2 Pose(std::size_t i, std::string_view x, std::string_view y, std::string_view theta) const {
    const double px = Coordinate(i, x);
    const double py = Coordinate(i + 1, y);
    const double ptheta = Finite(i + 2, theta);
    return Pose2(px, py, WrapAngle(ptheta));
  }

 private:
  const Tokens& tokens_;
};

// A range reading as REP 117 wants it, before the max-range pass.
float RangeReading(double value) {
  if (std::isnan(value) || value <= 0.0) return std::numeric_limits<float>::quiet_NaN();
  // Beyond float's range the conversion would be undefined; such a reading is no return.
  if (value > static_cast<double>(std::numeric_limits<float>::max())) {
    return std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(value);
}

std::vector<float> Ranges(const Fields& fields, std::size_t first, std::size_t count) {
  std::vector<float> ranges(count);
  for (std::size_t k = 0; k < count; ++k) {
    ranges[k] = RangeReading(fields.Number(first + k, fmt::format("range[{}]", k)));
  }
  return ranges;
}

bool SamePose(const Pose2& a, const Pose2& b) {
  return std::abs(a.x() - b.x()) <= kAnchorTolerance &&
         std::abs(a.y() - b.y()) <= kAnchorTolerance &&
         std::abs(WrapAngle(a.yaw - b.yaw)) <= kAnchorTolerance;
}

// A laser line of the old format (FLASER, RLASER): its angles and range limit are set later,
// from the PARAM lines and the whole log.
CarmenRecord ParseOldLaser(const Fields& f, CarmenSource source) {
  f.Require(2, "num_readings");
  const std::size_t n = f.Count(1, "num_readings", f.size() - 2);
  // n - 1 angular steps span the field of view.
  if (n < 2) throw LineError{"num_readings", "a scan needs at least 2 readings"};
  f.Require(2 + n + 7, "ipc_timestamp");
  CarmenRecord record;
  record.source = source;
  LidarScan scan;
  scan.ranges_m = Ranges(f, 2, n);
  const std::size_t p = 2 + n;
  // The first pose is the laser's, the second the robot's; the reference is the robot's.
  f.Pose(p, "x", "y", "theta");
  record.reference_pose = f.Pose(p + 3, "odom_x", "odom_y", "odom_theta");
  record.t_s = f.Time(p + 6, "ipc_timestamp");
  scan.stamp = FromSeconds(record.t_s);
  record.scan = std::move(scan);
  return record;
}

CarmenRecord ParseRobotLaser(const Fields& f) {
  f.Require(9, "num_readings");
  const double start_angle = f.Finite(2, "start_angle");
  f.Finite(3, "fov");
  const double resolution = f.Finite(4, "angular_resolution");
  const double max_range = f.Finite(5, "maximum_range");
  if (max_range <= 0.0) throw LineError{"maximum_range", "not positive"};
  const std::size_t n = f.Count(8, "num_readings", f.size() - 9);
  if (n < 1) throw LineError{"num_readings", "a scan needs at least 1 reading"};
  f.Require(9 + n + 1, "num_remissions");
  const std::size_t m = f.Count(9 + n, "num_remissions", f.size() - (10 + n));
  const std::size_t p = 10 + n + m;
  f.Require(p + 12, "ipc_timestamp");
  CarmenRecord record;
  record.source = CarmenSource::kRobotLaser;
  LidarScan scan;
  scan.angle_min_rad = start_angle;
  scan.angle_increment_rad = resolution;
  scan.max_range_m = max_range;
  scan.ranges_m = Ranges(f, 9, n);
  const Pose2 laser = f.Pose(p, "laser_pose_x", "laser_pose_y", "laser_pose_theta");
  const Pose2 robot = f.Pose(p + 3, "robot_pose_x", "robot_pose_y", "robot_pose_theta");
  scan.mount = robot.Inverse() * laser;
  record.reference_pose = robot;
  record.t_s = f.Time(p + 11, "ipc_timestamp");
  scan.stamp = FromSeconds(record.t_s);
  record.scan = std::move(scan);
  return record;
}

// The PARAM values the old-format lasers need. A bad value is a bad line: an InputError naming
// the PARAM's line when strict, else a warning and the default.
class ParamReader {
 public:
  ParamReader(CarmenLog& log, const std::map<std::string, int>& lines, const std::string& name,
              bool strict)
      : log_(log), lines_(lines), name_(name), strict_(strict) {}

  std::optional<double> Number(const std::string& key) {
    const auto it = log_.params.find(key);
    if (it == log_.params.end()) return std::nullopt;
    double value = 0.0;
    const std::string& s = it->second;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(value)) {
      Refuse(key, fmt::format("not a finite number: '{}'", s));
      return std::nullopt;
    }
    return value;
  }

  // The field of view in radians of a laser ("front" or "rear") of n beams.
  double FieldOfView(const std::string& laser, std::size_t n) {
    const std::string fov_key = fmt::format("laser_{}_laser_fov", laser);
    const std::string resolution_key = fmt::format("laser_{}_laser_resolution", laser);
    std::optional<double> fov;
    std::string key = fov_key;
    if (const auto value = Number(fov_key)) {
      fov = *value <= 2.0 * kPi ? *value : DegToRad(*value);
    } else if (const auto resolution = Number(resolution_key)) {
      fov = DegToRad(*resolution) * static_cast<double>(n - 1);
      key = resolution_key;
    }
    if (!fov) {
      // No parameter: the resolution the SICK scanners of these logs run at, known by the beam
      // count as CARMEN's own tools know it (1 deg for 180 or 181 beams, 0.5 deg for 360 or
      // 361). 180 beams are 1 deg apart and span 179 deg, not 180: spread over 180 deg, a scan
      // is stretched by 0.56 % and a wall at the side turns by up to 0.5 deg.
      if (n == 180 || n == 181) return DegToRad(1.0) * static_cast<double>(n - 1);
      if (n == 360 || n == 361) return DegToRad(0.5) * static_cast<double>(n - 1);
      return kPi;
    }
    if (!(*fov > 0.0 && *fov <= 2.0 * kPi)) {
      Refuse(key, fmt::format("gives a field of view of {} rad for {} beams, not in (0, 2 pi]",
                              *fov, n));
      return kPi;
    }
    return *fov;
  }

 private:
  void Refuse(const std::string& key, const std::string& problem) {
    // Each bad PARAM is reported once, though many scans ask for it.
    if (!refused_.insert(key).second) return;
    InputError error(name_, lines_.at(key), key, problem);
    if (strict_) throw error;
    ++log_.skipped_lines;
    if (log_.warnings.size() < kMaxCarmenWarnings) log_.warnings.emplace_back(error.what());
  }

  CarmenLog& log_;
  const std::map<std::string, int>& lines_;
  const std::string& name_;
  bool strict_;
  std::set<std::string> refused_;
};

// Sets the angles, mount and range limit of the FLASER and RLASER scans once every PARAM line
// and every reading of the log are known.
void FinishOldLaserScans(CarmenLog& log, const std::map<std::string, int>& param_lines,
                         const std::string& name, const CarmenReadOptions& options) {
  ParamReader params(log, param_lines, name, options.strict);
  const double front_offset = params.Number("robot_frontlaser_offset").value_or(0.0);
  const double rear_offset = params.Number("robot_rearlaser_offset").value_or(0.0);
  for (const CarmenSource source : {CarmenSource::kFrontLaser, CarmenSource::kRearLaser}) {
    double max_range = options.max_range_m;
    if (max_range <= 0.0) {
      for (const CarmenRecord& record : log.records) {
        if (record.source != source) continue;
        for (const float r : record.scan->ranges_m) {
          if (std::isfinite(r)) max_range = std::max(max_range, static_cast<double>(r));
        }
      }
    }
    const std::string laser = source == CarmenSource::kFrontLaser ? "front" : "rear";
    const Pose2 mount = source == CarmenSource::kFrontLaser ? Pose2(front_offset, 0.0, 0.0)
                                                            : Pose2(-rear_offset, 0.0, kPi);
    const auto no_return_from = static_cast<float>(max_range - options.max_range_tolerance_m);
    for (CarmenRecord& record : log.records) {
      if (record.source != source) continue;
      LidarScan& scan = *record.scan;
      const std::size_t n = scan.ranges_m.size();
      const double fov = params.FieldOfView(laser, n);
      scan.angle_min_rad = -0.5 * fov;
      scan.angle_increment_rad = fov / static_cast<double>(n - 1);
      scan.max_range_m = max_range;
      scan.mount = mount;
      for (float& r : scan.ranges_m) {
        if (r >= no_return_from) r = std::numeric_limits<float>::infinity();
      }
    }
  }
}

void MarkRobotLaserNoReturns(LidarScan& scan, const CarmenReadOptions& options) {
  if (options.max_range_m > 0.0) scan.max_range_m = options.max_range_m;
  const auto no_return_from = static_cast<float>(scan.max_range_m - options.max_range_tolerance_m);
  for (float& r : scan.ranges_m) {
    if (r >= no_return_from) r = std::numeric_limits<float>::infinity();
  }
}

}  // namespace

void CarmenReadOptions::Validate() const {
  if (!std::isfinite(max_range_m) || max_range_m < 0.0) {
    throw InputError("options", 0, "max_range_m", "must be 0 (from the log) or positive");
  }
  if (!std::isfinite(max_range_tolerance_m) || max_range_tolerance_m < 0.0) {
    throw InputError("options", 0, "max_range_tolerance_m", "must be finite and not negative");
  }
}

std::size_t CarmenLog::ScanCount() const {
  return static_cast<std::size_t>(std::count_if(
      records.begin(), records.end(), [](const CarmenRecord& r) { return r.scan.has_value(); }));
}

CarmenLog ParseCarmenLog(std::string_view text, const std::string& name,
                         const CarmenReadOptions& options) {
  options.Validate();
  CarmenLog log;
  std::map<std::string, int> param_lines;
  Tokens tokens;

  // The odometry chain (see the header): the absolute pose of the latest ODOM line, anchors
  // included, and the raw pose rebuilt so far.
  std::optional<Pose2> base;
  Pose2 raw;
  // The robot pose of the laser line just read, while the next line may be its anchor.
  std::optional<Pose2> anchor_candidate;
  bool odometry_since_scan = false;
  bool any_scan = false;

  int line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;

    Tokenize(line, tokens);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::optional<Pose2> candidate = std::exchange(anchor_candidate, std::nullopt);
    const Fields f(tokens);
    const std::string_view type = tokens[0];
    try {
      if (type == "ODOM") {
        f.Require(4, "theta");
        const Pose2 pose = f.Pose(1, "x", "y", "theta");
        if (candidate && SamePose(pose, *candidate)) {
          base = pose;
          ++log.anchor_lines;
          continue;
        }
        f.Require(8, "ipc_timestamp");
        f.Finite(4, "tv");
        f.Finite(5, "rv");
        f.Finite(6, "accel");
        CarmenRecord record;
        record.t_s = f.Time(7, "ipc_timestamp");
        if (base) raw = raw * (base->Inverse() * pose);
        base = pose;
        record.odometry = raw;
        record.line = line_number;
        log.records.push_back(std::move(record));
        odometry_since_scan = true;
      } else if (type == "FLASER" || type == "RLASER" || type == "ROBOTLASER1") {
        CarmenRecord record = type == "FLASER"   ? ParseOldLaser(f, CarmenSource::kFrontLaser)
                              : type == "RLASER" ? ParseOldLaser(f, CarmenSource::kRearLaser)
                                                 : ParseRobotLaser(f);
        if (record.source == CarmenSource::kRobotLaser) {
          MarkRobotLaserNoReturns(*record.scan, options);
        }
        record.odometry = raw;
        record.line = line_number;
        anchor_candidate = record.reference_pose;
        if (any_scan && !odometry_since_scan) ++log.scans_without_odometry;
        any_scan = true;
        odometry_since_scan = false;
        log.records.push_back(std::move(record));
      } else if (type == "PARAM") {
        f.Require(3, "value");
        const std::string key(tokens[1]);
        log.params[key] = std::string(tokens[2]);
        param_lines[key] = line_number;
      } else {
        ++log.ignored_lines;
      }
    } catch (const LineError& e) {
      InputError error(name, line_number, e.field, e.problem);
      if (options.strict) throw error;
      ++log.skipped_lines;
      if (log.warnings.size() < kMaxCarmenWarnings) log.warnings.emplace_back(error.what());
    }
  }

  FinishOldLaserScans(log, param_lines, name, options);
  for (std::size_t i = 1; i < log.records.size(); ++i) {
    if (log.records[i].t_s < log.records[i - 1].t_s) ++log.time_reversals;
  }
  return log;
}

CarmenLog ReadCarmenLog(const std::filesystem::path& path, const CarmenReadOptions& options) {
  const std::string text = ReadMaybeGzippedFile(path);
  return ParseCarmenLog(text, path.string(), options);
}

}  // namespace lookout::io
