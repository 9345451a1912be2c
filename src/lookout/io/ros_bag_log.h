#pragma once

// A ROS1 bag as a Lookout log: which topics it holds, and its laser scans, odometry,
// transforms and ground-truth people decoded into Lookout's types, each in time order.
//
// Topics are found by message type (docs/cli-contract.md, `lookout replay`):
//   scans     sensor_msgs/LaserScan           one topic, or the one `scan_topic` names
//   odometry  nav_msgs/Odometry               one topic, or `odom_topic`
//   truth     leg_tracker/Person              one topic, or `truth_topic`
//   tf        tf2_msgs/TFMessage, tf/tfMessage  every such topic (/tf and /tf_static)
//   markers   visualization_msgs/Marker       every such topic, for the annotations' frame only
// Several topics of one kind and no option to choose: an InputError that lists them. Messages
// are decoded by the definitions the bag carries (ros_message.h).
//
// Time base: every stamp is nanoseconds after the bag's earliest message record time
// (`start_unix_ns`, kept so that absolute ROS time can be rebuilt), as docs/conventions.md
// asks of logs. A header stamp of 0 (a driver that does not stamp) takes the record's time.
//
// Bad data: a definition that does not parse, for a topic that is read, is an InputError (no
// message of it could be decoded). A message that does not decode or convert (too short, a
// field of the wrong type, a zero quaternion) is skipped and counted in `messages_skipped`,
// with a line in `warnings`. Chunk-level skips are in `bag` (ros_bag.h).

#include <cstdint>
#include <string>
#include <vector>

#include "lookout/core/time.h"
#include "lookout/io/ros_bag.h"
#include "lookout/io/ros_conversions.h"

namespace lookout::io {

struct RosBagLogOptions {
  std::string scan_topic;   // empty: the bag's one sensor_msgs/LaserScan topic
  std::string odom_topic;   // empty: its one nav_msgs/Odometry topic
  std::string truth_topic;  // empty: its one leg_tracker/Person topic

  // Throws InputError (file "options") naming the field when a topic is not a ROS name.
  void Validate() const;
};

struct RosTopicSummary {
  std::string topic;
  std::string type;
  std::uint64_t message_count = 0;  // message records read
};

inline constexpr std::size_t kMaxRosLogWarnings = 100;

// The marker namespace of leg_tracker_benchmarks' annotation tool (annotate_rosbags.py).
inline constexpr const char* kPeopleMarkerNamespace = "ground_truth_people_tracks_markers";

struct RosBagLog {
  std::string source;
  TimeNs start_unix_ns = 0;  // the earliest message record time: 0 of the log's time base
  TimeNs end_ns = 0;         // the latest message record time, in the log's time base
  std::vector<RosTopicSummary> topics;  // every topic, by name
  std::string scan_topic;  // the topics read; empty when the bag has none of that kind
  std::string odom_topic;
  std::string truth_topic;
  std::vector<RosLaserScan> scans;
  std::vector<RosOdometry> odometry;
  std::vector<RosTransform> transforms;
  std::vector<PersonTruth> people;
  // The frame the people were annotated in: leg_tracker/Person has no header, but the
  // benchmark's annotation tool draws each annotated person as a visualization_msgs/Marker in
  // that frame (namespace kPeopleMarkerNamespace). Empty when no such marker is in the bag.
  std::string people_frame_id;
  std::uint64_t messages_skipped = 0;
  std::vector<std::string> warnings;  // at most kMaxRosLogWarnings lines, then a count
  RosBagStats bag;
};

RosBagLog ReadRosBagLog(const std::string& path, const RosBagLogOptions& options = {});
RosBagLog ReadRosBagLog(RosBag& bag, const RosBagLogOptions& options = {});

}  // namespace lookout::io
