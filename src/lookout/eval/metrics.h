#pragma once

// Metric values of one scenario, by the keys of docs/cli-contract.md, and their summary over
// a catalogue. Ordered maps, so reports list keys in one fixed order.

#include <map>
#include <string>
#include <vector>

namespace lookout::eval {

struct ScenarioMetrics {
  std::string scenario;
  std::map<std::string, double> values;
};

struct KeySummary {
  int count = 0;  // scenarios that report the key
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// Per key: how many scenarios report it, and the mean, min and max over them. Non-finite
// values are not counted.
std::map<std::string, KeySummary> Summarise(const std::vector<ScenarioMetrics>& scenarios);

}  // namespace lookout::eval
