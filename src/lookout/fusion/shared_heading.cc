#include "lookout/fusion/shared_heading.h"

#include <algorithm>
#include <cmath>

namespace lookout::fusion {

using Eigen::Matrix2d;

Matrix2d SharedHeadingCovariance(const stereo::HeadingShare& a, const stereo::HeadingShare& b) {
  const double yaw_variance = std::sqrt(a.yaw_variance * b.yaw_variance);
  Matrix2d cross = yaw_variance * a.heading_slope_m * b.heading_slope_m.transpose();
  const double qa = a.other_side_probability;
  const double qb = b.other_side_probability;
  const bool same_choice = a.other_side_offset_m.dot(b.other_side_offset_m) >= 0.0;
  const double indicator_covariance =
      same_choice ? std::min(qa, qb) - qa * qb : -(std::min(qa, 1.0 - qb) - qa * (1.0 - qb));
  cross += indicator_covariance * a.other_side_offset_m * b.other_side_offset_m.transpose();
  return cross;
}

}  // namespace lookout::fusion
