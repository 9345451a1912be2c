#include "lookout/grid/filter_options.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::grid {
namespace {

void Require(bool ok, const std::string& source, const std::string& field, const char* problem) {
  if (!ok) throw InputError(source, 0, "grid.filter." + field, problem);
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }
bool InOpenUnit(double v) { return v > 0.0 && v < 1.0; }  // NaN: false

}  // namespace

void FilterOptions::Validate(const std::string& source) const {
  Require(active_occupancy >= 0.5 && active_occupancy < 1.0, source, "active_occupancy",
          "must be in [0.5, 1)");
  Require(tracked_min_occupancy > 0.0 && tracked_min_occupancy <= active_occupancy, source,
          "tracked_min_occupancy", "must be in (0, active_occupancy]");
  Require(velocity_persistence_s > 0.0, source, "velocity_persistence_s",
          "must be > 0 (infinity: no decay)");
  Require(known_confidence >= 0.0 && known_confidence <= 1.0, source, "known_confidence",
          "must be in [0, 1]");
  Require(window_size_cells >= 1 && window_size_cells % 2 == 1 &&
              window_size_cells <= kMaxWindowSideCells,
          source, "window_size_cells", "must be odd and in [1, 31]");
  Require(new_window_size_cells >= 1 && new_window_size_cells % 2 == 1 &&
              new_window_size_cells <= kMaxWindowSideCells,
          source, "new_window_size_cells", "must be odd and in [1, 31]");
  Require(new_window_stride_cells >= 1 && new_window_stride_cells <= 4, source,
          "new_window_stride_cells", "must be in [1, 4]");
  Require(new_window_dense_half_cells >= 0 &&
              new_window_dense_half_cells <=
                  new_window_stride_cells * ((new_window_size_cells - 1) / 2),
          source, "new_window_dense_half_cells",
          "must be in [0, new_window_stride_cells * (new_window_size_cells - 1) / 2]");
  Require(std::isfinite(moved_share_exponent) && moved_share_exponent >= 0.0, source,
          "moved_share_exponent", "must be finite and >= 0");
  Require(InOpenUnit(seen_threshold), source, "seen_threshold", "must be in (0, 1)");
  Require(max_displacement_cells >= 0 && max_displacement_cells <= 64, source,
          "max_displacement_cells", "must be in [0, 64]");
  for (const double s : class_velocity_sigma_mps) {
    Require(Positive(s), source, "class_velocity_sigma_mps", "must be finite and > 0");
  }
  Require(Positive(min_sigma_cells), source, "min_sigma_cells", "must be finite and > 0");
  Require(Positive(new_sigma_m), source, "new_sigma_m", "must be finite and > 0");
  Require(new_stay_probability >= 0.0 && new_stay_probability < 1.0, source,
          "new_stay_probability", "must be in [0, 1)");
  scan_flow.Validate(source);
  cluster_motion.Validate(source);
  hidden_bodies.Validate(source);
  Require(Positive(no_convergence_sigma), source, "no_convergence_sigma",
          "must be finite and > 0");
  Require(Positive(rigidity_sigma_cells), source, "rigidity_sigma_cells",
          "must be finite and > 0");
  Require(std::isfinite(rigidity_link_gain) && rigidity_link_gain >= 0.0, source,
          "rigidity_link_gain", "must be finite and >= 0");
  Require(renewal_rate >= 0.0 && renewal_rate <= 1.0, source, "renewal_rate",
          "must be in [0, 1]");
  Require(occupancy_clamp > 0.0 && occupancy_clamp < 0.5, source, "occupancy_clamp",
          "must be in (0, 0.5)");
  Require(velocity_blend > 0.0 && velocity_blend <= 1.0, source, "velocity_blend",
          "must be in (0, 1]");
  Require(Positive(confidence_spread_cells2), source, "confidence_spread_cells2",
          "must be finite and > 0");
  Require(class_floor >= 0.0 && class_floor < 0.2, source, "class_floor", "must be in [0, 0.2)");
  Require(Positive(extent_radius_cells), source, "extent_radius_cells", "must be finite and > 0");
  Require(std::isfinite(unobserved_mover_speed_mps) && unobserved_mover_speed_mps >= 0.0, source,
          "unobserved_mover_speed_mps", "must be finite and >= 0");
  Require(std::isfinite(stereo_weight) && stereo_weight >= 0.0, source, "stereo_weight",
          "must be finite and >= 0");
}

}  // namespace lookout::grid
