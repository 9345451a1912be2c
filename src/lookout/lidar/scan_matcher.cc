#include "lookout/lidar/scan_matcher.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace lookout::lidar {
namespace {

// PointLogLikelihood tabulated over [0, max distance]: the correlative search evaluates it
// hundreds of thousands of times per scan.
class LikelihoodTable {
 public:
  LikelihoodTable(double sigma_m, double max_distance_m, const MatcherOptions& options) {
    MatcherOptions o = options;
    o.sigma_m = sigma_m;
    inv_bin_ = static_cast<double>(kBins - 1) / max_distance_m;
    values_.resize(kBins + 1);
    for (int i = 0; i <= kBins; ++i) {
      values_[static_cast<std::size_t>(i)] =
          PointLogLikelihood(static_cast<double>(i) / inv_bin_, o);
    }
  }
  double operator()(float distance_m) const {
    const auto i = static_cast<std::size_t>(static_cast<double>(distance_m) * inv_bin_ + 0.5);
    return values_[std::min(i, static_cast<std::size_t>(kBins))];
  }

 private:
  static constexpr int kBins = 1024;
  double inv_bin_ = 1.0;
  std::vector<double> values_;
};

// The points rotated by `yaw` and moved to `origin`, as global cells.
void CellsAt(const LocalMap& map, std::span<const Eigen::Vector2d> points, double yaw,
             const Eigen::Vector2d& origin, std::vector<CellIndex>* cells) {
  const Eigen::Matrix2d r = Pose2(0.0, 0.0, yaw).Rotation();
  cells->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) (*cells)[i] = map.CellOf(r * points[i] + origin);
}

struct GridBest {
  double score = -std::numeric_limits<double>::infinity();
  double yaw = 0.0;
  int dx = 0;
  int dy = 0;
};

// Scores the poses yaw in yaws, cell offsets (dx, dy) = step * k for |k| <= half_steps:
// scale * summed log-likelihood + log prior.
GridBest SearchGrid(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                    const Eigen::Vector2d& origin, const std::vector<double>& yaws,
                    int half_steps, int step_cells, const LikelihoodTable& table, double scale,
                    const PosePrior& prior) {
  GridBest best;
  std::vector<CellIndex> cells;
  const double cell = map.options().cell_size_m;
  const double ixy = 1.0 / (prior.sigma_xy_m * prior.sigma_xy_m);
  const double iyaw = 1.0 / (prior.sigma_yaw_rad * prior.sigma_yaw_rad);
  for (double yaw : yaws) {
    CellsAt(map, points, yaw, origin, &cells);
    const double dyaw = WrapAngle(yaw - prior.mean.yaw);
    for (int ky = -half_steps; ky <= half_steps; ++ky) {
      for (int kx = -half_steps; kx <= half_steps; ++kx) {
        const int dx = kx * step_cells;
        const int dy = ky * step_cells;
        const Eigen::Vector2d offset =
            origin + cell * Eigen::Vector2d(dx, dy) - prior.mean.translation;
        double sum = 0.0;
        for (const CellIndex& c : cells) sum += table(map.FieldDistance({c.ix + dx, c.iy + dy}));
        const double score =
            scale * sum - 0.5 * (offset.squaredNorm() * ixy + dyaw * dyaw * iyaw);
        // Strictly better only: equal scores keep the earlier pose, a fixed order.
        if (score > best.score) best = {score, yaw, dx, dy};
      }
    }
  }
  return best;
}

std::vector<double> AnglesAround(double centre, double half_width, double step) {
  const int n = static_cast<int>(std::ceil(half_width / step));
  std::vector<double> yaws;
  yaws.reserve(static_cast<std::size_t>(2 * n + 1));
  // Centre first, so ties favour the prior.
  yaws.push_back(centre);
  for (int k = 1; k <= n; ++k) {
    yaws.push_back(centre + static_cast<double>(k) * step);
    yaws.push_back(centre - static_cast<double>(k) * step);
  }
  return yaws;
}

// The angles centre +- k step for first <= k <= last, the positive one of each pair first.
std::vector<double> AnglesInBand(double centre, int first, int last, double step) {
  std::vector<double> yaws;
  for (int k = first; k <= last; ++k) {
    yaws.push_back(centre + static_cast<double>(k) * step);
    yaws.push_back(centre - static_cast<double>(k) * step);
  }
  return yaws;
}

}  // namespace

