#include "lookout/grid/occupancy_update.h"

#include <algorithm>

namespace lookout::grid {

void UpdateOccupancy(const Associations& a, const TargetIndex& targets,
                     const std::vector<UpdateCell>& cells, const MeasurementGrid& z,
                     const FilterOptions& options, std::span<float> occupancy,
                     std::span<float> seen) {
  const double gamma = options.renewal_rate;
  const double lo = options.occupancy_clamp;
  const double hi = 1.0 - options.occupancy_clamp;
  ParallelForBlocks(cells.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t u = begin; u < end; ++u) {
      const UpdateCell& c = cells[u];
      double carried_mass = 0.0;
      double cover = 0.0;
      if (c.target_slot != FilterWorkspace::kNone) {
        for (std::size_t n = targets.first[c.target_slot]; n < targets.first[c.target_slot + 1];
             ++n) {
          const std::uint32_t e = targets.entries[n];
          const double p = static_cast<double>(a.weight[e]);
          carried_mass += p * static_cast<double>(a.occupancy[a.entry_source[e]]);
          cover += p;
        }
      }
      double prior = 0.0;
      double seen_mass = std::min(1.0, carried_mass);
      if (c.source == FilterWorkspace::kNone) {
        // The cell's own content stays: P(S=1) = 1.
        const double own = static_cast<double>(occupancy[c.cell]);
        prior = std::max(seen_mass, own);
        if (own > seen_mass) seen_mass = own * static_cast<double>(seen[c.cell]);
      } else {
        // Its content left: P(S=1) = cover, Pseen = carried / cover, Punseen = gamma / 2.
        prior = std::min(1.0, carried_mass) + std::max(0.0, 1.0 - cover) * 0.5 * gamma;
      }
      const double m = static_cast<double>(z.p_occupied[c.cell]);
      const double posterior = prior * m / (prior * m + (1.0 - prior) * (1.0 - m));
      occupancy[c.cell] = static_cast<float>(std::clamp(posterior, lo, hi));
      seen[c.cell] = static_cast<float>(
          prior > 0.0 ? std::clamp(seen_mass / prior, 0.0, 1.0) : 0.0);
    }
  });
}

}  // namespace lookout::grid
