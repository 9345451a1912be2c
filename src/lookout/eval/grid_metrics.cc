#include "lookout/eval/grid_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "lookout/core/planar_geometry.h"
#include "lookout/sim/shapes.h"

namespace lookout::eval {
namespace {

using Eigen::Vector2d;

std::size_t CellCount(const GridGeometry& g) {
  return static_cast<std::size_t>(std::max(g.CellCount(), 0));
}

bool SameGeometry(const GridGeometry& a, const GridGeometry& b) {
  return a.origin_m == b.origin_m && a.cell_size_m == b.cell_size_m && a.width == b.width &&
         a.height == b.height;
}

// A mismatch is a caller's bug, but one that would silently score the wrong cells in a release
// build, so it throws rather than asserts.
void CheckBelief(const GridBelief& belief) {
  const std::size_t n = CellCount(belief.geometry);
  if (belief.occupancy.size() != n || belief.velocity_x_mps.size() != n ||
      belief.velocity_y_mps.size() != n || belief.velocity_confidence.size() != n) {
    throw std::invalid_argument("GridBelief: every layer must hold geometry.CellCount() = " +
                                std::to_string(n) + " values");
  }
}

void CheckTruth(const GridBelief& belief, const sim::TruthRaster& truth) {
  CheckBelief(belief);
  const std::size_t n = CellCount(belief.geometry);
  if (!SameGeometry(belief.geometry, truth.geometry) || truth.occupied.size() != n ||
      truth.velocity.size() != n || truth.owner.size() != n) {
    throw std::invalid_argument("TruthRaster: not on the belief's geometry");
  }
}

double SquaredNorm(float x, float y) {
  const double dx = static_cast<double>(x);
  const double dy = static_cast<double>(y);
  return dx * dx + dy * dy;
}

// The footprint's reference point for "is the actor inside the grid".
Vector2d ShapeCentre(const sim::Shape& shape) {
  if (shape.kind == sim::Shape::Kind::kCircle) return shape.center;
  const sim::Aabb box = sim::BoundingBox(shape);
  return 0.5 * (box.min + box.max);
}

sim::Shape ShapeIn(const sim::Shape& shape, const Pose2& target_from_world) {
  sim::Shape out = shape;
  out.center = target_from_world * shape.center;
  for (Vector2d& v : out.vertices) v = target_from_world * v;
  return out;
}

}  // namespace

double DistanceToShape(const sim::Shape& shape, const Vector2d& p) {
  if (shape.kind == sim::Shape::Kind::kCircle) {
    return std::max(0.0, (p - shape.center).norm() - shape.radius);
  }
  if (sim::Contains(shape, p)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = shape.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    best = std::min(best, PointToSegment(p, shape.vertices[i], shape.vertices[(i + 1) % n]));
  }
  return best;
}

sim::TruthFrame TruthFrameIn(const sim::TruthFrame& frame, const Pose2& target_from_world) {
  sim::TruthFrame out = frame;
  out.ego.state.pose = target_from_world * frame.ego.state.pose;  // composition wraps the yaw
  out.ego.footprint = ShapeIn(frame.ego.footprint, target_from_world);
  for (sim::ActorTruth& a : out.actors) {
    a.state.pose = target_from_world * a.state.pose;
    a.footprint = ShapeIn(a.footprint, target_from_world);
  }
  return out;
}

std::vector<sim::Shape> ShapesIn(const std::vector<sim::Shape>& shapes,
                                 const Pose2& target_from_world) {
  std::vector<sim::Shape> out;
  out.reserve(shapes.size());
  for (const sim::Shape& s : shapes) out.push_back(ShapeIn(s, target_from_world));
  return out;
}

void GridMetricOptions::Validate() const {
  auto require = [](bool ok, const char* field, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("GridMetricOptions.") + field + ": " + what);
  };
  require(occupied_probability >= 0.0 && occupied_probability < 1.0, "occupied_probability",
          "must be in [0, 1)");
  require(moving_speed_mps >= 0.0 && std::isfinite(moving_speed_mps), "moving_speed_mps",
          "must be finite and >= 0");
  require(confident_velocity >= 0.0 && confident_velocity <= 1.0, "confident_velocity",
          "must be in [0, 1]");
  require(retention_radius_m >= 0.0 && std::isfinite(retention_radius_m), "retention_radius_m",
          "must be finite and >= 0");
  require(retention_mass_fraction > 0.0 && retention_mass_fraction <= 1.0,
          "retention_mass_fraction", "must be in (0, 1]");
  require(retention_min_mass_cells >= 0.0 && std::isfinite(retention_min_mass_cells),
          "retention_min_mass_cells", "must be finite and >= 0");
}

