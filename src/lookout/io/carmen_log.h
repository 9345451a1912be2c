#pragma once

// Importer of CARMEN logs (the text format of the CARMEN robot toolkit's logger), as the
// Radish data sets under ../shared/data/carmen use it. docs/carmen.md has the format as read and
// the figures on those logs.
//
// Lines read (tokens separated by blanks; everything else is counted in `ignored_lines`):
//   ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp
//   FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname
//          logger_timestamp                  (front laser; RLASER: the same for the rear laser)
//   ROBOTLASER1 laser_type start_angle fov angular_resolution max_range accuracy remission_mode
//          n r_1 .. r_n m e_1 .. e_m laser_x laser_y laser_theta robot_x robot_y robot_theta
//          tv rv forward_safety side_safety turn_axis ipc_timestamp ipc_hostname logger_timestamp
//   PARAM name value [ipc_timestamp] ipc_hostname logger_timestamp
// Blank lines and lines starting with '#' are comments.
//
// Raw odometry. The Radish "corrected" logs are the output of a SLAM run: every original
// odometry reading is an ODOM line whose pose is the corrected pose of the last scan composed
// with the raw odometry since that scan, and right after each laser line comes an extra "anchor"
// ODOM line that repeats the corrected pose (with a time of 0 or garbage). The raw odometry is
// rebuilt by chaining increments:
//   - `base` is the absolute pose of the latest ODOM line, anchors included; `raw` starts at the
//     identity.
//   - An ordinary ODOM line at absolute pose P: raw = raw * (base^-1 * P), then base = P. Its
//     increment is read in one frame only, the frame of the line before it: both poses carry the
//     same correction, so the correction cancels.
//   - An anchor: base = its pose, raw unchanged. It adds no motion (the scan was taken where the
//     previous ODOM line was; the logs give the laser line that ODOM line's time), but it moves
//     the frame in which the following increments are read to the corrected one. Chaining
//     across it instead (base^-1 * P with the pre-anchor base) would add the SLAM correction to
//     the odometry, which is reading the answer.
// An anchor is known by its position, never by its time: it is the ODOM line that directly
// follows a laser line (FLASER, RLASER, ROBOTLASER1; comments aside) AND repeats that line's
// robot pose (odom_x, odom_y, odom_theta; robot_x..theta for ROBOTLASER1) to 1e-5. The pose
// check makes the reader right for raw logs too, where the ODOM line after a scan is an ordinary
// reading. Where no ODOM line separates two scans (orebro-corrected has few), the raw motion
// between them is not in the file: `scans_without_odometry` counts those scans, and their
// odometry repeats the previous scan's.
//
// Records: one per ordinary ODOM line (odometry only) and one per laser line (odometry = the
// raw pose of the latest ODOM line, scan, and reference_pose = the line's robot pose, which in
// the corrected logs is the SLAM result). Anchors make no record.
//
// Time. t_s is the line's ipc_timestamp, the first of its two time fields: the time the reading
// was taken on the robot, where logger_timestamp is when the logger received it (they are equal
// in the Radish logs). Times are kept as the log prints them: several Radish logs print about
// 6 significant digits, so a burst shares one stamp and absolute Unix times are rounded to
// 10^4 s; some are all 0 or garbage (infinite-corridor). `time_reversals` counts records whose
// time is below the previous record's; nothing is reordered, since the lines' order is the
// sensor's. The anchors' times are never read.
//
// Scans (LidarScan, REP 117): negative, zero or NaN readings are NaN (no valid measurement);
// readings at or above max_range_m - max_range_tolerance_m are +inf (no return). The range
// limit is CarmenReadOptions::max_range_m when set, else the field of a ROBOTLASER1 line, else
// for FLASER/RLASER the largest reading of that laser in the whole log: the sensors report "no
// return" as a saturated code (50, 51.15, 81.91, 32.767 m in the Radish logs) and the logs'
// PARAM robot_front_laser_max is not reliable (edmonton says 10 m and has 4000 readings beyond).
// FLASER beams span the laser's field of view centred on its x axis: -fov/2 .. +fov/2 in n - 1
// steps. fov is PARAM laser_front_laser_fov when present (degrees, or radians when at most
// 2 pi: csail writes 3.14159), else laser_front_laser_resolution (degrees) * (n - 1), else the
// scanner's resolution by the beam count as CARMEN's tools read these logs (1 deg for 180 or
// 181 beams, 0.5 deg for 360 or 361: 180 beams span -89.5..+89.5 deg), else 180 deg. RLASER:
// the same with laser_rear_laser_*; the rear laser looks backwards, as CARMEN mounts it: mount
// (-robot_rearlaser_offset, 0, pi). FLASER mount: (robot_frontlaser_offset, 0, 0). A PARAM
// given twice (belgioioso) takes its last value. ROBOTLASER1 carries its own start angle,
// resolution and range, and its mount is robot_pose^-1 * laser_pose.
//
// Bad input: a malformed line (missing or non-numeric field, a non-finite pose or time, a time
// beyond +-9.2e9 s, which TimeNs cannot hold, a coordinate beyond +-1e7 m) is skipped and counted,
// and the first few are described in `warnings` as "file:line: field: problem"; with `strict`, the
// first one is an InputError naming the file, the 1-based line and the field instead.

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"

