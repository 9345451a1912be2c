#pragma once

// Test-only: a tiny writer of ROS1 bags (format 2.0) and of the ROS1 serialisation, to build
// small bags inside the tests and the fuzz seeds. Included by *_test.cc files only.
//
// The writer lays a bag out as rosbag does: magic, a bag header record padded to 4096 bytes,
// chunks (each with the connection records of connections first used in it, then message
// data records), an index data record per connection after each chunk, and at index_pos the
// connection records and one chunk info per chunk. lz4 chunks are LZ4 frames with independent
// 1 MiB blocks and a content checksum, as roslz4 writes them.

#include <bzlib.h>
#include <lz4frame.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lookout/io/ros_message.h"

namespace lookout::io::testing {

// Appends ROS1-serialised values (little-endian, no padding).
class RosSerializer {
 public:
  template <typename T>
  RosSerializer& Put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes_.append(raw, sizeof(T));
    return *this;
  }
  RosSerializer& PutString(std::string_view s) {
    Put(static_cast<std::uint32_t>(s.size()));
    bytes_.append(s);
    return *this;
  }
  RosSerializer& PutTime(RosTime t) { return Put(t.sec).Put(t.nsec); }
  RosSerializer& PutHeader(std::uint32_t seq, RosTime stamp, std::string_view frame_id) {
    return Put(seq).PutTime(stamp).PutString(frame_id);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// The definitions of the leg-tracker bag's types, as ROS writes them into connection headers
// (comments dropped; the real texts with comments are tested on the real bag).
inline constexpr std::string_view kHeaderDefinition =
    "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n";
inline const std::string kSeparator(80, '=');

inline std::string LaserScanDefinition() {
  return "Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
         "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
         "float32[] ranges\nfloat32[] intensities\n" +
         kSeparator + "\n" + std::string(kHeaderDefinition);
}

inline std::string OdometryDefinition() {
  const std::string s = kSeparator + "\n";
  return "Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
         "geometry_msgs/TwistWithCovariance twist\n" +
         s + std::string(kHeaderDefinition) + s +
         "MSG: geometry_msgs/PoseWithCovariance\nPose pose\nfloat64[36] covariance\n" + s +
         "MSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n" + s +
         "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" + s +
         "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n" + s +
         "MSG: geometry_msgs/TwistWithCovariance\nTwist twist\nfloat64[36] covariance\n" + s +
         "MSG: geometry_msgs/Twist\nVector3  linear\nVector3  angular\n" + s +
         "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";
}

inline std::string TfMessageDefinition() {
  const std::string s = kSeparator + "\n";
  return "geometry_msgs/TransformStamped[] transforms\n" + s +
         "MSG: geometry_msgs/TransformStamped\nHeader header\nstring child_frame_id\n"
         "Transform transform\n" +
         s + std::string(kHeaderDefinition) + s +
         "MSG: geometry_msgs/Transform\nVector3 translation\nQuaternion rotation\n" + s +
         "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n" + s +
         "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n";
}

inline std::string PersonDefinition() {
  const std::string s = kSeparator + "\n";
  return "geometry_msgs/Pose pose\nuint32 id\n" + s +
         "MSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n" + s +
         "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" + s +
         "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n";
}

inline std::string LaserScanMessage(RosTime stamp, float angle_min, float increment,
                                    const std::vector<float>& ranges, float range_min = 0.03F,
                                    float range_max = 11.0F) {
  RosSerializer s;
  s.PutHeader(7, stamp, "laser").Put(angle_min);
  s.Put(angle_min + increment * static_cast<float>(ranges.size() - 1)).Put(increment);
  s.Put(0.0F).Put(0.1F).Put(range_min).Put(range_max);
  s.Put(static_cast<std::uint32_t>(ranges.size()));
  for (const float r : ranges) s.Put(r);
  s.Put(std::uint32_t{0});  // no intensities
  return s.bytes();
}

inline void PutPose(RosSerializer& s, double x, double y, double yaw) {
  s.Put(x).Put(y).Put(0.0);
  s.Put(0.0).Put(0.0).Put(std::sin(yaw / 2)).Put(std::cos(yaw / 2));
}

inline std::string OdometryMessage(RosTime stamp, double x, double y, double yaw, double speed,
                                   double yaw_rate) {
  RosSerializer s;
  s.PutHeader(1, stamp, "odom").PutString("base_link");
  PutPose(s, x, y, yaw);
  for (int i = 0; i < 36; ++i) s.Put(i == 0 ? 0.01 : 0.0);
  s.Put(speed).Put(0.0).Put(0.0).Put(0.0).Put(0.0).Put(yaw_rate);
  for (int i = 0; i < 36; ++i) s.Put(0.0);
  return s.bytes();
}

struct TestTransform {
  RosTime stamp;
  std::string parent;
  std::string child;
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

inline std::string TfMessage(const std::vector<TestTransform>& transforms) {
  RosSerializer s;
  s.Put(static_cast<std::uint32_t>(transforms.size()));
  for (const TestTransform& t : transforms) {
    s.PutHeader(0, t.stamp, t.parent).PutString(t.child);
    s.Put(t.x).Put(t.y).Put(0.0);
    s.Put(0.0).Put(0.0).Put(std::sin(t.yaw / 2)).Put(std::cos(t.yaw / 2));
  }
  return s.bytes();
}

inline std::string PersonMessage(double x, double y, std::uint32_t id) {
  RosSerializer s;
  PutPose(s, x, y, 0.0);
  s.Put(id);
  return s.bytes();
}

class TestBagWriter {
 public:
  struct Options {
    std::string compression = "none";  // none, bz2 or lz4
    std::size_t messages_per_chunk = 3;
    bool index = true;  // false: index_pos 0 and no index section, as a killed recording
  };

  explicit TestBagWriter(Options options) : options_(std::move(options)) {}

  void AddConnection(std::uint32_t id, std::string topic, std::string type,
                     std::string definition) {
    connections_.push_back({id, std::move(topic), std::move(type), std::move(definition)});
  }
  void AddMessage(std::uint32_t connection, RosTime time, std::string data) {
    messages_.push_back({connection, time, std::move(data)});
  }

  std::string Finish() const {
    std::string out("#ROSBAG V2.0\n");
    const std::size_t header_position = out.size();
    out += BagHeader(0, 0, 0);  // rewritten at the end
    std::set<std::uint32_t> written;
    std::vector<std::string> chunk_infos;
    for (std::size_t first = 0; first < messages_.size(); first += options_.messages_per_chunk) {
      const std::size_t last = std::min(messages_.size(), first + options_.messages_per_chunk);
      std::string records;
      std::map<std::uint32_t, std::vector<std::pair<RosTime, std::uint32_t>>> index;
      RosTime start = messages_[first].time;
      RosTime end = messages_[first].time;
      for (std::size_t i = first; i < last; ++i) {
        const Message& m = messages_[i];
        if (written.insert(m.connection).second) {
          records += ConnectionRecord(Connection(m.connection));
        }
        index[m.connection].emplace_back(m.time, static_cast<std::uint32_t>(records.size()));
        records += Record({{"op", std::string(1, '\x02')}, {"conn", U32(m.connection)},
                           {"time", Time(m.time)}},
                          m.data);
        if (Less(m.time, start)) start = m.time;
        if (Less(end, m.time)) end = m.time;
      }
      const std::uint64_t chunk_position = out.size();
      out += Record({{"op", std::string(1, '\x05')}, {"compression", options_.compression},
                     {"size", U32(static_cast<std::uint32_t>(records.size()))}},
                    Compress(records));
      std::string counts;
      for (const auto& [connection, entries] : index) {
        std::string data;
        for (const auto& [time, offset] : entries) data += Time(time) + U32(offset);
        out += Record({{"op", std::string(1, '\x04')}, {"ver", U32(1)}, {"conn", U32(connection)},
                       {"count", U32(static_cast<std::uint32_t>(entries.size()))}},
                      data);
        counts += U32(connection) + U32(static_cast<std::uint32_t>(entries.size()));
      }
      chunk_infos.push_back(Record(
          {{"op", std::string(1, '\x06')}, {"ver", U32(1)}, {"chunk_pos", U64(chunk_position)},
           {"start_time", Time(start)}, {"end_time", Time(end)},
           {"count", U32(static_cast<std::uint32_t>(index.size()))}},
          counts));
    }
    if (!options_.index) return out;
    const std::uint64_t index_position = out.size();
    for (const ConnectionSpec& c : connections_) out += ConnectionRecord(c);
    for (const std::string& info : chunk_infos) out += info;
    out.replace(header_position, 4096,
                BagHeader(index_position, static_cast<std::uint32_t>(connections_.size()),
                          static_cast<std::uint32_t>(chunk_infos.size())));
    return out;
  }

  static std::string U32(std::uint32_t v) { return Raw(v); }
  static std::string U64(std::uint64_t v) { return Raw(v); }
  static std::string Time(RosTime t) { return Raw(t.sec) + Raw(t.nsec); }

  static std::string Fields(const std::vector<std::pair<std::string, std::string>>& fields) {
    std::string out;
    for (const auto& [name, value] : fields) {
      out += U32(static_cast<std::uint32_t>(name.size() + 1 + value.size())) + name + "=" + value;
    }
    return out;
  }

  static std::string Record(const std::vector<std::pair<std::string, std::string>>& header,
                            std::string_view data) {
    const std::string h = Fields(header);
    return U32(static_cast<std::uint32_t>(h.size())) + h +
           U32(static_cast<std::uint32_t>(data.size())) + std::string(data);
  }

 private:
  struct ConnectionSpec {
    std::uint32_t id;
    std::string topic;
    std::string type;
    std::string definition;
  };
  struct Message {
    std::uint32_t connection;
    RosTime time;
    std::string data;
  };

  template <typename T>
  static std::string Raw(T v) {
    std::string s(sizeof(T), '\0');
    std::memcpy(s.data(), &v, sizeof(T));
    return s;
  }

  static bool Less(RosTime a, RosTime b) {
    return a.sec < b.sec || (a.sec == b.sec && a.nsec < b.nsec);
  }

  const ConnectionSpec& Connection(std::uint32_t id) const {
    for (const ConnectionSpec& c : connections_) {
      if (c.id == id) return c;
    }
    throw std::logic_error("message on a connection that was not added");
  }

  static std::string ConnectionRecord(const ConnectionSpec& c) {
    return Record({{"op", std::string(1, '\x07')}, {"conn", U32(c.id)}, {"topic", c.topic}},
                  Fields({{"topic", c.topic},
                          {"type", c.type},
                          {"md5sum", std::string(32, '0')},
                          {"message_definition", c.definition},
                          {"callerid", "/test"}}));
  }

  // rosbag pads the bag header record to 4096 bytes so that it can be rewritten in place.
  static std::string BagHeader(std::uint64_t index_position, std::uint32_t connections,
                               std::uint32_t chunks) {
    const std::string h = Fields({{"op", std::string(1, '\x03')},
                                  {"index_pos", U64(index_position)},
                                  {"conn_count", U32(connections)},
                                  {"chunk_count", U32(chunks)}});
    const std::size_t padding = 4096 - 8 - h.size();
    return U32(static_cast<std::uint32_t>(h.size())) + h +
           U32(static_cast<std::uint32_t>(padding)) + std::string(padding, ' ');
  }

  std::string Compress(const std::string& records) const {
    if (options_.compression == "bz2") {
      std::string out(records.size() + records.size() / 100 + 600, '\0');
      auto size = static_cast<unsigned int>(out.size());
      if (BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(records.data()),
                                   static_cast<unsigned int>(records.size()), 9, 0, 0) != BZ_OK) {
        throw std::runtime_error("bz2 compression failed");
      }
      out.resize(size);
      return out;
    }
    if (options_.compression == "lz4") {
      LZ4F_preferences_t preferences{};
      preferences.frameInfo.blockSizeID = LZ4F_max1MB;
      preferences.frameInfo.blockMode = LZ4F_blockIndependent;
      preferences.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
      std::string out(LZ4F_compressFrameBound(records.size(), &preferences), '\0');
      const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), records.data(),
                                               records.size(), &preferences);
      if (LZ4F_isError(n) != 0) throw std::runtime_error("lz4 compression failed");
      out.resize(n);
      return out;
    }
    return records;
  }

