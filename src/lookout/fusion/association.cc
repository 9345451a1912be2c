#include "lookout/fusion/association.h"

#include <Eigen/Core>
#include <optional>

#include "lookout/assignment/linear_assignment.h"

namespace lookout::fusion {

std::vector<std::optional<std::size_t>> OwnPriors(std::span<const PairPrior> priors,
                                                  std::size_t stereo_count) {
  std::vector<std::optional<std::size_t>> own(stereo_count);
  for (std::size_t k = 0; k < priors.size(); ++k) {
    const std::optional<std::size_t>& stereo = priors[k].stereo;
    if (stereo && *stereo < stereo_count) own[*stereo] = k;
  }
  return own;
}

std::vector<AssociationPair> AssociateStereoToLidar(
    const std::vector<stereo::CartesianPoint>& stereo_points,
    const std::vector<stereo::CartesianPoint>& lidar_points, const AssociationGate& gate,
    std::span<const PairPrior> priors) {
  const auto n = static_cast<Eigen::Index>(stereo_points.size());
  const auto m = static_cast<Eigen::Index>(lidar_points.size());
  std::vector<AssociationPair> pairs;
  if (n == 0 || m == 0) return pairs;
  // Columns: the lidar objects, then one "unpaired" column per stereo object, allowed only on
  // its own row, at the gate's cost.
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n, m + n, assignment::kForbidden);
  Eigen::MatrixXd distance = Eigen::MatrixXd::Constant(n, m, assignment::kForbidden);
  // Which priors hold each lidar point: how many, and per stereo point whether its own does.
  // O(priors x lidar points) once, not per pair.
  std::vector<int> holders(static_cast<std::size_t>(m), 0);
  const std::vector<std::optional<std::size_t>> own_prior =
      OwnPriors(priors, static_cast<std::size_t>(n));
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> holds(
      static_cast<Eigen::Index>(priors.size()), m);
  for (std::size_t k = 0; k < priors.size(); ++k) {
    const PairPrior& p = priors[k];
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto& l = lidar_points[static_cast<std::size_t>(j)];
      const bool held = gate.Accepts(
          gate.DistanceSquared(p.point.point_m, p.point.covariance, l.point_m, l.covariance));
      holds(static_cast<Eigen::Index>(k), j) = held;
      holders[static_cast<std::size_t>(j)] += held ? 1 : 0;
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& s = stereo_points[static_cast<std::size_t>(i)];
    const std::optional<std::size_t> own = own_prior[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto& l = lidar_points[static_cast<std::size_t>(j)];
      const double d2 = gate.DistanceSquared(s.point_m, s.covariance, l.point_m, l.covariance);
      distance(i, j) = d2;
      if (!gate.Accepts(d2)) continue;
      if (own && !holds(static_cast<Eigen::Index>(*own), j) &&
          holders[static_cast<std::size_t>(j)] > 0) {
        continue;  // another camera track's body
      }
      cost(i, j) = d2;
    }
    cost(i, m + i) = gate.threshold();
  }
  const std::optional<assignment::Assignment> solution =
      assignment::SolveCompleteAssignment(cost);
  // Every row has its own allowed column, so a complete assignment always exists.
  if (!solution) return pairs;
  for (Eigen::Index i = 0; i < n; ++i) {
    const int column = solution->column_of_row[static_cast<std::size_t>(i)];
    if (column >= 0 && column < m) {
      pairs.push_back(AssociationPair{static_cast<std::size_t>(i),
                                      static_cast<std::size_t>(column), distance(i, column)});
    }
  }
  return pairs;
}

}  // namespace lookout::fusion
