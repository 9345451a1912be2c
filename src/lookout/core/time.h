#pragma once

#include <cmath>
#include <cstdint>

namespace lookout {

// Every timestamp in Lookout is an integer count of nanoseconds. Integers keep sensor
// schedules exact (12.5 Hz is exactly 80 ms) and make recordings byte-identical; MCAP log
// times are nanoseconds too. Scenario time starts at 0.
using TimeNs = std::int64_t;

inline constexpr TimeNs kNanosPerSecond = 1'000'000'000;

// Division, not multiplication by 1e-9: it is correctly rounded, so a stamp that is exactly a
// frame time gives exactly that frame time in seconds.
inline double ToSeconds(TimeNs t) { return static_cast<double>(t) / 1e9; }

inline TimeNs FromSeconds(double seconds) {
  return static_cast<TimeNs>(std::llround(seconds * 1e9));
}

}  // namespace lookout
