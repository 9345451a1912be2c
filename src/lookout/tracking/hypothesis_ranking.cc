#include "lookout/tracking/hypothesis_ranking.h"

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <queue>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/assignment/murty.h"

namespace lookout::tracking {
namespace {

// One cluster's choices: its detections and, per ranked choice, the cost and what each of those
// detections became.
struct Cluster {
  std::vector<int> detections;
  std::vector<int> tracks;
  std::vector<double> costs;                  // ascending
  std::vector<std::vector<int>> assignments;  // per choice, per cluster detection
};

int Find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    int& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];
    i = p;
  }
  return i;
}

std::vector<Cluster> MakeClusters(const AssociationProblem& p) {
  const auto detections = static_cast<std::size_t>(p.detections);
  // Detections joined through a common track: union-find, a track's pairs linked to its first.
  std::vector<int> parent(detections);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> first_of_track(static_cast<std::size_t>(p.tracks), -1);
  for (const GatedPair& g : p.pairs) {
    int& first = first_of_track[static_cast<std::size_t>(g.track)];
    if (first < 0) {
      first = g.detection;
      continue;
    }
    const int a = Find(parent, first);
    const int b = Find(parent, g.detection);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  // Clusters in the order of their first detection (each root is its cluster's least index).
  std::vector<int> cluster_of(detections, -1);
  std::vector<Cluster> clusters;
  for (std::size_t d = 0; d < detections; ++d) {
    const auto root = static_cast<std::size_t>(Find(parent, static_cast<int>(d)));
    if (cluster_of[root] < 0) {
      cluster_of[root] = static_cast<int>(clusters.size());
      clusters.emplace_back();
    }
    cluster_of[d] = cluster_of[root];
    clusters[static_cast<std::size_t>(cluster_of[d])].detections.push_back(static_cast<int>(d));
  }
  for (int t = 0; t < p.tracks; ++t) {
    const int first = first_of_track[static_cast<std::size_t>(t)];
    if (first >= 0) clusters[static_cast<std::size_t>(cluster_of[static_cast<std::size_t>(first)])]
                        .tracks.push_back(t);
  }
  return clusters;
}

// The cluster's m best choices by Murty's method on rows = its detections, columns = its tracks,
// then one false-alarm and one new-track column per detection.
void RankCluster(const AssociationProblem& p,
                 const std::vector<std::vector<const GatedPair*>>& by_detection, std::size_t m,
                 Cluster& c) {
  const auto rows = static_cast<Eigen::Index>(c.detections.size());
  const auto tracks = static_cast<Eigen::Index>(c.tracks.size());
  if (rows == 1) {
    // One detection: its choices are its gated tracks, a false alarm and a new track, sorted by
    // cost, equal costs in that order (the fixed order). No solver needed: the common case.
    struct Choice {
      double cost;
      int what;
    };
    std::vector<Choice> choices;
    for (const GatedPair* g : by_detection[static_cast<std::size_t>(c.detections[0])]) {
      choices.push_back({g->cost, g->track});
    }
    std::stable_sort(choices.begin(), choices.end(),
                     [](const Choice& a, const Choice& b) { return a.what < b.what; });
    choices.push_back({p.false_alarm_cost, kFalseAlarm});
    choices.push_back({p.new_track_cost, kNewTrack});
    std::stable_sort(choices.begin(), choices.end(),
                     [](const Choice& a, const Choice& b) { return a.cost < b.cost; });
    if (choices.size() > m) choices.resize(m);
    for (const Choice& choice : choices) {
      c.costs.push_back(choice.cost);
      c.assignments.push_back({choice.what});
    }
    return;
  }
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(rows, tracks + 2 * rows, assignment::kForbidden);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (const GatedPair* g :
         by_detection[static_cast<std::size_t>(c.detections[static_cast<std::size_t>(r)])]) {
      const auto column =
          std::lower_bound(c.tracks.begin(), c.tracks.end(), g->track) - c.tracks.begin();
      cost(r, static_cast<Eigen::Index>(column)) = g->cost;
    }
    cost(r, tracks + r) = p.false_alarm_cost;
    cost(r, tracks + rows + r) = p.new_track_cost;
  }
  for (const assignment::Assignment& a : assignment::MurtyBestAssignments(cost, m)) {
    std::vector<int> choice(c.detections.size());
    for (Eigen::Index r = 0; r < rows; ++r) {
      const int column = a.column_of_row[static_cast<std::size_t>(r)];
      choice[static_cast<std::size_t>(r)] =
          column < tracks ? c.tracks[static_cast<std::size_t>(column)]
                          : (column < tracks + rows ? kFalseAlarm : kNewTrack);
    }
    c.costs.push_back(a.cost);
    c.assignments.push_back(std::move(choice));
  }
}