SquaredErrorSum VelocitySquaredErrors(const GridBelief& belief, const sim::TruthRaster& truth,
                                      const GridMetricOptions& options,
                                      const OwnerFilter& counting_allowed) {
  CheckTruth(belief, truth);
  const double min_speed2 = options.moving_speed_mps * options.moving_speed_mps;
  SquaredErrorSum out;
  const std::size_t n = CellCount(belief.geometry);
  for (std::size_t i = 0; i < n; ++i) {
    const int owner = truth.owner[i];
    if (!truth.occupied[i] || owner < 0) continue;
    const Eigen::Vector2f& v = truth.velocity[i];
    if (!(SquaredNorm(v.x(), v.y()) > min_speed2)) continue;
    if (!(static_cast<double>(belief.occupancy[i]) > options.occupied_probability)) continue;
    if (counting_allowed && !counting_allowed(owner)) continue;
    out.sum_squared +=
        SquaredNorm(belief.velocity_x_mps[i] - v.x(), belief.velocity_y_mps[i] - v.y());
    ++out.count;
  }
  return out;
}

FalseDynamicCount CountFalseDynamic(const GridBelief& belief, const sim::TruthRaster& truth,
                                    const GridMetricOptions& options) {
  CheckTruth(belief, truth);
  const double min_speed2 = options.moving_speed_mps * options.moving_speed_mps;
  FalseDynamicCount out;
  const std::size_t n = CellCount(belief.geometry);
  for (std::size_t i = 0; i < n; ++i) {
    if (!truth.occupied[i] || truth.owner[i] != sim::kStaticOwner) continue;
    if (!(static_cast<double>(belief.occupancy[i]) > options.occupied_probability)) continue;
    ++out.static_cells;
    const bool fast = SquaredNorm(belief.velocity_x_mps[i], belief.velocity_y_mps[i]) > min_speed2;
    const bool confident =
        static_cast<double>(belief.velocity_confidence[i]) >= options.confident_velocity;
    if (fast && confident) ++out.false_dynamic_cells;
  }
  return out;
}

SquaredErrorSum OccupancySquaredErrors(const GridBelief& belief, const sim::TruthRaster& truth,
                                       std::span<const std::uint8_t> in_range) {
  CheckTruth(belief, truth);
  const std::size_t n = CellCount(belief.geometry);
  if (in_range.size() != n) {
    throw std::invalid_argument("in-range mask: not on the belief's geometry");
  }
  SquaredErrorSum out;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_range[i]) continue;
    const double e = static_cast<double>(belief.occupancy[i]) - (truth.occupied[i] ? 1.0 : 0.0);
    out.sum_squared += e * e;
    ++out.count;
  }
  return out;
}

std::vector<std::uint8_t> WithinRangeMask(const GridGeometry& geometry,
                                          const Vector2d& sensor_position_m, double max_range_m) {
  std::vector<std::uint8_t> mask(CellCount(geometry), 0);
  const double r2 = max_range_m * max_range_m;
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      const CellIndex c{ix, iy};
      if ((geometry.CellCenter(c) - sensor_position_m).squaredNorm() <= r2) {
        mask[static_cast<std::size_t>(geometry.LinearIndex(c))] = 1;
      }
    }
  }
  return mask;
}

