#pragma once

#include <string>
#include <string_view>

#include "lookout/sim/scenario.h"

namespace lookout::io {

// Loads a scenario written to docs/scenario-format.md, version 1, applies every default, and
// checks it. Anything the format does not allow throws lookout::InputError naming the file,
// the 1-based line and the field path (e.g. "actors[2].speed_profile[1]"): unknown keys, wrong
// types, missing required fields, format != 1, duration <= 0, fewer than 2 waypoints, unknown
// class or obstacle kind, duplicate ids, NaN or infinite numbers, profile times out of order.
sim::Scenario LoadScenarioFile(const std::string& path);

// Same, from text; `source` names it in messages.
sim::Scenario LoadScenarioText(std::string_view yaml, const std::string& source);

// The built-in default scenario (io/default_scenario.h), loaded.
sim::Scenario LoadDefaultScenario();

}  // namespace lookout::io
