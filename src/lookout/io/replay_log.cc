#include "lookout/io/replay_log.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <utility>

#include "lookout/core/input_error.h"
#include "lookout/io/carmen_log.h"
#include "lookout/io/file_bytes.h"
#include "lookout/io/gzip_file.h"
#include "lookout/io/json_schemas.h"
#include "lookout/io/mcap_reader.h"
#include "lookout/io/message_json.h"
#include "lookout/io/ros_bag.h"
#include "lookout/io/ros_bag_log.h"
#include "lookout/io/ros_transform_tree.h"
#include "lookout/io/zip_entry.h"

namespace lookout::io {
namespace {

constexpr std::string_view kBagMagic = "#ROSBAG V";
constexpr std::string_view kMcapMagic = "\x89MCAP0\r\n";
constexpr std::string_view kZipMagic = "PK\x03\x04";

// A laser tilted by more than this out of the plane still gives planar points, but wrong ones:
// the replay says so.
constexpr double kTiltWarning_rad = 0.05;

bool StartsWith(std::string_view bytes, std::string_view prefix) {
  return bytes.substr(0, prefix.size()) == prefix;
}

// "data/aces-corrected.log.gz" -> "aces-corrected".
std::string LogName(const std::string& source) {
  std::string name = std::filesystem::path(source).filename().string();
  for (bool stripped = true; stripped;) {
    stripped = false;
    for (std::string_view ext : {".gz", ".zip", ".bag", ".log", ".clf", ".mcap"}) {
      if (name.size() > ext.size() && name.ends_with(ext)) {
        name.resize(name.size() - ext.size());
        stripped = true;
      }
    }
  }
  return name.empty() ? std::string("log") : name;
}

class Degradations {
 public:
  explicit Degradations(ReplayLog& log) : log_(log) {}
  void Count(const std::string& what, std::uint64_t n = 1) {
    if (n > 0) log_.counts[what] += n;
  }
  void Warn(std::string line) {
    if (log_.warnings.size() < kMaxReplayWarnings) {
      log_.warnings.push_back(std::move(line));
    } else {
      ++dropped_;
    }
  }
  void Finish() {
    if (dropped_ > 0) log_.warnings.push_back(fmt::format("... and {} more", dropped_));
  }