ScanPoints ExtractScanPoints(const LidarScan& scan, const MatcherOptions& options) {
  ScanPoints out;
  out.all.reserve(scan.ranges_m.size());
  const double no_return = scan.NoReturnRangeM();
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = static_cast<double>(scan.ranges_m[i]);
    if (!std::isfinite(r) || r < options.min_range_m || r >= no_return) continue;
    const double a = scan.BeamAngle(i);
    out.all.push_back(scan.mount * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
  }
  // Subsample by spacing along the scan: dense returns near the sensor would otherwise
  // outweigh the far walls that pin the heading.
  std::vector<Eigen::Vector2d> spaced;
  for (const Eigen::Vector2d& p : out.all) {
    if (spaced.empty() || (p - spaced.back()).norm() >= options.point_spacing_m) {
      spaced.push_back(p);
    }
  }
  const auto max_points = static_cast<std::size_t>(options.max_points);
  if (spaced.size() <= max_points) {
    out.match = std::move(spaced);
  } else {
    out.match.reserve(max_points);
    for (std::size_t k = 0; k < max_points; ++k) {
      out.match.push_back(spaced[k * spaced.size() / max_points]);
    }
  }
  return out;
}

double PointLogLikelihood(double distance_m, const MatcherOptions& options) {
  const double z_hit = 1.0 - options.z_rand;
  return std::log(z_hit * std::exp(-distance_m * distance_m /
                                   (2.0 * options.sigma_m * options.sigma_m)) +
                  options.z_rand);
}

double ScanLogLikelihood(const LocalMap& map, const Pose2& pose,
                         std::span<const Eigen::Vector2d> points, const MatcherOptions& options) {
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    sum += PointLogLikelihood(static_cast<double>(map.FieldDistanceAt(pose * p)), options);
  }
  return sum;
}

PosePrior PriorFromWindow(const Pose2& mean, const SearchWindow& window) {
  // The window is 2 sigma; a zero window would be an infinitely sure prior: keep it finite.
  return {mean, std::max(0.5 * window.xy_m, 1e-3), std::max(0.5 * window.yaw_rad, 1e-4)};
}

double PriorLogDensity(const PosePrior& prior, const Pose2& pose) {
  const double dxy = (pose.translation - prior.mean.translation).norm() / prior.sigma_xy_m;
  const double dyaw = WrapAngle(pose.yaw - prior.mean.yaw) / prior.sigma_yaw_rad;
  return -0.5 * (dxy * dxy + dyaw * dyaw);
}

SearchWindow SearchWindowFor(const Pose2& increment, const MatcherOptions& o) {
  const double dist = increment.translation.norm();
  const double turn = std::abs(WrapAngle(increment.yaw));
  SearchWindow w;
  w.xy_m = std::min(o.max_search_xy_m, o.search_xy_base_m + o.search_xy_per_m * dist);
  w.yaw_rad = std::min(o.max_search_yaw_rad, o.search_yaw_base_rad +
                                                 o.search_yaw_per_rad * turn +
                                                 o.search_yaw_per_m * dist);
  return w;
}

Pose2 CorrelativeSearch(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                        const Pose2& initial, const SearchWindow& window,
                        const MatcherOptions& options) {
  if (points.empty()) return initial;
  const double cell = map.options().cell_size_m;
  const double max_d = map.options().field_max_distance_m;
  const int step = options.coarse_step_cells;
  const int coarse_half =
      static_cast<int>(std::ceil(window.xy_m / (static_cast<double>(step) * cell)));
  const double scale = options.effective_beams / static_cast<double>(points.size());
  const PosePrior prior = PriorFromWindow(initial, window);
  const LikelihoodTable coarse_table(options.coarse_sigma_m, max_d, options);
  GridBest coarse = SearchGrid(map, points, initial.translation,
                               AnglesAround(initial.yaw, window.yaw_rad, options.coarse_step_rad),
                               coarse_half, step, coarse_table, scale, prior);
  // A best heading on the window's edge says the true one may lie beyond it: extend the
  // heading window band by band while the best stays on the outermost angle. The prior is the
  // window's still (a weaker one let the scan's other optima win: docs/lidar-slam.md), so a
  // heading beyond the window must earn its place against it.
  const double yaw_step = options.coarse_step_rad;
  const int band = static_cast<int>(std::ceil(window.yaw_rad / yaw_step));
  const int last_allowed = static_cast<int>(
      std::floor(options.search_yaw_edge_extend * static_cast<double>(band) + 1e-9));
  int outer = band;
  const auto on_edge = [&](const GridBest& best) {
    return std::lround(std::abs(WrapAngle(best.yaw - initial.yaw)) / yaw_step) >= outer;
  };
  while (band > 0 && outer < last_allowed && on_edge(coarse)) {
    const int next = std::min(outer + band, last_allowed);
    const GridBest extended = SearchGrid(map, points, initial.translation,
                                         AnglesInBand(initial.yaw, outer + 1, next, yaw_step),
                                         coarse_half, step, coarse_table, scale, prior);
    outer = next;
    // Strictly better only, as inside the grid: a tie keeps the pose nearer the prior.
    if (extended.score > coarse.score) coarse = extended;
  }
  // Fine: one-cell steps over +-1 coarse step, finer angles over +-1 coarse angle step.
  const Eigen::Vector2d coarse_origin =
      initial.translation + cell * Eigen::Vector2d(coarse.dx, coarse.dy);
  const GridBest fine =
      SearchGrid(map, points, coarse_origin,
                 AnglesAround(coarse.yaw, options.coarse_step_rad, options.fine_step_rad), step,
                 1, LikelihoodTable(options.sigma_m, max_d, options), scale, prior);
  return Pose2(coarse_origin + cell * Eigen::Vector2d(fine.dx, fine.dy), WrapAngle(fine.yaw));
}

