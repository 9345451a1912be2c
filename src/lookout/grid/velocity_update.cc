#include "lookout/grid/velocity_update.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace lookout::grid {

double SurvivalWeight(double o, double m, const FilterOptions& options) {
  if (!options.survival_needs_evidence) return o;
  return m < 0.5 ? 0.0 : std::max(0.0, 2.0 * o - 1.0);  // 0.5: unobserved, kept
}

void UpdateVelocity(const Associations& a, const TargetIndex& targets,
                    std::span<const UpdateCell> cells, double dt_s, double cell_size_m,
                    const FilterOptions& options, const MeasurementGrid& z,
                    std::span<const float> occupancy, std::span<const float> seen,
                    const VelocityLayers& out) {
  const double alpha = options.velocity_blend;
  const double cells_to_mps = cell_size_m / dt_s;
  // Below this carried weight the cell received nothing worth an estimate.
  constexpr double kMinWeight = 1e-6;
  const bool with_share = options.moved_share_exponent > 0.0;
  // Per source, one Eigen array: the mean (x, y) and second moment of where its mass went (its
  // displacement posterior), its carried velocity (x, y) and confidence. Why one array: the cells'
  // gathers read one record a contribution (six arrays before: six cache lines), and its six
  // products are three vector operations (element-wise: the same sums).
  using Motion = Eigen::Array<double, 6, 1>;
  enum : Eigen::Index { kMeanX, kMeanY, kSecondMoment, kVelocityX, kVelocityY, kConfidence };
  const std::size_t sources = a.SourceCount();
  std::vector<Motion> motion(sources, Motion::Zero());
  ParallelForBlocks(sources, kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      Motion& m = motion[s];
      m(kVelocityX) = static_cast<double>(a.velocity_x_mps[s]);
      m(kVelocityY) = static_cast<double>(a.velocity_y_mps[s]);
      m(kConfidence) = static_cast<double>(a.confidence[s]);
      double w_sum = 0.0, sx = 0.0, sy = 0.0, s2 = 0.0;
      const std::size_t first = a.first_entry[s];
      a.window[s].ForEachDisplacement([&](std::size_t k, const CellIndex& d) {
        const std::size_t e = first + k;
        const auto t = static_cast<std::size_t>(a.target[e]);  // read only inside the window
        // Where the mass survived: a move into a cell now believed free destroyed it.
        const double w = a.target[e] == kOutsideWindow
                             ? 0.0
                             : static_cast<double>(a.weight[e]) *
                                   SurvivalWeight(static_cast<double>(occupancy[t]),
                                                  static_cast<double>(z.p_occupied[t]), options);
        w_sum += w;
        sx += w * d.ix;
        sy += w * d.iy;
        s2 += w * (d.ix * d.ix + d.iy * d.iy);
      });
      if (w_sum <= 0.0) continue;
      const double mean_x = sx / w_sum;
      const double mean_y = sy / w_sum;
      const double variance = std::max(0.0, s2 / w_sum - mean_x * mean_x - mean_y * mean_y);
      m(kMeanX) = mean_x;
      m(kMeanY) = mean_y;
      m(kSecondMoment) = variance + mean_x * mean_x + mean_y * mean_y;
    }
  });
  ParallelForBlocks(cells.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t u = begin; u < end; ++u) {
      const UpdateCell& c = cells[u];
      Motion carried = Motion::Zero();
      double sum = 0.0;
      double stayed = 0.0;
      if (c.target_slot != FilterWorkspace::kNone) {
        sum = GatherWeighted(a, targets, c.target_slot,
                             [&](std::uint32_t e, std::uint32_t s, double w) {
                               if (with_share) stayed += w * static_cast<double>(a.stay_share[e]);
                               carried += w * motion[s];
                             });
      }
      const double dx = carried(kMeanX), dy = carried(kMeanY), d2 = carried(kSecondMoment);
      const double vx = carried(kVelocityX), vy = carried(kVelocityY);
      const double conf = carried(kConfidence);
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
      double c_obs = 1.0 / (1.0 + spread / options.confidence_spread_cells2);
      if (with_share) {
        // Occupancy explained by staying in place is no evidence of motion.
        const double moved = std::clamp(1.0 - stayed / sum, 0.0, 1.0);
        c_obs *= std::pow(moved, options.moved_share_exponent);
      }
      const double new_conf =
          static_cast<double>(seen[c.cell]) * ((1.0 - alpha) * c_prev + alpha * c_obs);
      out.velocity_x_mps[c.cell] = static_cast<float>(new_vx);
      out.velocity_y_mps[c.cell] = static_cast<float>(new_vy);
      out.confidence[c.cell] = static_cast<float>(new_conf);
    }
  });
}

}  // namespace lookout::grid
