#pragma once

// The stages' step timings (`*_ms_median` of the metrics and `lookout bench`) are wall-clock
// milliseconds on the steady clock: one definition for every stage that times itself.

#include <chrono>

namespace lookout::app {

using WallClock = std::chrono::steady_clock;

inline double MsSince(WallClock::time_point start) {
  return std::chrono::duration<double, std::milli>(WallClock::now() - start).count();
}

}  // namespace lookout::app
