#include "lookout/core/breakpoint_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/pose2.h"

namespace lookout {
namespace {

// Two impacts on a plane seen at exactly the incidence lambda, from beams dphi apart, lie
// r sin(dphi) / sin(lambda - dphi) apart (the sine rule in the triangle sensor-impact-impact):
// the breakpoint distance without noise is that spacing.
TEST(BreakpointDistance, IsTheSpacingOfImpactsOnASurfaceAtTheGrazingIncidence) {
  const double r = 12.0, dphi = DegToRad(0.25), lambda = DegToRad(10.0);
  // The plane through the first impact (r, 0) at incidence lambda to its beam; the second beam
  // at angle dphi meets it at range r2 (law of sines: r2 / sin(pi - lambda) = r / sin(lambda -
  // dphi)).
  const double r2 = r * std::sin(lambda) / std::sin(lambda - dphi);
  const double spacing = std::hypot(r2 * std::cos(dphi) - r, r2 * std::sin(dphi));
  EXPECT_NEAR(BreakpointDistance(r, dphi, lambda, 0.0), spacing, 1e-9);
  EXPECT_NEAR(BreakpointDistance(r, dphi, lambda, 0.09), spacing + 0.09, 1e-9);
}

TEST(BreakpointDistance, GrowsWithRangeAndIsTheNoiseBeyondTheIncidence) {
  const double dphi = DegToRad(0.25), lambda = DegToRad(10.0);
  EXPECT_LT(BreakpointDistance(5.0, dphi, lambda, 0.09),
            BreakpointDistance(40.0, dphi, lambda, 0.09));
  EXPECT_DOUBLE_EQ(BreakpointDistance(40.0, lambda, lambda, 0.09), 0.09);
}

}  // namespace
}  // namespace lookout