 private:
  ReplayLog& log_;
  std::uint64_t dropped_ = 0;
};

// What every format goes through at the end: single bad messages out (counted), the duration,
// and the refusals that make a log unusable.
void Finalise(ReplayLog& log, Degradations& d) {
  const auto drop_backwards = [&](auto& stream, const char* what) {
    using T = typename std::decay_t<decltype(stream)>::value_type;
    std::vector<T> kept;
    kept.reserve(stream.size());
    std::uint64_t dropped = 0;
    for (T& m : stream) {
      if (!kept.empty() && m.stamp < kept.back().stamp) {
        if (dropped++ == 0) {
          d.Warn(fmt::format("{}: {} at {:.6f} s is earlier than the one before ({:.6f} s): "
                             "dropped (time going backwards)",
                             log.source, what, ToSeconds(m.stamp), ToSeconds(kept.back().stamp)));
        }
        continue;
      }
      kept.push_back(std::move(m));
    }
    stream = std::move(kept);
    d.Count(fmt::format("{}_backwards", what), dropped);
  };
  drop_backwards(log.odometry, "odometry");
  drop_backwards(log.stereo, "stereo");

  // Scans: also one per stamp (a cycle needs time to pass), finite geometry, and ranges as
  // REP 117 spells them. The people frames follow their scans' new indices.
  std::vector<LidarScan> kept;
  std::vector<std::optional<std::size_t>> new_index(log.lidar.size());
  std::uint64_t invalid_ranges = 0;
  for (std::size_t i = 0; i < log.lidar.size(); ++i) {
    LidarScan& s = log.lidar[i];
    const bool geometry = std::isfinite(s.angle_min_rad) && std::isfinite(s.angle_increment_rad) &&
                          std::isfinite(s.max_range_m) && std::isfinite(s.mount.x()) &&
                          std::isfinite(s.mount.y()) && std::isfinite(s.mount.yaw) &&
                          s.angle_increment_rad != 0.0 && !s.ranges_m.empty();
    if (!geometry) {
      if (log.counts["scans_bad_geometry"]++ == 0) {
        d.Warn(fmt::format("{}: scan at {:.6f} s: its angles, range limit or mount are not "
                           "finite, or it has no beam: dropped",
                           log.source, ToSeconds(s.stamp)));
      }
      continue;
    }
    if (!kept.empty() && s.stamp <= kept.back().stamp) {
      const bool backwards = s.stamp < kept.back().stamp;
      const char* what = backwards ? "scans_backwards" : "scans_same_stamp";
      if (log.counts[what]++ == 0) {
        d.Warn(fmt::format("{}: scan at {:.6f} s is {} the one before: dropped{}", log.source,
                           ToSeconds(s.stamp), backwards ? "earlier than" : "at the stamp of",
                           backwards ? " (time going backwards)" : ""));
      }
      continue;
    }
    for (float& r : s.ranges_m) {
      if (std::isnan(r) || r < 0.0f) {
        ++invalid_ranges;
        r = std::numeric_limits<float>::quiet_NaN();
      }
    }
    new_index[i] = kept.size();
    kept.push_back(std::move(s));
  }
  log.lidar = std::move(kept);
  d.Count("invalid_ranges", invalid_ranges);
  std::vector<PeopleFrame> people;
  for (PeopleFrame& f : log.people) {
    if (f.scan_index >= new_index.size() || !new_index[f.scan_index]) {
      d.Count("people_on_dropped_scans", f.people.size());
      continue;
    }
    f.scan_index = *new_index[f.scan_index];
    people.push_back(std::move(f));
  }
  log.people = std::move(people);

  if (log.lidar.empty()) {
    throw InputError(log.source, 0, "scans", "the log holds no usable laser scan");
  }
  TimeNs first = log.lidar.front().stamp;
  TimeNs last = log.lidar.back().stamp;
  for (const EgoOdometry& o : log.odometry) {
    first = std::min(first, o.stamp);
    last = std::max(last, o.stamp);
  }
  for (const StereoFrame& f : log.stereo) {
    first = std::min(first, f.stamp);
    last = std::max(last, f.stamp);
  }
  log.duration_s = ToSeconds(last - first);
  if (log.odometry.empty()) {
    d.Warn(fmt::format("{}: the log has no odometry: the pipeline has no ego pose and skips "
                       "every scan",
                       log.source));
  }
  d.Finish();
}

// ---------------------------------------------------------------------------------- CARMEN

// The speed and yaw rate that carry `from` to `to` in dt along one arc, as dead reckoning
// integrates them (core/dead_reckoning.h: forward s sin(a)/a, left s (1 - cos a)/a, a the
// turn): the turn is the increment's, the arc length the least-squares fit of the chord.
EgoOdometry ArcReading(TimeNs stamp, const Pose2& from, const Pose2& to, double dt_s) {
  const Pose2 d = from.Inverse() * to;
  const double a = WrapAngle(d.yaw);
  // sin(a)/a and (1 - cos a)/a, with their series near 0.
  const double f = std::abs(a) < 1e-4 ? 1.0 - a * a / 6.0 : std::sin(a) / a;
  const double l = std::abs(a) < 1e-4 ? a / 2.0 - a * a * a / 24.0 : (1.0 - std::cos(a)) / a;
  const double s = (d.x() * f + d.y() * l) / (f * f + l * l);
  EgoOdometry o;
  o.stamp = stamp;
  o.speed_mps = s / dt_s;
  o.yaw_rate_radps = a / dt_s;
  return o;
}

void FromCarmen(const CarmenLog& carmen, ReplayLog& log, Degradations& d) {
  log.format = LogFormat::kCarmen;
  log.inputs.push_back("CARMEN laser lines (FLASER, RLASER, ROBOTLASER1)");
  log.inputs.push_back("raw odometry rebuilt from the ODOM increments");
  d.Count("lines_skipped", carmen.skipped_lines);
  d.Count("scans_without_odometry", carmen.scans_without_odometry);
  for (const std::string& w : carmen.warnings) d.Warn(w);

  // Without a time base (all stamps equal, or rounded to 10^4 s) the log cannot be run in time.
  std::size_t scans = 0, advancing = 0;
  std::optional<double> previous;
  for (const CarmenRecord& r : carmen.records) {
    if (!r.scan) continue;
    ++scans;
    if (previous && r.t_s > *previous) ++advancing;
    previous = r.t_s;
  }
  if (scans >= 2 && 2 * advancing < scans - 1) {
    throw InputError(log.source, 0, "ipc_timestamp",
                     fmt::format("the log has no usable time base: {} of its {} scans do not "
                                 "come later than the scan before (`lookout slam` reads such a "
                                 "log by the order of its lines)",
                                 scans - 1 - advancing, scans));
  }

  // The raw odometry pose at each distinct time (the last one printed at that time).
  struct Sample {
    TimeNs t;
    Pose2 pose;
  };
  std::vector<Sample> poses;
  std::optional<double> last_t;
  for (const CarmenRecord& r : carmen.records) {
    if (last_t && r.t_s < *last_t) {
      // Records earlier than the one before: dropped (Finalise counts the scans among them).
      if (!r.scan) d.Count("odometry_backwards");
      if (r.scan) log.lidar.push_back(*r.scan);
      continue;
    }
    last_t = r.t_s;
    const TimeNs t = FromSeconds(r.t_s);
    if (!poses.empty() && poses.back().t == t) {
      poses.back().pose = r.odometry;
    } else {
      poses.push_back({t, r.odometry});
    }
    if (r.scan) {
      log.lidar.push_back(*r.scan);
      if (r.reference_pose) log.reference.push_back({r.scan->stamp, *r.reference_pose});
    }
  }
  log.odometry.reserve(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k + 1 < poses.size()) {
      const double dt = ToSeconds(poses[k + 1].t - poses[k].t);
      log.odometry.push_back(ArcReading(poses[k].t, poses[k].pose, poses[k + 1].pose, dt));
    } else {
      log.odometry.push_back(EgoOdometry{poses[k].t, 0.0, 0.0});  // the log ends: stopped
    }
  }
  // A reference pose belongs to a scan Finalise may drop (same stamp): keep one per stamp.
  log.reference.erase(std::unique(log.reference.begin(), log.reference.end(),
                                  [](const ReferencePose& a, const ReferencePose& b) {
                                    return a.stamp == b.stamp;
                                  }),
                      log.reference.end());
}

// ------------------------------------------------------------------------------- ROS bag

void FromRosBag(const RosBagLog& bag, ReplayLog& log, Degradations& d) {
  log.format = LogFormat::kRosBag;
  const auto topic_line = [&](const std::string& topic, const char* role) {
    for (const RosTopicSummary& t : bag.topics) {
      if (t.topic == topic) {
        log.inputs.push_back(fmt::format("{} {} ({}, {} messages)", role, t.topic, t.type,
                                         t.message_count));
      }
    }
  };
  topic_line(bag.scan_topic, "scans");
  topic_line(bag.odom_topic, "odometry");
  topic_line(bag.truth_topic, "truth");
  d.Count("messages_skipped", bag.messages_skipped);
  d.Count("chunks_skipped", bag.bag.chunks_skipped);
  d.Count("truncated_bytes", bag.bag.truncated_bytes);
  for (const std::string& w : bag.bag.warnings) d.Warn(w);
  for (const std::string& w : bag.warnings) d.Warn(w);

  const RosTransformTree tree(bag.transforms);
  // The vehicle frame is the odometry's child frame (base_link on a ROS robot).
  const std::string base =
      bag.odometry.empty() ? std::string("base_link")
                           : NormaliseFrameId(bag.odometry.front().child_frame_id);
  log.inputs.push_back(fmt::format("vehicle frame {}, sensor mounts from {} transforms", base,
                                   bag.transforms.size()));
  std::set<std::string> tilt_warned;
  const auto pose_in_base = [&](const std::string& frame, TimeNs t, const std::string& field)
      -> Pose2 {
    if (NormaliseFrameId(frame) == base) return Pose2();
    const std::optional<RosTransformTree::Lookup> found = tree.Find(base, frame, t);
    if (!found) {
      throw InputError(log.source, 0, field,
                       fmt::format("no transform from '{}' to the vehicle frame '{}' in the "
                                   "bag's tf",
                                   frame, base));
    }
    if (found->max_tilt_rad > kTiltWarning_rad && tilt_warned.insert(frame).second) {
      d.Warn(fmt::format("{}: frame '{}' is tilted by {:.1f} deg out of the vehicle's plane: "
                         "taken as level",
                         log.source, frame, RadToDeg(found->max_tilt_rad)));
    }
    return found->pose;
  };

  // (Ranges outside the laser's limits are already NaN: Finalise counts them.)
  log.lidar.reserve(bag.scans.size());
  for (const RosLaserScan& s : bag.scans) {
    LidarScan scan = s.scan;
    scan.mount = pose_in_base(s.frame_id, scan.stamp, bag.scan_topic + ".header.frame_id");
    log.lidar.push_back(std::move(scan));
  }
  log.odometry.reserve(bag.odometry.size());
  for (const RosOdometry& o : bag.odometry) log.odometry.push_back(o.Ego());

  if (bag.people.empty()) return;
  // The annotations are in the frame of their markers (the annotation tool draws each person
  // in its fixed frame), else in the scan's frame, the tool's default.
  log.people_frame = !bag.people_frame_id.empty() ? NormaliseFrameId(bag.people_frame_id)
                     : bag.scans.empty()           ? base
                                                   : NormaliseFrameId(bag.scans.front().frame_id);
  if (bag.people_frame_id.empty()) {
    d.Warn(fmt::format("{}: no marker gives the annotations' frame: taken as the scans' frame "
                       "'{}'",
                       log.source, log.people_frame));
  }
  // An annotation belongs to the scan on screen when it was made: the last scan recorded before
  // it (the tool stamps it between that scan's record and the next one's).
  std::map<std::size_t, PeopleFrame> frames;
  for (const PersonTruth& p : bag.people) {
    const auto after = std::upper_bound(
        bag.scans.begin(), bag.scans.end(), p.stamp,
        [](TimeNs t, const RosLaserScan& s) { return t <= s.record_stamp; });
    if (after == bag.scans.begin()) {
      d.Count("people_before_first_scan");
      continue;
    }
    const std::size_t k = static_cast<std::size_t>(after - bag.scans.begin()) - 1;
    PeopleFrame& frame = frames[k];
    frame.scan_index = k;
    frame.stamp = log.lidar[k].stamp;
    const Pose2 base_from_people = pose_in_base(
        log.people_frame, frame.stamp, bag.truth_topic + " (annotation frame)");
    frame.people.push_back({p.id, base_from_people * Eigen::Vector2d(p.x_m, p.y_m)});
  }
  for (auto& [k, frame] : frames) log.people.push_back(std::move(frame));
}

// ---------------------------------------------------------------------------------- MCAP

void FromMcap(const McapContents& mcap, const ReplayLogOptions& options, ReplayLog& log,
              Degradations& d) {
  log.format = LogFormat::kMcap;
  // Channels by the schema of their messages.
  const auto channels_of = [&](const std::string& schema) {
    std::vector<const McapChannel*> out;
    for (const auto& [id, channel] : mcap.channels) {
      const auto s = mcap.schemas.find(channel.schema_id);
      if (s != mcap.schemas.end() && s->second.name == schema &&
          channel.message_encoding == "json") {
        out.push_back(&channel);
      }
    }
    return out;
  };
  const auto choose = [&](const std::string& schema, const std::string& wanted,
                          const char* option) -> const McapChannel* {
    const std::vector<const McapChannel*> channels = channels_of(schema);
    std::vector<std::string> topics;
    for (const McapChannel* c : channels) topics.push_back(c->topic);
    if (!wanted.empty()) {
      for (const McapChannel* c : channels) {
        if (c->topic == wanted) return c;
      }
      throw InputError(log.source, 0, option,
                       fmt::format("the recording has no {} topic '{}' (its {} topics: {})",
                                   schema, wanted, schema, fmt::join(topics, ", ")));
    }
    if (channels.size() > 1) {
      throw InputError(log.source, 0, option,
                       fmt::format("the recording has several {} topics ({}): choose one",
                                   schema, fmt::join(topics, ", ")));
    }
    return channels.empty() ? nullptr : channels.front();
  };
  const McapChannel* scans = choose(FoxgloveLaserScanSchema().name, options.scan_topic,
                                    "scan_topic");
  const McapChannel* odometry = choose(LookoutEgoOdometrySchema().name, options.odom_topic,
                                       "odom_topic");
  const McapChannel* stereo = choose(LookoutStereoFrameSchema().name, "", "stereo_topic");
  std::map<std::uint16_t, std::uint64_t> counts;
  for (const McapMessage& m : mcap.messages) ++counts[m.channel_id];
  for (const McapChannel* c : {scans, odometry, stereo}) {
    if (c) {
      log.inputs.push_back(fmt::format("{} ({}, {} messages)", c->topic,
                                       mcap.schemas.at(c->schema_id).name, counts[c->id]));
    }
  }

  std::uint64_t skipped = 0;
  for (const McapMessage& m : mcap.messages) {
    const McapChannel* channel = scans && m.channel_id == scans->id         ? scans
                                 : odometry && m.channel_id == odometry->id ? odometry
                                 : stereo && m.channel_id == stereo->id     ? stereo
                                                                            : nullptr;
    if (!channel) continue;
    try {
      const nlohmann::json j = nlohmann::json::parse(m.data);
      if (channel == scans) {
        log.lidar.push_back(LidarScanFromJson(j, log.source));
      } else if (channel == odometry) {
        log.odometry.push_back(EgoOdometryFromJson(j, log.source));
      } else {
        log.stereo.push_back(StereoFrameFromJson(j, log.source));
      }
    } catch (const std::exception& e) {  // JSON syntax, or a field missing or of another type
      ++skipped;
      d.Warn(fmt::format("{}: {} message {} at {:.6f} s skipped: {}", log.source,
                         channel->topic, m.sequence, ToSeconds(m.log_time), e.what()));
    }
  }
  d.Count("messages_skipped", skipped);
}

ReplayLog FromBytes(std::string bytes, const std::string& source,
                    const ReplayLogOptions& options, int depth) {
  ReplayLog log;
  log.source = source;
  log.name = LogName(source);
  Degradations d(log);
  if (StartsWith(bytes, kZipMagic)) {
    if (depth > 0) throw InputError(source, 0, "zip", "a zip inside a zip");
    ZipEntry entry = ExtractSingleZipEntry(bytes, source);
    bytes.clear();
    return FromBytes(std::move(entry.data), source, options, depth + 1);
  }
  if (HasGzipMagic(bytes)) {
    throw InputError(source, 0, "gzip",
                     depth > 0 ? "a gzip file inside a zip: unzip it first"
                               : "gzip data is read from a file (ReadReplayLog)");
  }
  switch (DetectLogFormat(bytes)) {
    case LogFormat::kRosBag: {
      RosBag bag(std::move(bytes), source);
      RosBagLogOptions bag_options;
      bag_options.scan_topic = options.scan_topic;
      bag_options.odom_topic = options.odom_topic;
      bag_options.truth_topic = options.truth_topic;
      FromRosBag(ReadRosBagLog(bag, bag_options), log, d);
      break;
    }
    case LogFormat::kMcap:
      FromMcap(ReadMcapBytes(bytes, source), options, log, d);
      break;
    case LogFormat::kCarmen: {
      const CarmenLog carmen = ParseCarmenLog(bytes, source);
      if (carmen.records.empty()) {
        throw InputError(source, 0, "format",
                         "not a log lookout replays: no CARMEN ODOM or laser line, and not a "
                         "ROS1 bag, an MCAP file, or one of them zipped");
      }
      FromCarmen(carmen, log, d);
      break;
    }
  }
  Finalise(log, d);
  return log;
}

}  // namespace