Refinement RefineGaussNewton(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                             const Pose2& initial, int iterations, const MatcherOptions& options,
                             const PosePrior* prior) {
  Refinement result;
  result.pose = initial;
  const double s2 = options.sigma_m * options.sigma_m;
  const double max_d = map.options().field_max_distance_m;

  // Cost, Hessian and gradient at a pose; points at the field's cap carry no gradient.
  struct Normal {
    double cost = 0.0;
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
  };
  auto evaluate = [&](const Pose2& pose) {
    Normal n;
    const Eigen::Matrix2d r = pose.Rotation();
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector2d rp = r * p;
      const LocalMap::FieldSample f = map.InterpolatedField(rp + pose.translation);
      const double d = std::min(f.distance_m, max_d);
      const double w = s2 / (s2 + d * d);  // Cauchy weight
      n.cost += s2 * std::log1p(d * d / s2);
      if (d >= max_d) continue;
      // d(T p)/d(x, y, yaw) = grad^T [I | (-rp.y, rp.x)].
      const Eigen::Vector3d j(f.gradient.x(), f.gradient.y(),
                              f.gradient.x() * -rp.y() + f.gradient.y() * rp.x());
      n.h += w * j * j.transpose();
      n.g += w * j * d;
    }
    if (prior != nullptr) {
      // -log prior in the points' units: the points' cost is about 2 sigma^2 B / effective
      // beams times their negative log-likelihood.
      const double k = s2 * static_cast<double>(points.size()) / options.effective_beams;
      const Eigen::Vector3d e(pose.x() - prior->mean.x(), pose.y() - prior->mean.y(),
                              WrapAngle(pose.yaw - prior->mean.yaw));
      const Eigen::Vector3d inv(1.0 / (prior->sigma_xy_m * prior->sigma_xy_m),
                                1.0 / (prior->sigma_xy_m * prior->sigma_xy_m),
                                1.0 / (prior->sigma_yaw_rad * prior->sigma_yaw_rad));
      n.cost += k * e.dot(inv.cwiseProduct(e));
      n.h.diagonal() += k * inv;
      n.g += k * inv.cwiseProduct(e);
    }
    return n;
  };

  Normal current = evaluate(result.pose);
  for (int it = 0; it < iterations; ++it) {
    // A little damping keeps the step finite along directions the scan does not constrain
    // (a corridor's axis).
    Eigen::Matrix3d h = current.h;
    h.diagonal() += Eigen::Vector3d::Constant(1e-6 + 1e-3 * h.trace());
    const Eigen::Vector3d delta = -h.ldlt().solve(current.g);
    if (!delta.allFinite()) break;
    const Pose2 candidate(result.pose.translation + delta.head<2>(),
                          WrapAngle(result.pose.yaw + delta.z()));
    const Normal next = evaluate(candidate);
    if (next.cost > current.cost) break;
    result.pose = candidate;
    current = next;
    ++result.iterations;
    if (delta.head<2>().norm() < 1e-4 && std::abs(delta.z()) < 1e-5) break;
  }
  Eigen::Matrix3d h = current.h;
  h.diagonal() += Eigen::Vector3d::Constant(1e-9);
  result.covariance = s2 * h.inverse();
  return result;
}

Refinement MatchScan(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                     const Pose2& initial, const SearchWindow& window,
                     const MatcherOptions& options) {
  const Pose2 searched = CorrelativeSearch(map, points, initial, window, options);
  const PosePrior prior = PriorFromWindow(initial, window);
  return RefineGaussNewton(map, points, searched, options.gauss_newton_iterations, options,
                           &prior);
}

}  // namespace lookout::lidar
