// Fuzz target for the ROS1 message-definition parser, the dynamic decoder and the typed
// conversions. Input: a type name ("pkg/Type") on the first line, the definition text up to
// the first NUL byte, then the serialised message. A definition or message may be refused
// only with RosMessageError; anything else (another exception, a crash, a hang, a sanitizer
// report, an allocation sized by a corrupted count) is a bug.
//
// Seeds: fuzz/corpus/ros_message/ holds the LaserScan, Odometry, TFMessage and Person
// definitions with one message each, from the tests' writer (see ros_bag_fuzz.cc).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lookout/io/ros_conversions.h"
#include "lookout/io/ros_message.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lookout::io;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t type_end = input.find('\n');
  const std::size_t text_end = input.find('\0');
  if (type_end == std::string_view::npos || text_end == std::string_view::npos ||
      text_end < type_end) {
    return 0;
  }
  const std::string_view type = input.substr(0, type_end);
  const std::string_view text = input.substr(type_end + 1, text_end - type_end - 1);
  const std::string_view message = input.substr(text_end + 1);
  try {
    const RosMessageDefinition definition = ParseRosMessageDefinition(type, text);
    MinimumSerializedSize(definition, definition.root);
    const RosValue value = DecodeRosMessage(definition, message);
    if (type == "sensor_msgs/LaserScan") ToLaserScan(value);
    if (type == "nav_msgs/Odometry") ToOdometry(value);
    if (type == "tf2_msgs/TFMessage") ToTransforms(value);
    if (type == "leg_tracker/Person") ToPersonTruth(value, 0);
  } catch (const RosMessageError&) {
    // The one way a bad definition or message may be refused.
  }
  return 0;
}
