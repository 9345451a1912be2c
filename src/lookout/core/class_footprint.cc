#include "lookout/core/class_footprint.h"

#include <cmath>
#include <utility>

namespace lookout {

std::optional<const char*> ClassFootprints::FirstInvalidField() const {
  const std::pair<double, const char*> fields[] = {{pedestrian_radius_m, "pedestrian_radius_m"},
                                                   {cyclist_length_m, "cyclist_length_m"},
                                                   {cyclist_width_m, "cyclist_width_m"},
                                                   {car_length_m, "car_length_m"},
                                                   {car_width_m, "car_width_m"},
                                                   {truck_length_m, "truck_length_m"},
                                                   {truck_width_m, "truck_width_m"}};
  for (const auto& [value, name] : fields) {
    if (!(std::isfinite(value) && value > 0.0)) return name;
  }
  return std::nullopt;
}

}  // namespace lookout
