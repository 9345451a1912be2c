#include "lookout/risk/warning_levels.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::risk {

const char* ToString(WarningLevel level) {
  switch (level) {
    case WarningLevel::kNone: return "none";
    case WarningLevel::kInformation: return "information";
    case WarningLevel::kWarning: return "warning";
  }
  return "none";
}

void WarningOptions::Validate(const std::string& source) const {
  auto require = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, field, problem);
  };
  auto in_unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  require(in_unit(information_enter), "information_enter", "must be in [0, 1]");
  require(in_unit(information_exit) && information_exit <= information_enter, "information_exit",
          "must be in [0, information_enter]");
  require(in_unit(warning_enter) && warning_enter >= information_enter, "warning_enter",
          "must be in [information_enter, 1]");
  require(in_unit(warning_exit) && warning_exit <= warning_enter, "warning_exit",
          "must be in [0, warning_enter]");
  require(std::isfinite(hold_s) && hold_s >= 0.0, "hold_s", "must be finite and >= 0");
}

WarningState::WarningState(const WarningOptions& options) : options_(options) {
  options_.Validate();
}

std::optional<WarningEvent> WarningState::Update(TimeNs stamp, double risk,
                                                 std::optional<std::uint32_t> object_id,
                                                 std::optional<double> ttc_s) {
  if (last_stamp_ && stamp <= *last_stamp_) return std::nullopt;
  last_stamp_ = stamp;
  if (!std::isfinite(risk)) risk = 0.0;

  // Up at once: the level the risk reaches.
  WarningLevel reached = WarningLevel::kNone;
  if (risk >= options_.warning_enter) {
    reached = WarningLevel::kWarning;
  } else if (risk >= options_.information_enter) {
    reached = WarningLevel::kInformation;
  }
  WarningLevel next = level_;
  if (reached > level_) {
    next = reached;
    below_since_.reset();
  } else if (level_ != WarningLevel::kNone) {
    // Down only after hold_s below the current level's exit threshold, and then to the level
    // the risk still holds.
    const double exit = level_ == WarningLevel::kWarning ? options_.warning_exit
                                                         : options_.information_exit;
    if (risk < exit) {
      if (!below_since_) below_since_ = stamp;
      if (ToSeconds(stamp - *below_since_) >= options_.hold_s) {
        next = risk >= options_.information_exit && level_ == WarningLevel::kWarning
                   ? WarningLevel::kInformation
                   : WarningLevel::kNone;
        below_since_.reset();
      }
    } else {
      below_since_.reset();
    }
  }
  if (next == level_) return std::nullopt;
  level_ = next;
  WarningEvent e{stamp, next, object_id, ttc_s};
  events_.push_back(e);
  return e;
}

}  // namespace lookout::risk