double ActorEvidenceMass(const GridBelief& belief, const sim::TruthRaster& truth,
                         const sim::Shape& footprint, int owner, double radius_m) {
  CheckTruth(belief, truth);
  const GridGeometry& g = belief.geometry;
  if (g.width <= 0 || g.height <= 0) return 0.0;
  const sim::Aabb box = sim::BoundingBox(footprint);
  // Cells whose centre may lie within radius_m of the box, clamped to the grid in floating
  // point before the cast (a far-away actor must not overflow an int).
  auto range = [&](double lo, double hi, double origin, int count, int& first, int& last) {
    const double f = std::floor((lo - radius_m - origin) / g.cell_size_m) - 1.0;
    const double l = std::ceil((hi + radius_m - origin) / g.cell_size_m) + 1.0;
    first = static_cast<int>(std::clamp(f, 0.0, static_cast<double>(count)));
    last = static_cast<int>(std::clamp(l, -1.0, static_cast<double>(count - 1)));
  };
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
  range(box.min.x(), box.max.x(), g.origin_m.x(), g.width, x0, x1);
  range(box.min.y(), box.max.y(), g.origin_m.y(), g.height, y0, y1);
  double mass = 0.0;
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) {
      const CellIndex c{ix, iy};
      const auto i = static_cast<std::size_t>(g.LinearIndex(c));
      const int truth_owner = truth.owner[i];
      if (truth.occupied[i] && truth_owner != owner) continue;  // another body's cell
      const double evidence = 2.0 * static_cast<double>(belief.occupancy[i]) - 1.0;
      if (evidence <= 0.0) continue;
      if (DistanceToShape(footprint, g.CellCenter(c)) > radius_m) continue;
      mass += std::min(evidence, 1.0);
    }
  }
  return mass;
}

void VelocityRmseAccumulator::AddFrame(const GridBelief& belief, const sim::TruthRaster& truth,
                                       const OwnerFilter& counting_allowed) {
  const SquaredErrorSum s = VelocitySquaredErrors(belief, truth, options_, counting_allowed);
  total_.sum_squared += s.sum_squared;
  total_.count += s.count;
}

std::optional<double> VelocityRmseAccumulator::Value() const {
  if (total_.count == 0) return std::nullopt;
  return std::sqrt(total_.sum_squared / static_cast<double>(total_.count));
}

void FalseDynamicAccumulator::AddFrame(const GridBelief& belief, const sim::TruthRaster& truth) {
  const FalseDynamicCount c = CountFalseDynamic(belief, truth, options_);
  total_.static_cells += c.static_cells;
  total_.false_dynamic_cells += c.false_dynamic_cells;
}

std::optional<double> FalseDynamicAccumulator::Value() const {
  if (total_.static_cells == 0) return std::nullopt;
  return static_cast<double>(total_.false_dynamic_cells) / static_cast<double>(total_.static_cells);
}

void OccupancyBrierAccumulator::AddFrame(const GridBelief& belief, const sim::TruthRaster& truth,
                                         std::span<const std::uint8_t> in_range) {
  const SquaredErrorSum s = OccupancySquaredErrors(belief, truth, in_range);
  total_.sum_squared += s.sum_squared;
  total_.count += s.count;
}

std::optional<double> OccupancyBrierAccumulator::Value() const {
  if (total_.count == 0) return std::nullopt;
  return total_.sum_squared / static_cast<double>(total_.count);
}

void ActorVisibilityClock::Observe(const sim::TruthFrame& frame, const GridGeometry& window) {
  for (const sim::ActorTruth& a : frame.actors) {
    if (a.visible_fraction_lidar > 0.0 && window.CellAt(ShapeCentre(a.footprint)).has_value()) {
      first_visible_.try_emplace(a.index, frame.stamp);
    }
  }
}

std::optional<TimeNs> ActorVisibilityClock::FirstVisible(int owner) const {
  const auto it = first_visible_.find(owner);
  if (it == first_visible_.end()) return std::nullopt;
  return it->second;
}