  Options options_;
  std::vector<ConnectionSpec> connections_;
  std::vector<Message> messages_;
};

// A small log: two scans written out of stamp order, odometry, tf, people, and one scan whose
// bytes are cut short.
inline std::string SmallLog(const std::string& compression, bool second_scan_topic = false,
                     bool index = true) {
  TestBagWriter writer({compression, 4, index});
  writer.AddConnection(0, "/scan", "sensor_msgs/LaserScan", testing::LaserScanDefinition());
  writer.AddConnection(1, "/odom", "nav_msgs/Odometry", testing::OdometryDefinition());
  writer.AddConnection(2, "/tf", "tf2_msgs/TFMessage", testing::TfMessageDefinition());
  writer.AddConnection(3, "/truth", "leg_tracker/Person", testing::PersonDefinition());
  writer.AddConnection(4, "/chatter", "std_msgs/String", "string data\n");
  if (second_scan_topic) {
    writer.AddConnection(5, "/scan2", "sensor_msgs/LaserScan", testing::LaserScanDefinition());
    writer.AddMessage(5, {100, 0}, testing::LaserScanMessage({100, 0}, -1.0F, 0.5F, {1.0F}));
  }
  writer.AddMessage(4, {100, 0}, testing::RosSerializer().PutString("hello").bytes());
  writer.AddMessage(0, {101, 0},
                    testing::LaserScanMessage({100, 900000000}, -1.0F, 0.5F, {1, 2, 3, 4, 5}));
  writer.AddMessage(0, {101, 100},
                    testing::LaserScanMessage({100, 800000000}, -1.0F, 0.5F, {1, 2, 3, 4, 5}));
  writer.AddMessage(0, {101, 200}, testing::LaserScanMessage({0, 0}, -1.0F, 0.5F, {2.0F}));
  writer.AddMessage(0, {101, 300},
                    testing::LaserScanMessage({101, 0}, -1.0F, 0.5F, {1, 2}).substr(0, 30));
  writer.AddMessage(1, {101, 400}, testing::OdometryMessage({101, 300}, 1, 2, 0.1, 0.5, 0.0));
  writer.AddMessage(2, {101, 500},
                    testing::TfMessage({{{101, 500}, "odom", "base_link", 1, 2, 0.1},
                                        {{101, 500}, "base_link", "laser", 0, 0, 0}}));
  writer.AddMessage(3, {102, 0}, testing::PersonMessage(1.0, 2.0, 7));
  writer.AddMessage(3, {102, 1}, testing::PersonMessage(3.0, 4.0, 8));
  return writer.Finish();
}

// The seed bags of the ROS bag fuzz target (fuzz/make_ros_bag_seeds.cc): the small log with
// each chunk compression, without an index, and with a second scan topic; (file name, bytes).
inline std::vector<std::pair<std::string, std::string>> FuzzSeedBags() {
  return {{"small-none.bag", SmallLog("none")},
          {"small-bz2.bag", SmallLog("bz2")},
          {"small-lz4.bag", SmallLog("lz4")},
          {"small-unindexed.bag", SmallLog("bz2", false, false)},
          {"small-two-scan-topics.bag", SmallLog("lz4", true)}};
}

}  // namespace lookout::io::testing
