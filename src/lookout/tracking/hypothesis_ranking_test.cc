#include "lookout/tracking/hypothesis_ranking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "lookout/assignment/murty.h"
#include "lookout/core/random.h"

namespace lookout::tracking {
namespace {

// Every association, by depth-first enumeration: the literal reference.
std::vector<RankedAssociation> Enumerate(const AssociationProblem& p) {
  std::vector<RankedAssociation> all;
  std::vector<int> choice(static_cast<std::size_t>(p.detections));
  std::vector<bool> taken(static_cast<std::size_t>(p.tracks), false);
  const std::function<void(int, double)> visit = [&](int j, double cost) {
    if (j == p.detections) {
      all.push_back({cost, choice});
      return;
    }
    const auto uj = static_cast<std::size_t>(j);
    choice[uj] = kFalseAlarm;
    visit(j + 1, cost + p.false_alarm_cost);
    choice[uj] = kNewTrack;
    visit(j + 1, cost + p.new_track_cost);
    for (const GatedPair& g : p.pairs) {
      if (g.detection != j || taken[static_cast<std::size_t>(g.track)]) continue;
      taken[static_cast<std::size_t>(g.track)] = true;
      choice[uj] = g.track;
      visit(j + 1, cost + g.cost);
      taken[static_cast<std::size_t>(g.track)] = false;
    }
  };
  visit(0, 0.0);
  std::stable_sort(
      all.begin(), all.end(),
      [](const RankedAssociation& a, const RankedAssociation& b) { return a.cost < b.cost; });
  return all;
}

double CostOf(const AssociationProblem& p, const std::vector<int>& track_of_detection) {
  double sum = 0.0;
  for (int j = 0; j < p.detections; ++j) {
    const int t = track_of_detection[static_cast<std::size_t>(j)];
    if (t == kFalseAlarm) {
      sum += p.false_alarm_cost;
    } else if (t == kNewTrack) {
      sum += p.new_track_cost;
    } else {
      const auto it = std::find_if(p.pairs.begin(), p.pairs.end(), [&](const GatedPair& g) {
        return g.track == t && g.detection == j;
      });
      if (it == p.pairs.end()) return std::numeric_limits<double>::infinity();
      sum += it->cost;
    }
  }
  return sum;
}

// A random small problem: 5 tracks, 6 detections, each pair gated with probability `density`.
AssociationProblem RandomProblem(Rng& rng, double density) {
  AssociationProblem p;
  p.tracks = 5;
  p.detections = 6;
  p.false_alarm_cost = rng.Uniform(0.0, 6.0);
  p.new_track_cost = rng.Uniform(0.0, 6.0);
  for (int t = 0; t < p.tracks; ++t) {
    for (int j = 0; j < p.detections; ++j) {
      if (rng.Bernoulli(density)) p.pairs.push_back({t, j, rng.Uniform(-4.0, 6.0)});
    }
  }
  return p;
}

TEST(HypothesisRanking, TheMBestAgreeWithBruteForceEnumeration) {
  for (const double density : {0.15, 0.35, 0.7}) {
    for (std::uint64_t seed = 1; seed <= 30; ++seed) {
      Rng rng(seed * 7919);
      const AssociationProblem p = RandomProblem(rng, density);
      const std::vector<RankedAssociation> reference = Enumerate(p);
      for (const std::size_t m : {1u, 10u, 40u}) {
        const std::vector<RankedAssociation> ranked = BestAssociations(p, m);
        ASSERT_EQ(ranked.size(), std::min(m, reference.size())) << "seed " << seed;
        for (std::size_t k = 0; k < ranked.size(); ++k) {
          EXPECT_NEAR(ranked[k].cost, reference[k].cost, 1e-9)
              << "seed " << seed << " density " << density << " m " << m << " rank " << k;
          EXPECT_NEAR(CostOf(p, ranked[k].track_of_detection), ranked[k].cost, 1e-9)
              << "seed " << seed << ": the association does not cost what it says";
        }
        // Distinct associations: no combination comes out twice.
        for (std::size_t a = 0; a < ranked.size(); ++a) {
          for (std::size_t b = a + 1; b < ranked.size(); ++b) {
            EXPECT_NE(ranked[a].track_of_detection, ranked[b].track_of_detection)
                << "seed " << seed;
          }
        }
      }
    }
  }
}

// The clusters change nothing: the same costs as Murty's method on the whole matrix.
TEST(HypothesisRanking, ClustersGiveWhatMurtyGivesOnTheWholeMatrix) {
  Rng rng(20261123);
  const AssociationProblem p = RandomProblem(rng, 0.25);
  const auto rows = static_cast<Eigen::Index>(p.detections);
  const auto tracks = static_cast<Eigen::Index>(p.tracks);
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(rows, tracks + 2 * rows, assignment::kForbidden);
  for (const GatedPair& g : p.pairs) cost(g.detection, g.track) = g.cost;
  for (Eigen::Index r = 0; r < rows; ++r) {
    cost(r, tracks + r) = p.false_alarm_cost;
    cost(r, tracks + rows + r) = p.new_track_cost;
  }
  const std::vector<assignment::Assignment> whole = assignment::MurtyBestAssignments(cost, 25);
  const std::vector<RankedAssociation> ranked = BestAssociations(p, 25);
  ASSERT_EQ(whole.size(), ranked.size());
  for (std::size_t k = 0; k < ranked.size(); ++k) EXPECT_NEAR(whole[k].cost, ranked[k].cost, 1e-9);
}

TEST(HypothesisRanking, EdgeCases) {
  AssociationProblem none;
  none.tracks = 3;
  const std::vector<RankedAssociation> empty_scan = BestAssociations(none, 5);
  ASSERT_EQ(empty_scan.size(), 1u) << "one way to explain no detection: every track missed";
  EXPECT_EQ(empty_scan[0].cost, 0.0);
  EXPECT_TRUE(BestAssociations(none, 0).empty());

  AssociationProblem lone;
  lone.detections = 1;
  lone.false_alarm_cost = 2.0;
  lone.new_track_cost = 2.0;
  const std::vector<RankedAssociation> tie = BestAssociations(lone, 5);
  ASSERT_EQ(tie.size(), 2u);
  EXPECT_EQ(tie[0].track_of_detection[0], kFalseAlarm) << "the fixed order on a tie";
  EXPECT_EQ(tie[1].track_of_detection[0], kNewTrack);
}

}  // namespace
}  // namespace lookout::tracking
