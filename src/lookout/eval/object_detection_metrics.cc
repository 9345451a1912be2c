#include "lookout/eval/object_detection_metrics.h"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "lookout/eval/grid_metrics.h"

namespace lookout::eval {

DetectionCounts& DetectionCounts::operator+=(const DetectionCounts& o) {
  objects += o.objects;
  matched_objects += o.matched_objects;
  actors += o.actors;
  matched_actors += o.matched_actors;
  return *this;
}

DetectionCounts MatchObjectsToMovingActors(const std::vector<Eigen::Vector2d>& object_points,
                                           const std::vector<sim::ActorTruth>& actors,
                                           const std::vector<bool>& countable,
                                           const DetectionMatchOptions& options) {
  if (!countable.empty() && countable.size() != actors.size()) {
    throw std::invalid_argument("MatchObjectsToMovingActors: countable has the wrong size");
  }
  auto counts_for_recall = [&countable](std::size_t a) {
    return countable.empty() || countable[a];
  };
  auto moving = [&options](const sim::ActorTruth& a) {
    return a.state.Velocity().norm() > options.moving_speed_mps;
  };

  // Candidate pairs within the gate, then greedy by (distance, object, actor).
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < actors.size(); ++a) {
    if (!moving(actors[a])) continue;
    for (std::size_t o = 0; o < object_points.size(); ++o) {
      const double d = DistanceToShape(actors[a].footprint, object_points[o]);
      if (d <= options.gate_m) pairs.emplace_back(d, o, a);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> object_taken(object_points.size(), false), actor_taken(actors.size(), false);
  DetectionCounts c;
  c.objects = static_cast<std::int64_t>(object_points.size());
  for (const auto& [d, o, a] : pairs) {
    if (object_taken[o] || actor_taken[a]) continue;
    object_taken[o] = true;
    actor_taken[a] = true;
    ++c.matched_objects;
  }
  for (std::size_t a = 0; a < actors.size(); ++a) {
    if (!moving(actors[a]) || !counts_for_recall(a)) continue;
    ++c.actors;
    if (actor_taken[a]) ++c.matched_actors;
  }
  return c;
}

std::optional<double> DetectionAccumulator::Precision() const {
  if (total_.objects == 0) return std::nullopt;
  return static_cast<double>(total_.matched_objects) / static_cast<double>(total_.objects);
}

std::optional<double> DetectionAccumulator::Recall() const {
  if (total_.actors == 0) return std::nullopt;
  return static_cast<double>(total_.matched_actors) / static_cast<double>(total_.actors);
}

}  // namespace lookout::eval