// A combination of one choice per cluster that has more than one, in the enumeration that makes
// each combination exactly once: a combination's successors raise the choice of one cluster at or
// after the last one raised.
struct Combination {
  double cost = 0.0;
  std::uint64_t sequence = 0;
  std::vector<int> choice;  // per varying cluster
  std::size_t last = 0;
};

struct CostlierFirst {
  bool operator()(const Combination& a, const Combination& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    return a.sequence > b.sequence;
  }
};

}  // namespace

std::vector<RankedAssociation> BestAssociations(const AssociationProblem& p, std::size_t m) {
  std::vector<RankedAssociation> out;
  if (m == 0) return out;
  std::vector<std::vector<const GatedPair*>> by_detection(static_cast<std::size_t>(p.detections));
  for (const GatedPair& g : p.pairs) {
    by_detection[static_cast<std::size_t>(g.detection)].push_back(&g);
  }

  std::vector<Cluster> clusters = MakeClusters(p);
  double fixed_cost = 0.0;  // of the clusters with a single choice
  std::vector<std::size_t> varying;
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    RankCluster(p, by_detection, m, clusters[k]);
    if (clusters[k].costs.empty()) return out;  // a cluster that cannot be explained (never: its
                                                // false-alarm columns always can)
    if (clusters[k].costs.size() == 1) {
      fixed_cost += clusters[k].costs[0];
    } else {
      varying.push_back(k);
    }
  }

  const auto emit = [&](const Combination& combination) {
    RankedAssociation a;
    a.cost = combination.cost;
    a.track_of_detection.assign(static_cast<std::size_t>(p.detections), kFalseAlarm);
    for (std::size_t k = 0, v = 0; k < clusters.size(); ++k) {
      const Cluster& c = clusters[k];
      std::size_t pick = 0;
      if (v < varying.size() && varying[v] == k) {
        pick = static_cast<std::size_t>(combination.choice[v++]);
      }
      for (std::size_t r = 0; r < c.detections.size(); ++r) {
        a.track_of_detection[static_cast<std::size_t>(c.detections[r])] = c.assignments[pick][r];
      }
    }
    out.push_back(std::move(a));
  };

  Combination best;
  best.cost = fixed_cost;
  best.choice.assign(varying.size(), 0);
  for (const std::size_t k : varying) best.cost += clusters[k].costs[0];
  std::priority_queue<Combination, std::vector<Combination>, CostlierFirst> queue;
  queue.push(std::move(best));
  std::uint64_t sequence = 1;
  while (!queue.empty() && out.size() < m) {
    Combination top = queue.top();
    queue.pop();
    if (out.size() + 1 < m) {
      for (std::size_t v = top.last; v < varying.size(); ++v) {
        const Cluster& c = clusters[varying[v]];
        const auto next = static_cast<std::size_t>(top.choice[v]) + 1;
        if (next >= c.costs.size()) continue;
        Combination successor = top;
        successor.cost += c.costs[next] - c.costs[next - 1];
        successor.choice[v] = static_cast<int>(next);
        successor.last = v;
        successor.sequence = sequence++;
        queue.push(std::move(successor));
      }
    }
    emit(top);
  }
  return out;
}

}  // namespace lookout::tracking
