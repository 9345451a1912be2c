#include "lookout/lidar/lidar_chain_options.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::lidar {

SlamOptions VehicleLocaliserOptions() {
  SlamOptions o;
  o.map.window_cells = 4096;
  o.map.max_insert_range_m = 80.0;
  o.motion.kind = MotionModelKind::kBicycle;
  // A car's wheel odometry errs by about 2 % of the distance and its steering reading by a few
  // milliradians: much tighter than the robot logs' 10 % and 0.02 rad.
  o.motion.arc_length_noise = 0.02;
  o.motion.steering_noise_rad = 0.005;
  // The correlative window (2 sigma of the odometry prior) grows with the increment; one
  // period at 11 m/s is 0.9 m: 0.05 + 0.9 x 0.05 = 0.095 m, yaw 0.01 + 0.9 x 0.005 rad.
  o.matcher.search_xy_base_m = 0.05;
  o.matcher.search_xy_per_m = 0.05;
  o.matcher.search_yaw_base_rad = 0.01;
  o.matcher.search_yaw_per_rad = 0.1;
  o.matcher.search_yaw_per_m = 0.005;
  o.matcher.max_search_xy_m = 0.4;
  o.matcher.max_search_yaw_rad = 0.1;
  o.matcher.coarse_step_rad = 0.005;
  o.matcher.fine_step_rad = 0.001;
  o.filter.refine_with_prior = true;
  return o;
}

MapOptions FarMapOptions() {
  MapOptions o;
  o.cell_size_m = 0.2;
  o.window_cells = 2048;
  o.recentre_share = 0.125;
  o.max_insert_range_m = 150.0;
  // Only returns beyond the fine map's 80 m read it: its near cells would cost rays and
  // nothing else (10 m of margin for the field around 80 m).
  o.min_insert_range_m = 70.0;
  return o;
}

void LidarChainOptions::Validate(const std::string& source) const {
  localiser.Validate(source);
  hits.Validate(source);
  segmentation.Validate(source);
  dynamic_segments.Validate(source);
  segment_motion.Validate(source);
  if (hits.static_tolerance_m > localiser.map.field_max_distance_m) {
    throw InputError(source, 0, "hits.static_tolerance_m",
                     "must be at most map.field_max_distance_m (the field knows no further)");
  }
  if (!std::isfinite(dynamic_ray_margin_m) || dynamic_ray_margin_m < 0.0) {
    throw InputError(source, 0, "dynamic_ray_margin_m", "must be finite and >= 0");
  }
  if (far_map_enabled) {
    far_map.Validate(source + ": far_map");
    if (!std::isfinite(far_static_tolerance_m) || far_static_tolerance_m < 0.0 ||
        far_static_tolerance_m > far_map.field_max_distance_m) {
      throw InputError(source, 0, "far_static_tolerance_m",
                       "must be in [0, far_map.field_max_distance_m]");
    }
  }
  if (!std::isfinite(neighbour_clear_margin_m)) {
    throw InputError(source, 0, "neighbour_clear_margin_m", "must be finite");
  }
  if (!std::isfinite(no_return_clear_m) || no_return_clear_m < 0.0) {
    throw InputError(source, 0, "no_return_clear_m", "must be finite and >= 0");
  }
}

}  // namespace lookout::lidar
