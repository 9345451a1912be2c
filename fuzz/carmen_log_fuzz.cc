// Fuzz target for the CARMEN log parser: any text in. Read leniently, a log comes out (bad lines
// skipped and counted) and nothing may be thrown; read strictly, a log or an InputError. Any
// other exception, a crash, a hang or a sanitizer report is a bug in the parser.
//
// The first byte chooses the mode, so one corpus drives both. Seeds in corpus/carmen/: small
// logs written for this purpose (a corrected log with anchors, the three laser lines, PARAMs,
// broken lines).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lookout/core/input_error.h"
#include "lookout/io/carmen_log.h"

namespace {

// What every log must satisfy, whatever its text.
void CheckInvariants(const lookout::io::CarmenLog& log) {
  if (log.warnings.size() > log.skipped_lines) std::abort();
  for (const lookout::io::CarmenRecord& record : log.records) {
    if (!std::isfinite(record.t_s) || !std::isfinite(record.odometry.x()) ||
        !std::isfinite(record.odometry.y()) || !std::isfinite(record.odometry.yaw)) {
      std::abort();
    }
    if (record.scan) {
      for (const float range : record.scan->ranges_m) {
        if (range <= 0.0f) std::abort();  // NaN, +inf or a positive reading (REP 117)
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  lookout::io::CarmenReadOptions options;
  options.strict = (data[0] & 1u) != 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (!options.strict) {
    CheckInvariants(lookout::io::ParseCarmenLog(text, "fuzz.log", options));
    return 0;
  }
  try {
    CheckInvariants(lookout::io::ParseCarmenLog(text, "fuzz.log", options));
  } catch (const lookout::InputError&) {
    // The one way a strict read may refuse a file.
  }
  return 0;
}
