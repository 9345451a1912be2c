#include "lookout/io/ros_bag_log.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

enum class Kind { kNone, kScan, kOdometry, kTransforms, kTruth, kMarker };

Kind KindOfType(std::string_view type) {
  if (type == "sensor_msgs/LaserScan") return Kind::kScan;
  if (type == "nav_msgs/Odometry") return Kind::kOdometry;
  if (type == "tf2_msgs/TFMessage" || type == "tf/tfMessage") return Kind::kTransforms;
  if (type == "leg_tracker/Person") return Kind::kTruth;
  if (type == "visualization_msgs/Marker") return Kind::kMarker;
  return Kind::kNone;
}

// What one topic decoded to, before the topics of each kind are chosen and merged.
struct TopicData {
  std::string type;
  std::uint64_t count = 0;
  std::vector<RosLaserScan> scans;
  std::vector<RosOdometry> odometry;
  std::vector<RosTransform> transforms;
  std::vector<PersonTruth> people;
};

bool IsRosName(std::string_view name) {
  return name.size() > 1 && name.front() == '/' && name.back() != '/' &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '/';
         });
}

// The topic of `kind` to read: the one the option names, or the only one there is.
std::string ChooseTopic(const std::map<std::string, TopicData>& topics, Kind kind,
                        std::string_view wanted_type, const std::string& option,
                        const std::string& option_name, const std::string& source) {
  std::vector<std::string> candidates;
  for (const auto& [topic, data] : topics) {
    if (KindOfType(data.type) == kind) candidates.push_back(topic);
  }
  if (!option.empty()) {
    const auto it = topics.find(option);
    if (it == topics.end() || KindOfType(it->second.type) != kind) {
      throw InputError(source, 0, option_name,
                       fmt::format("the bag has no {} topic '{}' (its {} topics: {})", wanted_type,
                                   option, wanted_type, fmt::join(candidates, ", ")));
    }
    return option;
  }
  if (candidates.size() > 1) {
    throw InputError(source, 0, option_name,
                     fmt::format("the bag has several {} topics ({}): choose one", wanted_type,
                                 fmt::join(candidates, ", ")));
  }
  return candidates.empty() ? std::string() : candidates.front();
}

template <typename T>
void SortAndShift(std::vector<T>& items, TimeNs origin) {
  for (T& item : items) {
    if constexpr (std::is_same_v<T, RosLaserScan>) {
      item.scan.stamp -= origin;
      item.record_stamp -= origin;
    } else {
      item.stamp -= origin;
    }
  }
  // Stable: messages with one stamp keep the bag's order, so the output is deterministic.
  std::stable_sort(items.begin(), items.end(), [](const T& a, const T& b) {
    if constexpr (std::is_same_v<T, RosLaserScan>) {
      return a.scan.stamp < b.scan.stamp;
    } else {
      return a.stamp < b.stamp;
    }
  });
}

}  // namespace

void RosBagLogOptions::Validate() const {
  const auto check = [](const std::string& topic, const char* field) {
    if (!topic.empty() && !IsRosName(topic)) {
      throw InputError("options", 0, field,
                       fmt::format("'{}' is not a ROS topic name like /scan", topic));
    }
  };
  check(scan_topic, "scan_topic");
  check(odom_topic, "odom_topic");
  check(truth_topic, "truth_topic");
}

RosBagLog ReadRosBagLog(const std::string& path, const RosBagLogOptions& options) {
  options.Validate();
  RosBag bag = RosBag::Open(path);
  return ReadRosBagLog(bag, options);
}

