#include "lookout/app/lidar_hit_scoring.h"

#include <algorithm>
#include <vector>

#include "lookout/core/time.h"
#include "lookout/sim/shapes.h"

namespace lookout::app {
namespace {

constexpr double kMovingSpeed_mps = 0.5;

// The counts of one scan.
HitCounts CountBeams(const lidar::ScanHitClasses& classes, const sim::TruthFrame& truth) {
  HitCounts counts;
  // Speed of each actor index present in this frame.
  int max_index = -1;
  for (const sim::ActorTruth& a : truth.actors) max_index = std::max(max_index, a.index);
  std::vector<double> speed(static_cast<std::size_t>(max_index + 1), 0.0);
  for (const sim::ActorTruth& a : truth.actors) {
    speed[static_cast<std::size_t>(a.index)] = a.state.speed_mps;
  }
  const std::size_t n = std::min(classes.beam.size(), truth.lidar_beam_owner.size());
  for (std::size_t i = 0; i < n; ++i) {
    const lidar::HitClass k = classes.beam[i];
    if (k == lidar::HitClass::kNoReturn) {
      ++counts.no_returns;
      continue;
    }
    ++counts.returns;
    if (k == lidar::HitClass::kUnknown) ++counts.unknown;
    const bool dynamic = k == lidar::HitClass::kDynamic;
    const int owner = truth.lidar_beam_owner[i];
    if (owner == sim::kStaticOwner) {
      ++counts.static_world;
      if (dynamic) ++counts.static_dynamic;
    } else if (owner >= 0 && owner <= max_index) {
      if (speed[static_cast<std::size_t>(owner)] > kMovingSpeed_mps) {
        ++counts.moving;
        if (dynamic) ++counts.moving_dynamic;
        if (k == lidar::HitClass::kStatic) ++counts.moving_static;
        if (k == lidar::HitClass::kUnknown) ++counts.moving_unknown;
      } else if (dynamic) {
        ++counts.slow_actor_dynamic;
      }
    }
  }
  return counts;
}

}  // namespace

HitCounts& HitCounts::operator+=(const HitCounts& o) {
  returns += o.returns;
  no_returns += o.no_returns;
  unknown += o.unknown;
  moving += o.moving;
  moving_dynamic += o.moving_dynamic;
  moving_static += o.moving_static;
  moving_unknown += o.moving_unknown;
  static_world += o.static_world;
  static_dynamic += o.static_dynamic;
  slow_actor_dynamic += o.slow_actor_dynamic;
  return *this;
}

void LidarHitScorer::Observe(const lidar::ScanHitClasses& classes, const sim::TruthFrame& truth) {
  if (!first_stamp_) first_stamp_ = truth.stamp;
  const HitCounts scan = CountBeams(classes, truth);
  counts_ += scan;
  if (ToSeconds(truth.stamp - *first_stamp_) >= kWarmUpS - 1e-9) after_warm_up_ += scan;
  ++frames_;
}

void LidarHitScorer::Report(std::map<std::string, double>& metrics) const {
  const HitCounts& c = counts_;
  auto ratio = [](std::int64_t a, std::int64_t b) {
    return static_cast<double>(a) / static_cast<double>(b);
  };
  // Dynamic returns on moving actors over those on movers and on the static world.
  const auto precision = [&](const HitCounts& h, const std::string& key) {
    const std::int64_t counted_dynamic = h.moving_dynamic + h.static_dynamic;
    if (counted_dynamic > 0) metrics[key] = ratio(h.moving_dynamic, counted_dynamic);
  };
  precision(c, "lidar_hits.moving_precision");
  if (c.moving > 0) {
    metrics["lidar_hits.moving_recall"] = ratio(c.moving_dynamic, c.moving);
    metrics["lidar_hits.moving_as_static"] = ratio(c.moving_static, c.moving);
    metrics["lidar_hits.moving_as_unknown"] = ratio(c.moving_unknown, c.moving);
  }
  if (c.static_world > 0) {
    metrics["lidar_hits.static_false_dynamic"] = ratio(c.static_dynamic, c.static_world);
  }
  if (c.returns > 0) metrics["lidar_hits.unknown_share"] = ratio(c.unknown, c.returns);
  if (frames_ > 0) metrics["lidar_hits.no_returns_per_frame"] = ratio(c.no_returns, frames_);
  const HitCounts& w = after_warm_up_;
  precision(w, "lidar_hits.moving_precision_after_1s");
  if (w.moving > 0) {
    metrics["lidar_hits.moving_recall_after_1s"] = ratio(w.moving_dynamic, w.moving);
  }
}

}  // namespace lookout::app
