#include "lookout/assignment/murty.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <set>

#include "lookout/core/random.h"

namespace lookout::assignment {
namespace {

// Literal reference: the costs of every complete assignment, sorted.
std::vector<double> AllCompleteCosts(const Eigen::MatrixXd& cost) {
  std::vector<double> costs;
  std::vector<char> used(static_cast<std::size_t>(cost.cols()), 0);
  std::function<void(Eigen::Index, double)> visit = [&](Eigen::Index row, double sum) {
    if (row == cost.rows()) {
      costs.push_back(sum);
      return;
    }
    for (Eigen::Index j = 0; j < cost.cols(); ++j) {
      const auto uj = static_cast<std::size_t>(j);
      if (used[uj] || !std::isfinite(cost(row, j))) continue;
      used[uj] = 1;
      visit(row + 1, sum + cost(row, j));
      used[uj] = 0;
    }
  };
  visit(0, 0.0);
  std::sort(costs.begin(), costs.end());
  return costs;
}

TEST(Murty, SmallCaseByHand) {
  Eigen::MatrixXd cost(2, 2);
  cost << 1, 2,  //
      3, 5;
  const std::vector<Assignment> best = MurtyBestAssignments(cost, 5);
  ASSERT_EQ(best.size(), 2u);  // only two complete assignments exist
  EXPECT_EQ(best[0].column_of_row, (std::vector<int>{1, 0}));
  EXPECT_DOUBLE_EQ(best[0].cost, 5.0);
  EXPECT_EQ(best[1].column_of_row, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(best[1].cost, 6.0);
}

TEST(Murty, NothingWhenRowsCannotAllBeAssigned) {
  EXPECT_TRUE(MurtyBestAssignments(Eigen::MatrixXd::Zero(3, 2), 4).empty());
  Eigen::MatrixXd blocked(2, 2);
  blocked << 1, kForbidden,  //
      2, kForbidden;
  EXPECT_TRUE(MurtyBestAssignments(blocked, 4).empty());
  EXPECT_TRUE(MurtyBestAssignments(Eigen::MatrixXd::Zero(2, 2), 0).empty());
  const std::vector<Assignment> empty_rows = MurtyBestAssignments(Eigen::MatrixXd(0, 3), 4);
  ASSERT_EQ(empty_rows.size(), 1u);  // the empty assignment, once
  EXPECT_TRUE(empty_rows[0].column_of_row.empty());
}

TEST(Murty, MatchesBruteForceRankingOnRandomProblems) {
  for (std::uint64_t seed = 1; seed <= 1500; ++seed) {
    Rng rng(seed);
    const auto rows = static_cast<Eigen::Index>(rng.UniformIndex(6));
    const auto cols = rows + static_cast<Eigen::Index>(rng.UniformIndex(3));
    const double forbidden_share = rng.Uniform(0.0, 0.4);
    const bool integer_costs = seed % 2 == 0;  // many ties
    Eigen::MatrixXd cost(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index j = 0; j < cols; ++j) {
        cost(i, j) = rng.Bernoulli(forbidden_share) ? kForbidden
                     : integer_costs                ? static_cast<double>(rng.UniformIndex(3))
                                                    : rng.Uniform(0.0, 10.0);
      }
    }
    const std::size_t m = 1 + rng.UniformIndex(30);
    const std::vector<double> all = AllCompleteCosts(cost);
    const std::vector<Assignment> best = MurtyBestAssignments(cost, m);
    ASSERT_EQ(best.size(), std::min(m, all.size())) << "seed " << seed << "\n" << cost;
    std::set<std::vector<int>> distinct;
    for (std::size_t k = 0; k < best.size(); ++k) {
      ASSERT_NEAR(best[k].cost, all[k], 1e-9) << "seed " << seed << " rank " << k << "\n" << cost;
      ASSERT_DOUBLE_EQ(best[k].cost, AssignmentCost(cost, best[k].column_of_row))
          << "seed " << seed;
      ASSERT_EQ(best[k].AssignedCount(), rows) << "seed " << seed;
      ASSERT_TRUE(distinct.insert(best[k].column_of_row).second)
          << "seed " << seed << ": assignment " << k << " repeated";
      if (k > 0) {
        ASSERT_LE(best[k - 1].cost, best[k].cost) << "seed " << seed;
      }
    }
  }
}

}  // namespace
}  // namespace lookout::assignment
