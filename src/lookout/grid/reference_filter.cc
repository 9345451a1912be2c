#include "lookout/grid/reference_filter.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "lookout/grid/association_prediction.h"
#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/velocity_update.h"

namespace lookout::grid {
namespace {

struct Move {
  CellIndex displacement;
  long target = -1;  // storage index, -1 outside the window
  double p = 0.0;
  double stay_share = 0.0;  // the share of p that "stays in place" holds
};

struct Source {
  std::size_t cell = 0;
  CellIndex local;
  double occupancy = 0.0;
  double vx = 0.0, vy = 0.0, confidence = 0.0;
  std::vector<Move> moves;
};

double Gaussian(double dx, double dy, double sigma) {
  return std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
}

}  // namespace

void ReferenceUpdate(GridLayers& layers, const FilterLayerIds& ids, const MeasurementGrid& z,
                     double dt_s, const FilterOptions& options, const ScanFlow* flow) {
  const ScrollingGridGeometry& geometry = layers.geometry();
  const std::size_t n = geometry.CellCount();
  const double cell_m = geometry.cell_size_m();
  auto occupancy = layers.Values(ids.occupancy);
  auto seen = layers.Values(ids.seen);
  auto vx = layers.Values(ids.velocity_x_mps);
  auto vy = layers.Values(ids.velocity_y_mps);
  auto confidence = layers.Values(ids.velocity_confidence);

  // The windows first (a design choice shared with the fast path, not an equation): the scan
  // pair's measurement of a cell depends on the cells around it (ScanFlow::MeasureCells).
  std::vector<CellIndex> window_locals;
  std::vector<float> window_vx, window_vy, window_seen, window_confidence, window_pmf;
  for (int ly = 0; ly < geometry.height(); ++ly) {
    for (int lx = 0; lx < geometry.width(); ++lx) {
      const std::size_t cell = geometry.StorageIndexOfLocal({lx, ly});
      if (!IsSource(static_cast<double>(occupancy[cell]), static_cast<double>(seen[cell]),
                    options)) {
        continue;
      }
      window_locals.push_back({lx, ly});
      const bool observed = Observed(z.p_occupied[cell]);
      window_vx.push_back(static_cast<float>(
          PredictVelocity(static_cast<double>(vx[cell]), dt_s, observed, options)));
      window_vy.push_back(static_cast<float>(
          PredictVelocity(static_cast<double>(vy[cell]), dt_s, observed, options)));
      window_seen.push_back(seen[cell]);
      window_confidence.push_back(confidence[cell]);
      for (std::size_t c = 0; c < kGridClassCount; ++c) {
        window_pmf.push_back(layers.Values(ids.class_pmf[c])[cell]);
      }
    }
  }
  const std::vector<SearchWindow> windows =
      SourceWindows(window_locals, window_vx, window_vy, window_seen, window_confidence, window_pmf,
                    dt_s, cell_m, options, flow);

  // --- eq. 8-9: Psi over each active cell's window.
  std::vector<Source> sources;
  std::vector<long> source_of(n, -1);
  // The sources in the windows' order (row-major over the window).
  for (std::size_t k = 0; k < window_locals.size(); ++k) {
    const int lx = window_locals[k].ix, ly = window_locals[k].iy;
    const std::size_t cell = geometry.StorageIndexOfLocal(window_locals[k]);
    Source s;
    s.cell = cell;
    s.local = window_locals[k];
    s.occupancy = static_cast<double>(occupancy[cell]);
    // As the fast path: the velocity predicted in float, the layers' type.
    s.vx = static_cast<double>(window_vx[k]);
    s.vy = static_cast<double>(window_vy[k]);
    s.confidence = static_cast<double>(confidence[cell]);
    const SearchWindow& w = windows[k];
    // The window's samples: the lattice, then the dense core's displacements off it.
    std::vector<CellIndex> displacements;
    for (int v = 0; v < w.size(); ++v) {
      for (int u = 0; u < w.size(); ++u) {
        displacements.push_back(
            {w.center.ix + w.stride * (u - w.half), w.center.iy + w.stride * (v - w.half)});
      }
    }
    if (w.stride > 1) {
      for (int y = -w.dense_half; y <= w.dense_half; ++y) {
        for (int x = -w.dense_half; x <= w.dense_half; ++x) {
          if (x % w.stride != 0 || y % w.stride != 0) {
            displacements.push_back({w.center.ix + x, w.center.iy + y});
          }
        }
      }
    }
    double g_sum = 0.0, stay_sum = 0.0;
    for (const CellIndex& d : displacements) {
      Move m;
      m.displacement = d;
      const CellIndex t{lx + m.displacement.ix, ly + m.displacement.iy};
      if (t.ix >= 0 && t.iy >= 0 && t.ix < geometry.width() && t.iy < geometry.height()) {
        m.target = static_cast<long>(geometry.StorageIndexOfLocal(t));
      }
      const double ex = m.displacement.ix - w.mean_x_cells;
      const double ey = m.displacement.iy - w.mean_y_cells;
      g_sum += Gaussian(ex, ey, w.sigma_cells);
      stay_sum += Gaussian(ex, ey, w.stay_sigma_cells);
      s.moves.push_back(m);
    }
    // The stay component is the static hypothesis only where the prediction is no motion.
    const bool static_prediction =
        std::hypot(w.mean_x_cells, w.mean_y_cells) < 0.5 && w.stay_weight > 0.0;
    for (Move& m : s.moves) {
      const double ex = m.displacement.ix - w.mean_x_cells;
      const double ey = m.displacement.iy - w.mean_y_cells;
      const double move = (1.0 - w.stay_weight) * Gaussian(ex, ey, w.sigma_cells) / g_sum;
      const double stay = w.stay_weight * Gaussian(ex, ey, w.stay_sigma_cells) / stay_sum;
      m.p = move + stay;
      m.stay_share = static_prediction && m.p > 0.0 ? stay / m.p : 0.0;
    }
    source_of[cell] = static_cast<long>(sources.size());
    sources.push_back(std::move(s));
  }

  // --- eq. 10: Pw = Psi P(M(i) = 1 | z), renormalised.
  for (Source& s : sources) {
    double sum = 0.0;
    for (Move& m : s.moves) {
      const double p_occ =
          m.target < 0 ? 0.5
                       : static_cast<double>(z.p_occupied[static_cast<std::size_t>(m.target)]);
      m.p *= p_occ / (1.0 - p_occ);
      sum += m.p;
    }
    for (Move& m : s.moves) m.p /= sum;
  }

  // --- eq. 11, literal: no convergence from the scattered inflow; rigidity over every move of
  // every linked neighbour.
  std::vector<double> inflow(n, 0.0);
  for (const Source& s : sources) {
    for (const Move& m : s.moves) {
      if (m.target >= 0) inflow[static_cast<std::size_t>(m.target)] += m.p * s.occupancy;
    }
  }
  const double r = options.rigidity_sigma_cells;
  std::vector<std::vector<double>> constrained(sources.size());
  for (std::size_t j = 0; j < sources.size(); ++j) {
    const Source& s = sources[j];
    std::vector<double>& out = constrained[j];
    out.resize(s.moves.size());
    double sum = 0.0;
    for (std::size_t k = 0; k < s.moves.size(); ++k) {
      const Move& m = s.moves[k];
      double p = m.p;
      if (options.enable_no_convergence_constraint && m.target >= 0) {
        const double others = inflow[static_cast<std::size_t>(m.target)] - m.p * s.occupancy;
        const double excess = std::max(0.0, others + s.occupancy - 1.0);
        p *= std::exp(-excess * excess /
                      (2.0 * options.no_convergence_sigma * options.no_convergence_sigma));
      }
      if (options.enable_rigidity_constraint) {
        for (std::size_t d = 0; d < kNeighbourCount; ++d) {
          const double link =
              std::min(1.0, options.rigidity_link_gain *
                                static_cast<double>(layers.Values(ids.rigidity[d])[s.cell]));
          if (link <= 0.0) continue;
          const CellIndex nl{s.local.ix + kNeighbourOffsets[d].ix,
                             s.local.iy + kNeighbourOffsets[d].iy};
          if (nl.ix < 0 || nl.iy < 0 || nl.ix >= geometry.width() || nl.iy >= geometry.height()) {
            continue;
          }
          const long y = source_of[geometry.StorageIndexOfLocal(nl)];
          if (y < 0) continue;
          double agree = 0.0;
          for (const Move& other : sources[static_cast<std::size_t>(y)].moves) {
            agree += other.p * Gaussian(m.displacement.ix - other.displacement.ix,
                                        m.displacement.iy - other.displacement.iy, r);
          }
          p *= (1.0 - link) + link * agree;
        }
      }
      out[k] = p;
      sum += p;
    }
    for (double& p : out) p /= sum;
  }
  for (std::size_t j = 0; j < sources.size(); ++j) {
    for (std::size_t k = 0; k < sources[j].moves.size(); ++k) {
      sources[j].moves[k].p = constrained[j][k];
    }
  }

  // --- eq. 15, literal: D(x, y) = sum_a P(x moves by a) P(y moves by a), at the sources.
  std::vector<double> links(sources.size() * kNeighbourCount, 0.0);
  for (std::size_t x = 0; x < sources.size(); ++x) {
    for (std::size_t d = 0; d < kNeighbourCount; ++d) {
      const CellIndex nl{sources[x].local.ix + kNeighbourOffsets[d].ix,
                         sources[x].local.iy + kNeighbourOffsets[d].iy};
      if (nl.ix < 0 || nl.iy < 0 || nl.ix >= geometry.width() || nl.iy >= geometry.height()) {
        continue;
      }
      const long y = source_of[geometry.StorageIndexOfLocal(nl)];
      if (y < 0) continue;
      double sum = 0.0;
      for (const Move& a : sources[x].moves) {
        for (const Move& b : sources[static_cast<std::size_t>(y)].moves) {
          if (a.displacement == b.displacement) sum += a.p * b.p;
        }
      }
      links[x * kNeighbourCount + d] = sum;
    }
  }

  // --- scatter of eq. 13 (occupancy, coverage) and of the carried attributes (eq. 14, links).
  std::vector<double> carried(n, 0.0), cover(n, 0.0), w_sum(n, 0.0), dx(n, 0.0), dy(n, 0.0),
      d2(n, 0.0), cvx(n, 0.0), cvy(n, 0.0), cconf(n, 0.0);
  std::vector<double> clinks(n * kNeighbourCount, 0.0);
  for (std::size_t j = 0; j < sources.size(); ++j) {
    const Source& s = sources[j];
    for (const Move& m : s.moves) {
      if (m.target < 0) continue;
      const auto i = static_cast<std::size_t>(m.target);
      const double w = m.p * s.occupancy;
      carried[i] += w;
      cover[i] += m.p;
      w_sum[i] += w;
      cvx[i] += w * s.vx;
      cvy[i] += w * s.vy;
      cconf[i] += w * s.confidence;
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        clinks[i * kNeighbourCount + d] += w * links[j * kNeighbourCount + d];
      }
    }
  }

