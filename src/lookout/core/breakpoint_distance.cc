#include "lookout/core/breakpoint_distance.h"

#include <cmath>

namespace lookout {

double BreakpointDistance(double range_m, double dphi_rad, double incidence_rad, double noise_m) {
  if (dphi_rad >= incidence_rad) return noise_m;
  return range_m * std::sin(dphi_rad) / std::sin(incidence_rad - dphi_rad) + noise_m;
}

}  // namespace lookout
