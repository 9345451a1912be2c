#include "lookout/sim/contact.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace lookout::sim {
namespace {

constexpr double kBisectionToleranceS = 1e-4;

// Radius of the smallest circle about the pose that holds the footprint: two footprints
// whose centres are further apart than the sum cannot overlap, whatever their headings.
double BoundingRadius(const Footprint& f) {
  return f.kind == Footprint::Kind::kCircle ? f.radius_m : 0.5 * std::hypot(f.length_m, f.width_m);
}

}  // namespace

std::optional<double> FirstContactTime(const Trajectory& ego, double ego_length_m,
                                       double ego_width_m, const Trajectory& actor,
                                       const Footprint& actor_footprint, double t_begin_s,
                                       double t_end_s, double step_s) {
  assert(step_s > 0.0);
  const double lo = std::max({t_begin_s, ego.start_s(), actor.start_s()});
  const double hi = std::min({t_end_s, ego.stop_s(), actor.stop_s()});
  if (!(lo <= hi)) return std::nullopt;

  const Footprint ego_footprint = Footprint::Box(ego_length_m, ego_width_m);
  const double reach = BoundingRadius(ego_footprint) + BoundingRadius(actor_footprint);
  const auto touching = [&](double t) {
    const Pose2 ego_pose = ego.At(t).pose;
    const Pose2 actor_pose = actor.At(t).pose;
    if ((ego_pose.translation - actor_pose.translation).squaredNorm() > reach * reach) {
      return false;
    }
    return Overlap(FootprintAt(ego_footprint, ego_pose, kStaticOwner),
                   FootprintAt(actor_footprint, actor_pose, 0));
  };

  if (touching(lo)) return lo;
  double clear = lo;
  for (long i = 1;; ++i) {
    // Sample times from the index, not by accumulation, so that they do not drift.
    const double t = std::min(lo + static_cast<double>(i) * step_s, hi);
    if (touching(t)) {
      double hit = t;
      while (hit - clear > kBisectionToleranceS) {
        const double mid = 0.5 * (clear + hit);
        (touching(mid) ? hit : clear) = mid;
      }
      return hit;
    }
    if (t >= hi) return std::nullopt;
    clear = t;
  }
}

}  // namespace lookout::sim