bool ActorVisibilityClock::VisibleForAtLeast(int owner, double min_visible_s, TimeNs now) const {
  const std::optional<TimeNs> first = FirstVisible(owner);
  return first.has_value() && now - *first >= FromSeconds(min_visible_s);
}

OwnerFilter ActorVisibilityClock::AfterFirstVisible(double min_visible_s, TimeNs now) const {
  return [this, min_visible_s, now](int owner) {
    return VisibleForAtLeast(owner, min_visible_s, now);
  };
}

void OccludedRetentionAccumulator::CloseRun(ActorState& state, TimeNs end) const {
  if (!state.in_episode) return;
  if (state.run_kept) {
    const double retained_s = ToSeconds(end - state.episode_start);
    state.longest_s = std::max(state.longest_s.value_or(0.0), retained_s);
  }
  state.in_episode = false;
  state.run_kept = false;
}

void OccludedRetentionAccumulator::AddFrame(const sim::TruthFrame& frame, const GridBelief& belief,
                                            const sim::TruthRaster& truth) {
  CheckTruth(belief, truth);
  const TimeNs now = frame.stamp;
  last_frame_stamp_ = now;
  std::map<int, bool> present;
  for (const sim::ActorTruth& a : frame.actors) {
    present[a.index] = true;
    ActorState& s = actors_[a.index];
    const bool visible = a.visible_fraction_lidar > 0.0;
    const bool in_grid = belief.geometry.CellAt(ShapeCentre(a.footprint)).has_value();
    if (visible) {
      CloseRun(s, now);
      const double mass =
          ActorEvidenceMass(belief, truth, a.footprint, a.index, options_.retention_radius_m);
      // A new visible run (first sight, or after an occlusion) starts its reference afresh.
      s.visible_run_mass = s.visible_last ? std::max(s.visible_run_mass, mass) : mass;
      s.seen = true;
      s.visible_last = true;
      continue;
    }
    s.visible_last = false;
    if (!s.seen || !in_grid) {
      CloseRun(s, now);
      continue;
    }
    if (!s.in_episode) {
      s.in_episode = true;
      s.run_kept = true;
      s.episode_start = now;
      s.reference_mass = s.visible_run_mass;
      s.longest_s = std::max(s.longest_s.value_or(0.0), 0.0);
    }
    if (!s.run_kept) continue;  // lost once: a coincidental later match is not retention
    const double mass =
        ActorEvidenceMass(belief, truth, a.footprint, a.index, options_.retention_radius_m);
    const double needed = std::max(options_.retention_mass_fraction * s.reference_mass,
                                   options_.retention_min_mass_cells);
    if (!(mass >= needed)) {
      const double retained_s = ToSeconds(now - s.episode_start);
      s.longest_s = std::max(s.longest_s.value_or(0.0), retained_s);
      s.run_kept = false;
    }
  }
  // Actors that left the scene end their episodes here.
  for (auto& [index, s] : actors_) {
    if (!present.contains(index)) {
      CloseRun(s, now);
      s.visible_last = false;
    }
  }
}

std::map<int, double> OccludedRetentionAccumulator::PerActorSeconds() const {
  std::map<int, double> out;
  for (const auto& [index, s] : actors_) {
    std::optional<double> longest = s.longest_s;
    // An episode still kept at the last frame counts up to that frame.
    if (s.in_episode && s.run_kept) {
      longest = std::max(longest.value_or(0.0), ToSeconds(last_frame_stamp_ - s.episode_start));
    }
    if (longest.has_value()) out[index] = *longest;
  }
  return out;
}

std::optional<double> OccludedRetentionAccumulator::Value() const {
  std::optional<double> best;
  for (const auto& [index, seconds] : PerActorSeconds()) {
    best = std::max(best.value_or(0.0), seconds);
  }
  return best;
}

}  // namespace lookout::eval