const char* LogFormatName(LogFormat format) {
  switch (format) {
    case LogFormat::kCarmen:
      return "CARMEN";
    case LogFormat::kRosBag:
      return "ROS1 bag";
    case LogFormat::kMcap:
      return "MCAP";
  }
  return "?";
}

void ReplayLogOptions::Validate() const {
  const auto check = [](const std::string& topic, const char* field) {
    const bool ok = topic.empty() ||
                    (topic.size() > 1 && topic.front() == '/' &&
                     std::all_of(topic.begin(), topic.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' ||
                              c == '/';
                     }));
    if (!ok) {
      throw InputError("options", 0, field,
                       fmt::format("'{}' is not a topic name like /scan", topic));
    }
  };
  check(scan_topic, "scan_topic");
  check(odom_topic, "odom_topic");
  check(truth_topic, "truth_topic");
}

LogFormat DetectLogFormat(std::string_view bytes) {
  if (StartsWith(bytes, kBagMagic)) return LogFormat::kRosBag;
  if (StartsWith(bytes, kMcapMagic)) return LogFormat::kMcap;
  return LogFormat::kCarmen;
}

ReplayLog ReadReplayLog(const std::string& path, const ReplayLogOptions& options) {
  options.Validate();
  std::string bytes = ReadFileBytes(path);
  if (HasGzipMagic(bytes)) {
    bytes = ReadMaybeGzippedFile(path);  // inflated, by zlib's stream API
    if (HasGzipMagic(bytes)) throw InputError(path, 0, "gzip", "a gzip file inside a gzip file");
  }
  return FromBytes(std::move(bytes), path, options, 0);
}

ReplayLog ReplayLogFromBytes(std::string bytes, const std::string& source,
                             const ReplayLogOptions& options) {
  options.Validate();
  return FromBytes(std::move(bytes), source, options, 0);
}

}  // namespace lookout::io
