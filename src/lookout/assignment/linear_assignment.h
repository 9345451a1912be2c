#pragma once

// Optimal linear assignment: rows (targets, truths, measurements) to columns (hypotheses,
// tracks) at least total cost. The tracker's gating, Murty's m-best assignments and the
// tracking metrics all build on it.
//
// Written here rather than taken from a library: Debian 12 packages no C++ assignment solver
// (dlib's lives in a large framework and has no forbidden entries or rectangular problems).
// The algorithm is the shortest augmenting path of Jonker and Volgenant (1987) in the
// rectangular form of Crouse (2016, "On implementing 2D rectangular assignment algorithms"),
// without the initialisation heuristics (augmenting_path.h): O(min^2 * max) for a
// min x max problem, plus one dummy column per row when entries are forbidden.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

namespace lookout::assignment {

// An entry that may never be chosen. Every non-finite entry (+inf, -inf, NaN) is forbidden.
inline constexpr double kForbidden = std::numeric_limits<double>::infinity();

inline constexpr int kUnassigned = -1;

struct Assignment {
  std::vector<int> column_of_row;  // kUnassigned where a row has no column
  double cost = 0.0;               // the sum of the chosen entries

  int AssignedCount() const;
};

// The assignment with the most (row, column) pairs through allowed entries and, among those,
// the least total cost: rows are left unassigned only when the problem is rectangular or the
// forbidden entries leave no choice. (This is what "min-cost matching" means in the CLEAR MOT
// and identity metrics, and what scipy's linear_sum_assignment gives with its
// forbidden-entries workaround.) Any shape, 0 x N and N x 0 included.
Assignment SolveLinearAssignment(const Eigen::MatrixXd& cost);

// The least-cost assignment of every row to a distinct column through allowed entries;
// nullopt when there is none (more rows than columns, or forbidden entries block it).
// Murty's method and the tracker's hypotheses need this form: "miss" and "new track" are
// columns of their own, so that every row is always explained.
std::optional<Assignment> SolveCompleteAssignment(const Eigen::MatrixXd& cost);

// The cost of `column_of_row` on `cost`; +inf when it uses a forbidden entry. A literal check
// for tests and callers.
double AssignmentCost(const Eigen::MatrixXd& cost, const std::vector<int>& column_of_row);

}  // namespace lookout::assignment
