#include "lookout/assignment/linear_assignment.h"

#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lookout/assignment/augmenting_path.h"

namespace lookout::assignment {
namespace {

// Cost compared lexicographically: first the number of rows sent to a "no column" dummy,
// then the sum of real entries. Solving with it gives the most pairs first and the least cost
// among those, exactly, where a large finite stand-in for "unassigned" (scipy's workaround)
// would round away the real costs next to it.
struct LexCost {
  std::int64_t unassigned = 0;
  double sum = 0.0;
};

LexCost operator+(LexCost a, LexCost b) { return {a.unassigned + b.unassigned, a.sum + b.sum}; }
LexCost operator-(LexCost a, LexCost b) { return {a.unassigned - b.unassigned, a.sum - b.sum}; }
bool operator<(LexCost a, LexCost b) {
  return a.unassigned != b.unassigned ? a.unassigned < b.unassigned : a.sum < b.sum;
}

// Every row of a rows <= cols problem by the shortest augmenting path; false when some row
// has no path to a free column.
template <typename Cost, typename Entry>
bool AugmentAllRows(int rows, int cols, const Entry& entry, std::vector<int>& column_of_row) {
  internal::AugmentingState<Cost> state(static_cast<std::size_t>(rows),
                                        static_cast<std::size_t>(cols));
  internal::AugmentingWorkspace<Cost> workspace;
  for (int row = 0; row < rows; ++row) {
    if (!internal::AugmentRow(row, entry, state, workspace)) return false;
  }
  column_of_row = std::move(state.column_of_row);
  return true;
}

// Rows <= columns. Every row gets a real column or its own dummy column (cost: one
// unassigned row), so an assignment always exists.
std::vector<int> SolveMostPairs(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  std::vector<int> column_of_row;
  const auto entry = [&cost, cols](int i, int j, LexCost* c) {
    if (j < cols) {
      const double x = cost(i, j);
      if (!std::isfinite(x)) return false;
      *c = {0, x};
      return true;
    }
    if (j - cols != i) return false;
    *c = {1, 0.0};
    return true;
  };
  const bool ok = AugmentAllRows<LexCost>(rows, cols + rows, entry, column_of_row);
  assert(ok);
  static_cast<void>(ok);
  for (int& j : column_of_row) {
    if (j >= cols) j = kUnassigned;
  }
  return column_of_row;
}

// Rows <= columns: the most pairs, then the least cost.
std::vector<int> SolveWide(const Eigen::MatrixXd& cost) {
  // All entries allowed: every row is assigned, no dummy columns needed.
  if (cost.allFinite()) return SolveCompleteAssignment(cost)->column_of_row;
  return SolveMostPairs(cost);
}

}  // namespace

int Assignment::AssignedCount() const {
  int count = 0;
  for (const int j : column_of_row) count += j != kUnassigned ? 1 : 0;
  return count;
}

double AssignmentCost(const Eigen::MatrixXd& cost, const std::vector<int>& column_of_row) {
  double sum = 0.0;
  for (std::size_t i = 0; i < column_of_row.size(); ++i) {
    const int j = column_of_row[i];
    if (j == kUnassigned) continue;
    const double x = cost(static_cast<Eigen::Index>(i), j);
    if (!std::isfinite(x)) return kForbidden;
    sum += x;
  }
  return sum;
}

std::optional<Assignment> SolveCompleteAssignment(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  if (rows > cols) return std::nullopt;
  Assignment result;
  const auto entry = [&cost](int i, int j, double* c) {
    *c = cost(i, j);
    return std::isfinite(*c);
  };
  if (!AugmentAllRows<double>(rows, cols, entry, result.column_of_row)) return std::nullopt;
  result.cost = AssignmentCost(cost, result.column_of_row);
  return result;
}

Assignment SolveLinearAssignment(const Eigen::MatrixXd& cost) {
  const auto rows = static_cast<std::size_t>(cost.rows());
  Assignment result;
  result.column_of_row.assign(rows, kUnassigned);
  if (cost.rows() == 0 || cost.cols() == 0) return result;

  if (cost.rows() <= cost.cols()) {
    result.column_of_row = SolveWide(cost);
  } else {
    // More rows than columns: solve the transpose, whose rows are fewer.
    const std::vector<int> row_of_column = SolveWide(cost.transpose());
    for (std::size_t j = 0; j < row_of_column.size(); ++j) {
      if (row_of_column[j] != kUnassigned) {
        result.column_of_row[static_cast<std::size_t>(row_of_column[j])] = static_cast<int>(j);
      }
    }
  }
  result.cost = AssignmentCost(cost, result.column_of_row);
  return result;
}

}  // namespace lookout::assignment
