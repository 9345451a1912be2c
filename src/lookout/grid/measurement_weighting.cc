#include "lookout/grid/measurement_weighting.h"

namespace lookout::grid {

void WeightByMeasurement(const MeasurementGrid& z, Associations& a) {
  ParallelForBlocks(a.SourceCount(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      const std::size_t first = a.first_entry[s];
      const std::size_t last = a.first_entry[s + 1];
      double sum = 0.0;
      for (std::size_t e = first; e < last; ++e) {
        const float m = a.target[e] == kOutsideWindow
                            ? kUnknownProbability
                            : z.p_occupied[static_cast<std::size_t>(a.target[e])];
        a.weight[e] *= m / (1.0f - m);
        sum += static_cast<double>(a.weight[e]);
      }
      if (sum <= 0.0) continue;  // cannot happen with measurements inside (0, 1)
      const double inv_sum = 1.0 / sum;
      for (std::size_t e = first; e < last; ++e) {
        a.weight[e] = static_cast<float>(static_cast<double>(a.weight[e]) * inv_sum);
      }
    }
  });
}

}  // namespace lookout::grid
