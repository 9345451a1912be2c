#pragma once

// Risk management (seed 004 section VIII.E): the risk indicator of each instant becomes a
// warning level, none < information < warning, with hysteresis, so that a risk hovering at a
// threshold does not make the display flicker: a level is entered when the risk reaches its
// `enter` threshold, and left only when the risk has stayed below its `exit` threshold for
// `hold_s`. Each change of level is an event naming the object and its TTC.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/time.h"

namespace lookout::risk {

enum class WarningLevel { kNone = 0, kInformation = 1, kWarning = 2 };
const char* ToString(WarningLevel level);

struct WarningOptions {
  // Information: any collision predicted inside the horizon worth showing.
  double information_enter = 0.05;
  double information_exit = 0.02;
  // Warning: by default a TTC of 3.2 s or less (risk 0.6 with the 2 s reaction time and the 5 s
  // horizon): 1.2 s of margin over the reaction time for the prediction's own latency.
  double warning_enter = 0.6;
  double warning_exit = 0.4;
  double hold_s = 0.5;

  // Throws lookout::InputError naming the first field out of range (exits above enters).
  void Validate(const std::string& source = "warning options") const;
};

struct WarningEvent {
  TimeNs stamp = 0;
  WarningLevel level = WarningLevel::kNone;
  std::optional<std::uint32_t> object_id;  // the object of the earliest potential collision
  std::optional<double> ttc_s;
};

class WarningState {
 public:
  explicit WarningState(const WarningOptions& options = {});

  // The risk at `stamp` (stamps increasing; an older stamp is ignored and returns nullopt),
  // with the object and TTC it comes from. Returns the event when the level changes.
  std::optional<WarningEvent> Update(TimeNs stamp, double risk,
                                     std::optional<std::uint32_t> object_id,
                                     std::optional<double> ttc_s);

  WarningLevel level() const { return level_; }
  const std::vector<WarningEvent>& events() const { return events_; }

 private:
  WarningOptions options_;
  WarningLevel level_ = WarningLevel::kNone;
  std::optional<TimeNs> last_stamp_;
  std::optional<TimeNs> below_since_;  // when the risk fell below the current level's exit
  std::vector<WarningEvent> events_;
};

}  // namespace lookout::risk
