#include "lookout/risk/warning_levels.h"

#include <algorithm>
#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

// The level one object reaches under the enter thresholds (`holding` false) or the exit ones.
WarningLevel ObjectLevel(const ObjectRisk& o, bool sampled, const WarningOptions& w,
                         bool holding) {
  const double warning = holding ? w.warning_exit : w.warning_enter;
  const double probability = holding ? w.warning_probability_exit : w.warning_probability_enter;
  const double information = holding ? w.information_exit : w.information_enter;
  if (o.risk >= warning && (!sampled || o.collision_probability >= probability)) {
    return WarningLevel::kWarning;
  }
  return o.risk >= information && o.risk > 0.0 ? WarningLevel::kInformation : WarningLevel::kNone;
}

}  // namespace

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
  require(in_unit(warning_probability_enter), "warning_probability_enter", "must be in [0, 1]");
  require(in_unit(warning_probability_exit) &&
              warning_probability_exit <= warning_probability_enter,
          "warning_probability_exit", "must be in [0, warning_probability_enter]");
  require(std::isfinite(hold_s) && hold_s >= 0.0, "hold_s", "must be finite and >= 0");
}

LevelInput LevelsOf(const RiskAssessment& a, const WarningOptions& options) {
  LevelInput in;
  std::optional<std::size_t> named;
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const ObjectRisk& o = a.objects[i];
    const WarningLevel entered = ObjectLevel(o, a.sampled, options, false);
    in.held = std::max(in.held, ObjectLevel(o, a.sampled, options, true));
    const bool earlier = !named || (o.ttc_s && (!a.objects[*named].ttc_s ||
                                                *o.ttc_s < *a.objects[*named].ttc_s));
    if (entered > in.entered ||
        (entered == in.entered && entered != WarningLevel::kNone && earlier)) {
      in.entered = entered;
      named = i;
    }
  }
  if (in.entered == WarningLevel::kNone) named = a.earliest;
  if (named) {
    in.object_id = a.objects[*named].id;
    in.ttc_s = a.objects[*named].ttc_s;
  }
  return in;
}

WarningState::WarningState(const WarningOptions& options) : options_(options) {
  options_.Validate();
}

std::optional<WarningEvent> WarningState::Update(TimeNs stamp, const LevelInput& in) {
  if (last_stamp_ && stamp <= *last_stamp_) return std::nullopt;
  last_stamp_ = stamp;

  WarningLevel next = level_;
  if (in.entered > level_) {
    next = in.entered;  // up at once
    below_since_.reset();
  } else if (level_ != WarningLevel::kNone) {
    // Down only after hold_s without an object that holds the current level, and then to the
    // level still held.
    if (std::max(in.held, in.entered) < level_) {
      if (!below_since_) below_since_ = stamp;
      if (ToSeconds(stamp - *below_since_) >= options_.hold_s) {
        next = std::max(in.held, in.entered);
        below_since_.reset();
      }
    } else {
      below_since_.reset();
    }
  }
  if (next == level_) return std::nullopt;
  level_ = next;
  WarningEvent e{stamp, next, in.object_id, in.ttc_s};
  events_.push_back(e);
  return e;
}

}  // namespace lookout::risk
