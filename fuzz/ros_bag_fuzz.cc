// Fuzz target for the ROS1 bag reader and the bag log on top of it: any bytes in, a RosBagLog
// or an InputError out. Any other exception (std::bad_alloc from a size taken on trust
// included), a crash, a hang or a sanitizer report is a bug in the reader, in the message
// decoder, or in how they drive libbz2/liblz4.
//
// Seeds: small bags that the tests' writer makes (src/lookout/io/ros_bag_test_support.h),
// written into the build tree by make_ros_bag_seeds.cc when this target is built: a scan,
// odometry, tf and people log with none, bz2 and lz4 chunks, and one without an index.

#include <cstddef>
#include <cstdint>
#include <string>

#include "lookout/core/input_error.h"
#include "lookout/io/ros_bag.h"
#include "lookout/io/ros_bag_log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    lookout::io::RosBag bag(std::move(bytes), "fuzz.bag");
    lookout::io::ReadRosBagLog(bag);
  } catch (const lookout::InputError&) {
    // The one way a bad bag may be refused.
  }
  return 0;
}