namespace lookout::io {

struct CarmenReadOptions {
  bool strict = false;  // strict: refuse the file at the first bad line
  // The "no return" limit of every laser of the log; 0: from the log (see above).
  double max_range_m = 0.0;
  // Readings within this of the limit are "no return": the saturated codes jitter by a few cm.
  double max_range_tolerance_m = 0.2;

  // Throws InputError naming the option (file "options") when a field is out of range.
  void Validate() const;
};

enum class CarmenSource { kOdometry, kFrontLaser, kRearLaser, kRobotLaser };

struct CarmenRecord {
  double t_s = 0.0;  // the log's own time base, seconds (ipc_timestamp, see above)
  // RAW odometry pose at this record, rebuilt by chaining the increments between consecutive
  // ODOM lines (identity at start), as described above.
  Pose2 odometry;
  // From FLASER / RLASER / ROBOTLASER1 (front laser for FLASER, rear for RLASER); stamp =
  // round(t_s * 1e9).
  std::optional<LidarScan> scan;
  // The log's corrected pose (the laser line's robot pose fields): a reference only, never an
  // input to localisation.
  std::optional<Pose2> reference_pose;
  CarmenSource source = CarmenSource::kOdometry;
  int line = 0;  // 1-based line of the file
};

struct CarmenLog {
  std::vector<CarmenRecord> records;          // file order
  std::map<std::string, std::string> params;  // PARAM lines (the last value of each name)
  std::size_t skipped_lines = 0;              // malformed lines skipped (non-strict)
  std::vector<std::string> warnings;          // "file:line: field: problem", first few
  std::size_t ignored_lines = 0;              // other message types (NEFF, SYNC, TRUEPOS...)
  std::size_t anchor_lines = 0;               // corrected-log anchor ODOM lines recognised
  std::size_t scans_without_odometry = 0;     // scans with no ODOM line since the previous scan
  std::size_t time_reversals = 0;             // records earlier than the record before them

  std::size_t ScanCount() const;
};

// How many malformed lines `warnings` describes at most.
inline constexpr std::size_t kMaxCarmenWarnings = 20;

// Reads a CARMEN log, plain or gzip (known by its magic bytes, see gzip_file.h).
CarmenLog ReadCarmenLog(const std::filesystem::path& path, const CarmenReadOptions& options = {});

// The same from text already in memory (for tests and the fuzzer); `name` is used in errors.
CarmenLog ParseCarmenLog(std::string_view text, const std::string& name,
                         const CarmenReadOptions& options = {});

}  // namespace lookout::io