RosBagLog ReadRosBagLog(RosBag& bag, const RosBagLogOptions& options) {
  options.Validate();
  RosBagLog log;
  log.source = bag.source();
  std::map<std::string, TopicData> topics;
  std::map<std::uint32_t, std::shared_ptr<const RosMessageDefinition>> definitions;
  std::set<std::uint32_t> unreadable_markers;
  std::optional<TimeNs> first;
  TimeNs last = 0;
  std::uint64_t warnings_dropped = 0;
  const auto warn = [&](std::string line) {
    if (log.warnings.size() < kMaxRosLogWarnings) {
      log.warnings.push_back(std::move(line));
    } else {
      ++warnings_dropped;
    }
  };
  const auto read = [&](const std::string& option, Kind kind, const RosConnection& connection) {
    return KindOfType(connection.type) == kind && (option.empty() || option == connection.topic);
  };

  bag.ForEachMessage([&](const RosConnection& connection, const RosBagMessage& message) {
    const TimeNs time = ToTimeNs(message.time);
    first = std::min(first.value_or(time), time);
    last = std::max(last, time);
    TopicData& topic = topics[connection.topic];
    if (topic.count == 0) topic.type = connection.type;
    ++topic.count;
    const Kind kind = KindOfType(connection.type);
    // Markers only until one has given the annotations' frame.
    const bool wanted = kind == Kind::kTransforms ||
                        (kind == Kind::kMarker && log.people_frame_id.empty()) ||
                        read(options.scan_topic, Kind::kScan, connection) ||
                        read(options.odom_topic, Kind::kOdometry, connection) ||
                        read(options.truth_topic, Kind::kTruth, connection);
    if (!wanted) return;

    if (unreadable_markers.contains(connection.id)) return;
    auto& definition = definitions[connection.id];
    if (!definition) {
      try {
        definition = std::make_shared<const RosMessageDefinition>(
            ParseRosMessageDefinition(connection.type, connection.message_definition));
      } catch (const RosMessageError& e) {
        const std::string field = fmt::format("connection {} ({}).message_definition",
                                              connection.id, connection.topic);
        // Markers are read only for the annotations' frame: without them the log still reads.
        if (kind == Kind::kMarker) {
          unreadable_markers.insert(connection.id);
          warn(fmt::format("{}: {} (markers not read)", field, e.what()));
          return;
        }
        throw InputError(bag.source(), 0, field, e.what());
      }
    }
    try {
      const RosValue value = DecodeRosMessage(*definition, message.data);
      switch (kind) {
        case Kind::kScan: {
          RosLaserScan scan = ToLaserScan(value);
          if (scan.scan.stamp == 0) scan.scan.stamp = time;
          scan.record_stamp = time;
          topic.scans.push_back(std::move(scan));
          break;
        }
        case Kind::kOdometry: {
          RosOdometry odometry = ToOdometry(value);
          if (odometry.stamp == 0) odometry.stamp = time;
          topic.odometry.push_back(std::move(odometry));
          break;
        }
        case Kind::kTransforms:
          for (RosTransform& t : ToTransforms(value)) {
            if (t.stamp == 0) t.stamp = time;
            topic.transforms.push_back(std::move(t));
          }
          break;
        case Kind::kTruth:
          topic.people.push_back(ToPersonTruth(value, time));
          break;
        case Kind::kMarker:
          if (value["ns"].AsString() == kPeopleMarkerNamespace) {
            log.people_frame_id = value["header"]["frame_id"].AsString();
          }
          break;
        case Kind::kNone:
          break;
      }
    } catch (const RosMessageError& e) {
      ++log.messages_skipped;
      warn(fmt::format("{} message at {}.{:09} (chunk at byte {}) skipped: {}", connection.topic,
                       message.time.sec, message.time.nsec, message.chunk_position, e.what()));
    }
  });
  if (warnings_dropped > 0) warn(fmt::format("... and {} more", warnings_dropped));

  const RosBagLogOptions& o = options;
  log.scan_topic = ChooseTopic(topics, Kind::kScan, "sensor_msgs/LaserScan", o.scan_topic,
                               "scan_topic", log.source);
  log.odom_topic = ChooseTopic(topics, Kind::kOdometry, "nav_msgs/Odometry", o.odom_topic,
                               "odom_topic", log.source);
  log.truth_topic = ChooseTopic(topics, Kind::kTruth, "leg_tracker/Person", o.truth_topic,
                                "truth_topic", log.source);
  for (auto& [name, data] : topics) {
    log.topics.push_back(RosTopicSummary{name, data.type, data.count});
    if (name == log.scan_topic) log.scans = std::move(data.scans);
    if (name == log.odom_topic) log.odometry = std::move(data.odometry);
    if (name == log.truth_topic) log.people = std::move(data.people);
    log.transforms.insert(log.transforms.end(), std::make_move_iterator(data.transforms.begin()),
                          std::make_move_iterator(data.transforms.end()));
  }
  log.start_unix_ns = first.value_or(0);
  log.end_ns = last - log.start_unix_ns;
  SortAndShift(log.scans, log.start_unix_ns);
  SortAndShift(log.odometry, log.start_unix_ns);
  SortAndShift(log.transforms, log.start_unix_ns);
  SortAndShift(log.people, log.start_unix_ns);
  log.bag = bag.stats();
  return log;
}

}  // namespace lookout::io
