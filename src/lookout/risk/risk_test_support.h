#pragma once

// What the risk tests share: predicted tracks of circles moving straight at constant speed, at
// the prediction's default 0.1 s step.

#include <Eigen/Core>

#include "lookout/risk/footprint.h"

namespace lookout::risk::testing {

inline constexpr double kDt = 0.1;

// A circle of `radius` from `start` at `velocity`, one footprint per step up to `horizon_s`.
inline FootprintTrack Straight(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity,
                               double radius, double horizon_s = 5.0) {
  FootprintTrack t;
  for (int k = 0; k * kDt <= horizon_s + 1e-9; ++k) {
    t.push_back(Footprint::Circle(start + velocity * (k * kDt), radius));
  }
  return t;
}

}  // namespace lookout::risk::testing
