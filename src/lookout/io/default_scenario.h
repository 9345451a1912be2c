#pragma once

#include <string_view>

namespace lookout::io {

// The YAML text of the built-in default scenario (scenarios/left-turn-across-path.yaml,
// compiled in), and the name it is reported under as a source.
std::string_view DefaultScenarioYaml();
inline constexpr std::string_view kDefaultScenarioSource = "<default:left-turn-across-path>";

}  // namespace lookout::io
