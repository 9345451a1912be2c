#include "lookout/assignment/linear_assignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <set>

#include "lookout/core/random.h"

namespace lookout::assignment {
namespace {

struct Best {
  int pairs = 0;
  double cost = 0.0;
};

// Literal reference: every partial assignment (each row to an unused allowed column, or to
// none); the most pairs, then the least cost.
Best BruteForce(const Eigen::MatrixXd& cost) {
  Best best{-1, 0.0};
  std::vector<char> used(static_cast<std::size_t>(cost.cols()), 0);
  std::function<void(Eigen::Index, int, double)> visit = [&](Eigen::Index row, int pairs,
                                                             double sum) {
    if (row == cost.rows()) {
      if (pairs > best.pairs || (pairs == best.pairs && sum < best.cost)) best = {pairs, sum};
      return;
    }
    visit(row + 1, pairs, sum);
    for (Eigen::Index j = 0; j < cost.cols(); ++j) {
      const auto uj = static_cast<std::size_t>(j);
      if (used[uj] || !std::isfinite(cost(row, j))) continue;
      used[uj] = 1;
      visit(row + 1, pairs + 1, sum + cost(row, j));
      used[uj] = 0;
    }
  };
  visit(0, 0, 0.0);
  return best;
}

// A valid assignment: columns in range, distinct, through allowed entries only.
void ExpectValid(const Eigen::MatrixXd& cost, const Assignment& a) {
  ASSERT_EQ(a.column_of_row.size(), static_cast<std::size_t>(cost.rows()));
  std::set<int> seen;
  for (std::size_t i = 0; i < a.column_of_row.size(); ++i) {
    const int j = a.column_of_row[i];
    if (j == kUnassigned) continue;
    ASSERT_GE(j, 0);
    ASSERT_LT(j, cost.cols());
    EXPECT_TRUE(seen.insert(j).second) << "column " << j << " used twice";
    EXPECT_TRUE(std::isfinite(cost(static_cast<Eigen::Index>(i), j)));
  }
  EXPECT_DOUBLE_EQ(a.cost, AssignmentCost(cost, a.column_of_row));
}

// Random matrices of 0..6 rows and columns. Integer costs on a small range make ties common;
// a share of entries is forbidden (sometimes most of them, to make problems infeasible).
Eigen::MatrixXd RandomCost(Rng& rng, bool integer_costs) {
  const auto rows = static_cast<Eigen::Index>(rng.UniformIndex(7));
  const auto cols = static_cast<Eigen::Index>(rng.UniformIndex(7));
  const double forbidden_share = rng.Uniform(0.0, 0.8);
  Eigen::MatrixXd cost(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      if (rng.Bernoulli(forbidden_share)) {
        cost(i, j) = kForbidden;
      } else {
        cost(i, j) =
            integer_costs ? static_cast<double>(rng.UniformIndex(4)) : rng.Uniform(-5.0, 10.0);
      }
    }
  }
  return cost;
}

TEST(LinearAssignment, SquareTextbookCase) {
  Eigen::MatrixXd cost(3, 3);
  cost << 4, 1, 3,  //
      2, 0, 5,      //
      3, 2, 2;
  const Assignment a = SolveLinearAssignment(cost);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{1, 0, 2}));
  EXPECT_DOUBLE_EQ(a.cost, 5.0);
}

TEST(LinearAssignment, EmptyShapes) {
  EXPECT_TRUE(SolveLinearAssignment(Eigen::MatrixXd(0, 4)).column_of_row.empty());
  const Assignment tall = SolveLinearAssignment(Eigen::MatrixXd(3, 0));
  EXPECT_EQ(tall.column_of_row, (std::vector<int>{kUnassigned, kUnassigned, kUnassigned}));
  EXPECT_EQ(tall.cost, 0.0);
  EXPECT_FALSE(SolveCompleteAssignment(Eigen::MatrixXd(2, 0)).has_value());
  EXPECT_TRUE(SolveCompleteAssignment(Eigen::MatrixXd(0, 3)).has_value());
}

TEST(LinearAssignment, RectangularLeavesTheCostliestRowOut) {
  Eigen::MatrixXd cost(3, 2);
  cost << 1, 9,  //
      9, 1,      //
      0.5, 0.5;
  const Assignment a = SolveLinearAssignment(cost);
  EXPECT_EQ(a.AssignedCount(), 2);
  EXPECT_DOUBLE_EQ(a.cost, 1.5);
}

TEST(LinearAssignment, MorePairsBeatLowerCost) {
  // One pair at cost 0 (row 1 to column 0) against two pairs at cost 20: the two pairs win,
  // as in CLEAR MOT, where every possible match counts before distances do.
  Eigen::MatrixXd cost(2, 2);
  cost << 10, kForbidden,  //
      0, 10;
  const Assignment a = SolveLinearAssignment(cost);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(a.cost, 20.0);
}

TEST(LinearAssignment, InfeasibleRowsStayUnassigned) {
  Eigen::MatrixXd cost(3, 3);
  cost << 1, kForbidden, kForbidden,  //
      2, kForbidden, kForbidden,      //
      kForbidden, kForbidden, 7;
  const Assignment a = SolveLinearAssignment(cost);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{0, kUnassigned, 2}));
  EXPECT_DOUBLE_EQ(a.cost, 8.0);
  EXPECT_FALSE(SolveCompleteAssignment(cost).has_value());
  const Eigen::MatrixXd nan_everywhere = Eigen::MatrixXd::Constant(2, 2, std::nan(""));
  EXPECT_EQ(SolveLinearAssignment(nan_everywhere).AssignedCount(), 0);
}

TEST(LinearAssignment, MatchesBruteForceOnRandomProblems) {
  for (std::uint64_t seed = 1; seed <= 3000; ++seed) {
    Rng rng(seed);
    const Eigen::MatrixXd cost = RandomCost(rng, seed % 2 == 0);
    const Best expected = BruteForce(cost);
    const Assignment got = SolveLinearAssignment(cost);
    ExpectValid(cost, got);
    ASSERT_EQ(got.AssignedCount(), expected.pairs) << "seed " << seed << "\n" << cost;
    ASSERT_NEAR(got.cost, expected.cost, 1e-9) << "seed " << seed << "\n" << cost;

    const std::optional<Assignment> complete = SolveCompleteAssignment(cost);
    const bool all_rows = expected.pairs == cost.rows();
    ASSERT_EQ(complete.has_value(), all_rows) << "seed " << seed << "\n" << cost;
    if (complete) {
      ExpectValid(cost, *complete);
      ASSERT_NEAR(complete->cost, expected.cost, 1e-9) << "seed " << seed;
    }
  }
}

TEST(LinearAssignment, LargeRandomAgainstItsTranspose) {
  // No brute force at 60 x 40; the transpose is solved by the other code path and must cost
  // the same.
  Rng rng(42);
  Eigen::MatrixXd cost(60, 40);
  for (Eigen::Index i = 0; i < cost.rows(); ++i) {
    for (Eigen::Index j = 0; j < cost.cols(); ++j) {
      cost(i, j) = rng.Bernoulli(0.3) ? kForbidden : rng.Uniform(0.0, 100.0);
    }
  }
  const Assignment a = SolveLinearAssignment(cost);
  const Assignment b = SolveLinearAssignment(cost.transpose());
  ExpectValid(cost, a);
  EXPECT_EQ(a.AssignedCount(), b.AssignedCount());
  EXPECT_NEAR(a.cost, b.cost, 1e-9);
}

}  // namespace
}  // namespace lookout::assignment
