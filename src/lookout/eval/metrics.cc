#include "lookout/eval/metrics.h"

#include <algorithm>
#include <cmath>

namespace lookout::eval {

std::map<std::string, KeySummary> Summarise(const std::vector<ScenarioMetrics>& scenarios) {
  std::map<std::string, KeySummary> summary;
  for (const ScenarioMetrics& s : scenarios) {
    for (const auto& [key, value] : s.values) {
      if (!std::isfinite(value)) continue;
      KeySummary& k = summary[key];
      if (k.count == 0) {
        k.min = value;
        k.max = value;
      }
      k.min = std::min(k.min, value);
      k.max = std::max(k.max, value);
      k.mean += (value - k.mean) / (k.count + 1);  // running mean
      ++k.count;
    }
  }
  return summary;
}

}  // namespace lookout::eval
