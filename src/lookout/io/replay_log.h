#pragma once

// A recorded log as the pipeline's message streams: what `lookout replay` reads
// (docs/replay.md). One reader for every format Lookout knows, told apart by their bytes,
// never by the file's name:
//   ROS1 bag      "#ROSBAG V2.0"                     ros_bag_log.h
//   MCAP          "\x89MCAP0\r\n" (a recording of `lookout run` or `lookout replay`)
//   zip           "PK\x03\x04": the single file inside, any of these formats but gzip
//   gzip          1f 8b: inflated, then CARMEN text
//   anything else CARMEN text (carmen_log.h); refused when it holds no CARMEN message
//
// What comes out, for every format alike:
//   lidar      LidarScan with its mount in the vehicle frame (CARMEN: the laser offset of the
//              log's PARAMs; bag: the tf tree from the odometry's child frame to the scan's
//              frame_id; MCAP: the mount recorded with each scan);
//   odometry   EgoOdometry, speed and yaw rate (bag: the twist of nav_msgs/Odometry; MCAP: as
//              recorded; CARMEN: the arc between consecutive raw odometry poses, rebuilt from
//              the ODOM increments, over the time between them, so that dead reckoning through
//              the readings passes through the raw poses);
//   stereo     StereoFrame (MCAP recordings of simulated runs only);
//   truth      what the log holds to score against: CARMEN's corrected poses at each scan (a
//              SLAM result, never an input), or the bag's annotated people
//              (leg_tracker/Person) grouped by the scan they were annotated on, in the vehicle
//              frame at that scan's stamp.
// Stamps are nanoseconds from the log's start (docs/conventions.md).
//
// Bad input. What makes the log unusable is an InputError naming the file and the field (no
// scan; a CARMEN log without a time base: more than half of its scans not later than the one
// before, as five Radish logs print them; a scan frame with no transform to the vehicle; a
// topic option naming no topic of the log; anything the format's reader refuses). What spoils
// single messages is dropped and counted in `counts`, the first of each kind described in
// `warnings`: a message earlier than the one before it in its stream (time going backwards), a
// scan at the same stamp as the previous one, a scan whose geometry is not finite. Beams without
// a valid measurement (NaN, negative, and what the format's reader discards) are NaN (REP 117)
// and counted; +inf stays ("no return"). docs/replay.md has the list.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout::io {

enum class LogFormat { kCarmen, kRosBag, kMcap };
const char* LogFormatName(LogFormat format);

struct ReplayLogOptions {
  // ROS bag and MCAP: the topic to read when several carry one kind; empty: the only one.
  std::string scan_topic;
  std::string odom_topic;
  std::string truth_topic;

  // Throws InputError (file "options") naming the field when a topic is not a topic name.
  void Validate() const;
};

// CARMEN: the log's corrected pose of the vehicle at a scan (the reference, not an input).
struct ReferencePose {
  TimeNs stamp = 0;
  Pose2 pose;
};

struct AnnotatedPerson {
  std::uint32_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // vehicle frame at the scan's stamp
};

// The people annotated on one scan.
struct PeopleFrame {
  std::size_t scan_index = 0;  // in ReplayLog::lidar
  TimeNs stamp = 0;            // the scan's
  std::vector<AnnotatedPerson> people;
};

struct ReplayLog {
  std::string source;  // the file
  std::string name;    // the file's name without its extensions ("aces-corrected")
  LogFormat format = LogFormat::kCarmen;
  std::vector<std::string> inputs;  // what was read, one line each ("/scan sensor_msgs/LaserScan")

  std::vector<LidarScan> lidar;
  std::vector<EgoOdometry> odometry;
  std::vector<StereoFrame> stereo;
  std::vector<ReferencePose> reference;
  std::vector<PeopleFrame> people;
  std::string people_frame;  // the frame the annotations were made in ("left_laser")

  double duration_s = 0.0;  // first to last message

  // Degradations, by name (docs/replay.md): "scans_backwards", "scans_same_stamp",
  // "scans_bad_geometry", "odometry_backwards", "stereo_backwards", "invalid_ranges",
  // "people_before_first_scan", ...; and the importers' own (CARMEN "lines_skipped", bag
  // "messages_skipped", "chunks_skipped", "truncated_bytes").
  std::map<std::string, std::uint64_t> counts;
  std::vector<std::string> warnings;  // at most kMaxReplayWarnings lines, then a count
};

inline constexpr std::size_t kMaxReplayWarnings = 50;

// The format of a log from its first bytes.
LogFormat DetectLogFormat(std::string_view bytes);

// Reads the log at `path`. Throws InputError (see above).
ReplayLog ReadReplayLog(const std::string& path, const ReplayLogOptions& options = {});

// The same from bytes in memory (tests, the fuzzer); `source` names them in errors and gives
// the log its name. A gzip file is read from `source` as a path (zlib's stream API), so bytes
// with the gzip magic that are not a file are refused.
ReplayLog ReplayLogFromBytes(std::string bytes, const std::string& source,
                             const ReplayLogOptions& options = {});

}  // namespace lookout::io
