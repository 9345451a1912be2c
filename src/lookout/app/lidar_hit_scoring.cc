#include "lookout/app/lidar_hit_scoring.h"

#include <algorithm>
#include <vector>

#include "lookout/core/time.h"
#include "lookout/sim/shapes.h"

namespace lookout::app {
namespace {

constexpr double kMovingSpeed_mps = 0.5;

void CountBeams(const lidar::ScanHitClasses& classes, const sim::TruthFrame& truth,
                HitCounts& counts) {
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
}

}  // namespace

void LidarHitScorer::Observe(const lidar::ScanHitClasses& classes, const sim::TruthFrame& truth) {
  if (!first_stamp_) first_stamp_ = truth.stamp;
  CountBeams(classes, truth, counts_);
  if (ToSeconds(truth.stamp - *first_stamp_) >= kWarmUpS - 1e-9) {
    CountBeams(classes, truth, after_warm_up_);
  }
  ++frames_;
}

void LidarHitScorer::Report(std::map<std::string, double>& metrics) const {
  const HitCounts& c = counts_;
  auto ratio = [](std::int64_t a, std::int64_t b) {
    return static_cast<double>(a) / static_cast<double>(b);
  };
  const std::int64_t counted_dynamic = c.moving_dynamic + c.static_dynamic;
  if (counted_dynamic > 0) {
    metrics["lidar_hits.moving_precision"] = ratio(c.moving_dynamic, counted_dynamic);
  }
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
  if (w.moving_dynamic + w.static_dynamic > 0) {
    metrics["lidar_hits.moving_precision_after_1s"] =
        ratio(w.moving_dynamic, w.moving_dynamic + w.static_dynamic);
  }
  if (w.moving > 0) {
    metrics["lidar_hits.moving_recall_after_1s"] = ratio(w.moving_dynamic, w.moving);
  }
}

}  // namespace lookout::app
