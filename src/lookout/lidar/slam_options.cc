#include "lookout/lidar/slam_options.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::lidar {
namespace {

void Require(bool ok, const std::string& source, const std::string& field,
             const std::string& problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }
bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void MapOptions::Validate(const std::string& source) const {
  Require(Positive(cell_size_m), source, "map.cell_size_m", "must be finite and > 0");
  Require(window_cells >= 16 && window_cells <= 16384 &&
              (window_cells & (window_cells - 1)) == 0,
          source, "map.window_cells", "must be a power of two from 16 to 16384");
  Require(std::isfinite(recentre_share) && recentre_share > 0.0 && recentre_share < 0.5, source,
          "map.recentre_share", "must be in (0, 0.5)");
  Require(std::isfinite(log_odds_hit) && log_odds_hit > 0.0f, source, "map.log_odds_hit",
          "must be finite and > 0");
  Require(std::isfinite(log_odds_miss) && log_odds_miss < 0.0f, source, "map.log_odds_miss",
          "must be finite and < 0");
  Require(std::isfinite(log_odds_min) && log_odds_min < 0.0f, source, "map.log_odds_min",
          "must be finite and < 0");
  Require(std::isfinite(log_odds_max) && log_odds_max > 0.0f, source, "map.log_odds_max",
          "must be finite and > 0");
  Require(std::isfinite(occupied_log_odds) && occupied_log_odds > log_odds_min &&
              occupied_log_odds < log_odds_max,
          source, "map.occupied_log_odds", "must lie between log_odds_min and log_odds_max");
  Require(Positive(field_max_distance_m) && field_max_distance_m <= 50.0 * cell_size_m, source,
          "map.field_max_distance_m", "must be > 0 and at most 50 cells");
  Require(Positive(max_insert_range_m), source, "map.max_insert_range_m",
          "must be finite and > 0");
  Require(std::isfinite(min_insert_range_m) && min_insert_range_m >= 0.0 &&
              min_insert_range_m < max_insert_range_m,
          source, "map.min_insert_range_m", "must be in [0, max_insert_range_m)");
}

void MotionModelOptions::Validate(const std::string& source) const {
  Require(NonNegative(alpha1), source, "motion.alpha1", "must be finite and >= 0");
  Require(NonNegative(alpha2), source, "motion.alpha2", "must be finite and >= 0");
  Require(NonNegative(alpha3), source, "motion.alpha3", "must be finite and >= 0");
  Require(NonNegative(alpha4), source, "motion.alpha4", "must be finite and >= 0");
  Require(Positive(wheelbase_m), source, "motion.wheelbase_m", "must be finite and > 0");
  Require(Positive(max_steering_rad) && max_steering_rad < 1.5, source,
          "motion.max_steering_rad", "must be in (0, 1.5)");
  Require(NonNegative(arc_length_noise), source, "motion.arc_length_noise",
          "must be finite and >= 0");
  Require(NonNegative(steering_noise_rad), source, "motion.steering_noise_rad",
          "must be finite and >= 0");
}

void MatcherOptions::Validate(const std::string& source) const {
  Require(NonNegative(point_spacing_m), source, "matcher.point_spacing_m",
          "must be finite and >= 0");
  Require(max_points >= 3, source, "matcher.max_points", "must be at least 3");
  Require(NonNegative(min_range_m), source, "matcher.min_range_m", "must be finite and >= 0");
  Require(Positive(sigma_m), source, "matcher.sigma_m", "must be finite and > 0");
  Require(NonNegative(z_rand) && z_rand < 1.0, source, "matcher.z_rand", "must be in [0, 1)");
  Require(Positive(effective_beams), source, "matcher.effective_beams",
          "must be finite and > 0");
  Require(NonNegative(search_xy_base_m), source, "matcher.search_xy_base_m",
          "must be finite and >= 0");
  Require(NonNegative(search_xy_per_m), source, "matcher.search_xy_per_m",
          "must be finite and >= 0");
  Require(NonNegative(search_yaw_base_rad), source, "matcher.search_yaw_base_rad",
          "must be finite and >= 0");
  Require(NonNegative(search_yaw_per_rad), source, "matcher.search_yaw_per_rad",
          "must be finite and >= 0");
  Require(NonNegative(search_yaw_per_m), source, "matcher.search_yaw_per_m",
          "must be finite and >= 0");
  Require(NonNegative(max_search_xy_m), source, "matcher.max_search_xy_m",
          "must be finite and >= 0");
  Require(NonNegative(max_search_yaw_rad) && max_search_yaw_rad < 3.0, source,
          "matcher.max_search_yaw_rad", "must be in [0, 3)");
  Require(std::isfinite(search_yaw_edge_extend) && search_yaw_edge_extend >= 1.0 &&
              search_yaw_edge_extend <= 10.0,
          source, "matcher.search_yaw_edge_extend", "must be in [1, 10]");
  Require(coarse_step_cells >= 1 && coarse_step_cells <= 100, source,
          "matcher.coarse_step_cells", "must be in [1, 100]");
  Require(Positive(coarse_step_rad), source, "matcher.coarse_step_rad", "must be finite and > 0");
  Require(Positive(coarse_sigma_m), source, "matcher.coarse_sigma_m", "must be finite and > 0");
  Require(Positive(fine_step_rad) && fine_step_rad <= coarse_step_rad, source,
          "matcher.fine_step_rad", "must be > 0 and <= coarse_step_rad");
  Require(gauss_newton_iterations >= 0 && gauss_newton_iterations <= 100, source,
          "matcher.gauss_newton_iterations", "must be in [0, 100]");
}

void ParticleFilterOptions::Validate(const std::string& source) const {
  Require(
      std::isfinite(weight_prior_share) && weight_prior_share >= 0.0 && weight_prior_share <= 1.0,
      source, "filter.weight_prior_share", "must be in [0, 1]");
  Require(particle_count >= 1 && particle_count <= 100000, source, "filter.particle_count",
          "must be in [1, 100000]");
  Require(std::isfinite(resample_ess_share) && resample_ess_share >= 0.0 &&
              resample_ess_share <= 1.0,
          source, "filter.resample_ess_share", "must be in [0, 1]");
  Require(particle_refine_iterations >= 0 && particle_refine_iterations <= 100, source,
          "filter.particle_refine_iterations", "must be in [0, 100]");
}

void SlamOptions::Validate(const std::string& source) const {
  map.Validate(source);
  motion.Validate(source);
  matcher.Validate(source);
  filter.Validate(source);
  Require(NonNegative(history_s), source, "history_s", "must be finite and >= 0");
  Require(NonNegative(max_extrapolation_s), source, "max_extrapolation_s",
          "must be finite and >= 0");
}

}  // namespace lookout::lidar
