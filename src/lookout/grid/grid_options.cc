#include "lookout/grid/grid_options.h"

#include <cmath>

#include "lookout/core/input_error.h"
#include "lookout/core/pose2.h"

namespace lookout::grid {
namespace {

void RequireGridOption(bool ok, const std::string& source, const std::string& field,
                       const char* problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

bool StrictlyBetween(double v, double lo, double hi) { return v > lo && v < hi; }  // NaN: false

}  // namespace

void InverseSensorModelOptions::Validate(const std::string& source,
                                         const std::string& prefix) const {
  RequireGridOption(StrictlyBetween(p_hit, 0.5, 1.0), source, prefix + ".p_hit",
                    "must be strictly between 0.5 and 1 (a hit is evidence of occupancy, never "
                    "certainty)");
  RequireGridOption(StrictlyBetween(p_free, 0.0, 0.5), source, prefix + ".p_free",
                    "must be strictly between 0 and 0.5 (a crossing is evidence of free space, "
                    "never certainty)");
  RequireGridOption(p_free_no_return >= p_free && p_free_no_return < 0.5, source,
                    prefix + ".p_free_no_return",
                    "must be in [p_free, 0.5): a beam without return is weaker evidence than one "
                    "with");
  RequireGridOption(std::isfinite(no_return_free_range_m) && no_return_free_range_m >= 0.0,
                    source, prefix + ".no_return_free_range_m", "must be finite and >= 0");
  RequireGridOption(std::isfinite(surface_gap_m) && surface_gap_m >= 0.0, source,
                    prefix + ".surface_gap_m", "must be finite and >= 0");
  RequireGridOption(surface_incidence_rad > 0.0 && surface_incidence_rad <= 0.5 * kPi, source,
                    prefix + ".surface_incidence_rad", "must be in (0, pi/2]");
  RequireGridOption(std::isfinite(surface_range_noise_m) && surface_range_noise_m >= 0.0, source,
                    prefix + ".surface_range_noise_m", "must be finite and >= 0");
  RequireGridOption(surface_max_turn_rad >= 0.0 && surface_max_turn_rad <= kPi, source,
                    prefix + ".surface_max_turn_rad", "must be in [0, pi]");
}

void GridOptions::Validate(const std::string& source) const {
  RequireGridOption(std::isfinite(cell_size_m) && cell_size_m > 0.0, source, "grid.cell_size_m",
                    "must be finite and > 0");
  RequireGridOption(width_cells >= 1 && width_cells <= kMaxGridSideCells, source,
                    "grid.width_cells", "must be in [1, 16384]");
  RequireGridOption(height_cells >= 1 && height_cells <= kMaxGridSideCells, source,
                    "grid.height_cells", "must be in [1, 16384]");
  inverse_sensor_model.Validate(source, "grid.inverse_sensor_model");
}

}  // namespace lookout::grid
