// Fuzz target for the log detection and dispatch of `lookout replay` (io/replay_log.h): any
// bytes in, told apart by their magic (ROS1 bag, MCAP, zip, CARMEN text), read by the format's
// reader and turned into the pipeline's streams; a ReplayLog or an InputError out, nothing else.
// What comes out must hold what the message loop relies on (below). Any other exception, a
// crash, a hang or a sanitizer report is a bug.
//
// Seeds: the CARMEN and MCAP corpora and the ROS bag seeds (fuzz/CMakeLists.txt).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "lookout/core/input_error.h"
#include "lookout/io/replay_log.h"

namespace {

void CheckInvariants(const lookout::io::ReplayLog& log) {
  if (log.lidar.empty()) std::abort();  // refused otherwise
  for (std::size_t i = 0; i < log.lidar.size(); ++i) {
    const lookout::LidarScan& s = log.lidar[i];
    if (i > 0 && s.stamp <= log.lidar[i - 1].stamp) std::abort();
    if (!std::isfinite(s.angle_increment_rad) || s.angle_increment_rad == 0.0 ||
        !std::isfinite(s.mount.x()) || !std::isfinite(s.mount.yaw) || s.ranges_m.empty()) {
      std::abort();
    }
    for (const float r : s.ranges_m) {
      if (r < 0.0f) std::abort();  // NaN, +inf or a reading (REP 117)
    }
  }
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    if (log.odometry[i].stamp < log.odometry[i - 1].stamp) std::abort();
  }
  for (std::size_t i = 1; i < log.stereo.size(); ++i) {
    if (log.stereo[i].stamp < log.stereo[i - 1].stamp) std::abort();
  }
  for (const lookout::io::PeopleFrame& f : log.people) {
    if (f.scan_index >= log.lidar.size() || f.stamp != log.lidar[f.scan_index].stamp) std::abort();
  }
  if (!std::isfinite(log.duration_s) || log.duration_s < 0.0) std::abort();
  if (log.warnings.size() > lookout::io::kMaxReplayWarnings + 1) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    CheckInvariants(lookout::io::ReplayLogFromBytes(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz.log"));
  } catch (const lookout::InputError&) {
    // The one way a log may be refused.
  }
  return 0;
}