  // --- eq. 12-13 and 14 per cell.
  const double gamma = options.renewal_rate;
  const double alpha = options.velocity_blend;
  std::vector<char> updated(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool is_source = source_of[i] >= 0;
    const double m = static_cast<double>(z.p_occupied[i]);
    if (!is_source && cover[i] == 0.0 && m == 0.5) continue;  // nothing moves, nothing seen
    updated[i] = 1;
    const double prior =
        is_source ? std::min(1.0, carried[i]) + std::max(0.0, 1.0 - cover[i]) * 0.5 * gamma
                  : std::max(std::min(1.0, carried[i]), static_cast<double>(occupancy[i]));
    const double posterior = prior * m / (prior * m + (1.0 - prior) * (1.0 - m));
    double seen_mass = std::min(1.0, carried[i]);
    if (!is_source && static_cast<double>(occupancy[i]) > seen_mass) {
      seen_mass = static_cast<double>(occupancy[i]) * static_cast<double>(seen[i]);
    }
    occupancy[i] = static_cast<float>(
        std::clamp(posterior, options.occupancy_clamp, 1.0 - options.occupancy_clamp));
    const double seen_i = std::clamp(seen_mass / prior, 0.0, 1.0);
    seen[i] = static_cast<float>(seen_i);
  }

