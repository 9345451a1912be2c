#pragma once

// Risk management (seed 004 section VIII.E): each instant's assessment becomes a warning level,
// none < information < warning, with hysteresis, so that a risk hovering at a threshold does
// not make the display flicker. Each change of level is an event naming the object and its TTC.
//
// The rule, per object (LevelsOf):
//   - information: its risk indicator (the TTC of its potential collision against the reaction
//     time, risk_assessment.h) reaches information_enter: a collision predicted inside the
//     horizon;
//   - warning: its risk reaches warning_enter (a TTC of 3.2 s or less by default) **and** its
//     collision probability reaches warning_probability_enter (0.5: more likely than not),
//     when probabilities were sampled. The TTC says when, from the most likely futures; the
//     probability says how likely, from the tracks' uncertainty and the walkers' freedom: a
//     track whose velocity is barely known, or a walker whose likeliest path only grazes the
//     ego's, warns no one.
// The level of an instant is the highest any object enters. Once raised, a level holds while
// some object still meets it under the exit thresholds (information_exit; warning_exit and
// warning_probability_exit), and falls only after `hold_s` without one, to the level still held.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/time.h"
#include "lookout/risk/risk_assessment.h"

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
  // ... and a collision at least this probable (ignored when no probability was sampled).
  double warning_probability_enter = 0.5;
  double warning_probability_exit = 0.3;
  double hold_s = 0.5;

  // Throws lookout::InputError naming the first field out of range (exits above enters).
  void Validate(const std::string& source = "warning options") const;
};

// What one instant's assessment says to the warning levels.
struct LevelInput {
  WarningLevel entered = WarningLevel::kNone;  // the highest level an object enters
  WarningLevel held = WarningLevel::kNone;     // the highest level an object holds (exits)
  // The object of the event a rise would make: the earliest potential collision among the
  // objects at the entered level (or overall, when none enters a level).
  std::optional<std::uint32_t> object_id;
  std::optional<double> ttc_s;
};

// The rule above, applied to every object of `assessment`. Pure.
LevelInput LevelsOf(const RiskAssessment& assessment, const WarningOptions& options);

struct WarningEvent {
  TimeNs stamp = 0;
  WarningLevel level = WarningLevel::kNone;
  std::optional<std::uint32_t> object_id;  // the object of the earliest potential collision
  std::optional<double> ttc_s;
};

class WarningState {
 public:
  explicit WarningState(const WarningOptions& options = {});

  // The instant at `stamp` (stamps increasing; an older stamp is ignored and returns nullopt).
  // Returns the event when the level changes.
  std::optional<WarningEvent> Update(TimeNs stamp, const LevelInput& input);
  std::optional<WarningEvent> Update(TimeNs stamp, const RiskAssessment& assessment) {
    return Update(stamp, LevelsOf(assessment, options_));
  }

  WarningLevel level() const { return level_; }
  const std::vector<WarningEvent>& events() const { return events_; }
  const WarningOptions& options() const { return options_; }

 private:
  WarningOptions options_;
  WarningLevel level_ = WarningLevel::kNone;
  std::optional<TimeNs> last_stamp_;
  std::optional<TimeNs> below_since_;  // since when no object holds the current level
  std::vector<WarningEvent> events_;
};

}  // namespace lookout::risk
