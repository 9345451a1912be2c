#include "lookout/grid/velocity_update.h"

#include <algorithm>

namespace lookout::grid {

void UpdateVelocity(const Associations& a, const TargetIndex& targets,
                    const std::vector<UpdateCell>& cells, double dt_s, double cell_size_m,
                    const FilterOptions& options, std::span<const float> occupancy,
                    std::span<const float> seen,
                    const VelocityLayers& out) {
  const double alpha = options.velocity_blend;
  const double cells_to_mps = cell_size_m / dt_s;
  // Below this carried weight the cell received nothing worth an estimate.
  constexpr double kMinWeight = 1e-6;
  // Per source: the mean and variance of where its mass went (its displacement posterior).
  const std::size_t sources = a.SourceCount();
  std::vector<double> source_mean_x(sources), source_mean_y(sources), variance(sources);
  ParallelForBlocks(sources, 256, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      double w_sum = 0.0, sx = 0.0, sy = 0.0, s2 = 0.0;
      const std::size_t first = a.first_entry[s];
      a.window[s].ForEachDisplacement([&](std::size_t k, const CellIndex& d) {
        const std::size_t e = first + k;
        // Where the mass survived: a move into a cell now believed free destroyed it.
        const double w = a.target[e] == kOutsideWindow
                             ? 0.0
                             : static_cast<double>(a.weight[e]) *
                                   static_cast<double>(occupancy[static_cast<std::size_t>(a.target[e])]);
        w_sum += w;
        sx += w * d.ix;
        sy += w * d.iy;
        s2 += w * (d.ix * d.ix + d.iy * d.iy);
      });
      if (w_sum <= 0.0) continue;
      source_mean_x[s] = sx / w_sum;
      source_mean_y[s] = sy / w_sum;
      variance[s] = std::max(0.0, s2 / w_sum - source_mean_x[s] * source_mean_x[s] -
                                     source_mean_y[s] * source_mean_y[s]);
    }
  });
  ParallelForBlocks(cells.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t u = begin; u < end; ++u) {
      const UpdateCell& c = cells[u];
      double sum = 0.0, dx = 0.0, dy = 0.0, d2 = 0.0, vx = 0.0, vy = 0.0, conf = 0.0;
      if (c.target_slot != FilterWorkspace::kNone) {
        sum = GatherWeighted(a, targets, c.target_slot,
                             [&](std::uint32_t /*e*/, std::uint32_t s, double w) {
                               dx += w * source_mean_x[s];
                               dy += w * source_mean_y[s];
                               d2 += w * (variance[s] + source_mean_x[s] * source_mean_x[s] +
                                          source_mean_y[s] * source_mean_y[s]);
                               vx += w * static_cast<double>(a.velocity_x_mps[s]);
                               vy += w * static_cast<double>(a.velocity_y_mps[s]);
                               conf += w * static_cast<double>(a.confidence[s]);
                             });
      }
      if (sum < kMinWeight) {
        if (c.source != FilterWorkspace::kNone) {
          out.velocity_x_mps[c.cell] = 0.0f;
          out.velocity_y_mps[c.cell] = 0.0f;
          out.confidence[c.cell] = 0.0f;
        }
        continue;
      }
      const double mean_x = dx / sum, mean_y = dy / sum;
      const double spread = std::max(0.0, d2 / sum - mean_x * mean_x - mean_y * mean_y);
      const double c_prev = conf / sum;
      const double b = 1.0 - (1.0 - alpha) * c_prev;
      const double new_vx = (1.0 - b) * vx / sum + b * mean_x * cells_to_mps;
      const double new_vy = (1.0 - b) * vy / sum + b * mean_y * cells_to_mps;
      const double c_obs = 1.0 / (1.0 + spread / options.confidence_spread_cells2);
      const double new_conf =
          static_cast<double>(seen[c.cell]) * ((1.0 - alpha) * c_prev + alpha * c_obs);
      out.velocity_x_mps[c.cell] = static_cast<float>(new_vx);
      out.velocity_y_mps[c.cell] = static_cast<float>(new_vy);
      out.confidence[c.cell] = static_cast<float>(new_conf);
    }
  });
}

}  // namespace lookout::grid