  // --- eq. 14 as built: each source's displacement posterior, weighted by whether its mass
  // survived where it went (the target's posterior occupancy), then gathered per target.
  std::vector<double> source_mx(sources.size(), 0.0), source_my(sources.size(), 0.0),
      source_var(sources.size(), 0.0);
  for (std::size_t j = 0; j < sources.size(); ++j) {
    double ws = 0.0, sx = 0.0, sy = 0.0, s2 = 0.0;
    for (const Move& m : sources[j].moves) {
      if (m.target < 0) continue;
      const auto t = static_cast<std::size_t>(m.target);
      const double w = m.p * SurvivalWeight(static_cast<double>(occupancy[t]),
                                            static_cast<double>(z.p_occupied[t]), options);
      ws += w;
      sx += w * m.displacement.ix;
      sy += w * m.displacement.iy;
      s2 += w * (m.displacement.ix * m.displacement.ix + m.displacement.iy * m.displacement.iy);
    }
    if (ws <= 0.0) continue;
    source_mx[j] = sx / ws;
    source_my[j] = sy / ws;
    source_var[j] =
        std::max(0.0, s2 / ws - source_mx[j] * source_mx[j] - source_my[j] * source_my[j]);
  }
  std::vector<double> stayed(n, 0.0);
  for (std::size_t j = 0; j < sources.size(); ++j) {
    for (const Move& m : sources[j].moves) {
      if (m.target < 0) continue;
      const auto i = static_cast<std::size_t>(m.target);
      const double w = m.p * sources[j].occupancy;
      stayed[i] += w * m.stay_share;
      dx[i] += w * source_mx[j];
      dy[i] += w * source_my[j];
      d2[i] += w * (source_var[j] + source_mx[j] * source_mx[j] + source_my[j] * source_my[j]);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!updated[i]) continue;
    const bool is_source = source_of[i] >= 0;
    const double ws = w_sum[i];
    if (ws > 0.0) {
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        layers.Values(ids.rigidity[d])[i] =
            static_cast<float>(clinks[i * kNeighbourCount + d] / ws);
      }
    } else if (is_source) {
      for (std::size_t d = 0; d < kNeighbourCount; ++d) layers.Values(ids.rigidity[d])[i] = 0.0f;
    }
    if (ws < 1e-6) {
      if (is_source) vx[i] = vy[i] = confidence[i] = 0.0f;
      continue;
    }
    const double mx = dx[i] / ws, my = dy[i] / ws;
    const double spread = std::max(0.0, d2[i] / ws - mx * mx - my * my);
    const double c_prev = cconf[i] / ws;
    const double b = 1.0 - (1.0 - alpha) * c_prev;
    vx[i] = static_cast<float>((1.0 - b) * cvx[i] / ws + b * mx * cell_m / dt_s);
    vy[i] = static_cast<float>((1.0 - b) * cvy[i] / ws + b * my * cell_m / dt_s);
    double c_obs = 1.0 / (1.0 + spread / options.confidence_spread_cells2);
    if (options.moved_share_exponent > 0.0) {
      c_obs *= std::pow(std::clamp(1.0 - stayed[i] / ws, 0.0, 1.0), options.moved_share_exponent);
    }
    confidence[i] =
        static_cast<float>(static_cast<double>(seen[i]) * ((1.0 - alpha) * c_prev + alpha * c_obs));
  }
  // Beyond the paper and not an equation: shared with the fast path, like the windows.
  if (flow != nullptr) {
    ApplyClusterMotion(layers, ids, z, *flow, dt_s, options.known_confidence,
                       options.cluster_motion);
  }
}

}  // namespace lookout::grid
