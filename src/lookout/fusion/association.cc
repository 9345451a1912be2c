#include "lookout/fusion/association.h"

#include <Eigen/Core>
#include <optional>

#include "lookout/assignment/linear_assignment.h"

namespace lookout::fusion {

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
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& s = stereo_points[static_cast<std::size_t>(i)];
    const auto own = static_cast<std::size_t>(i);
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto& l = lidar_points[static_cast<std::size_t>(j)];
      const double d2 = gate.DistanceSquared(s.point_m, s.covariance, l.point_m, l.covariance);
      distance(i, j) = d2;
      if (!gate.Accepts(d2)) continue;
      const auto holds = [&](const PairPrior& p) {
        return gate.Accepts(
            gate.DistanceSquared(p.point.point_m, p.point.covariance, l.point_m, l.covariance));
      };
      bool own_prior = false, own_holds = false, other_holds = false;
      for (const PairPrior& p : priors) {
        if (p.stereo == own) {
          own_prior = true;
          own_holds = own_holds || holds(p);
        } else {
          other_holds = other_holds || holds(p);
        }
      }
      if (own_prior && !own_holds && other_holds) continue;
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
