#include "lookout/risk/carriageway.h"

#include <gtest/gtest.h>

#include <numbers>

namespace lookout::risk {
namespace {

// A junction of two 7 m roads, the north-south one turned by 90 degrees: inside either, on a
// kerb, and on the sidewalks and the corner block between them.
TEST(CarriagewayTest, APointIsOnTheRoadInsideARectangleOrOnItsKerb) {
  const Carriageways roads = {Footprint::Box({0.0, 0.0}, 0.0, 120.0, 7.0),
                              Footprint::Box({0.0, 0.0}, 0.5 * std::numbers::pi, 120.0, 7.0)};
  EXPECT_TRUE(OnCarriageway(roads, {-30.0, -1.75})) << "the east-west road's lane";
  EXPECT_TRUE(OnCarriageway(roads, {1.0, 40.0})) << "the north-south road";
  EXPECT_TRUE(OnCarriageway(roads, {-30.0, -3.5})) << "the kerb itself";
  EXPECT_FALSE(OnCarriageway(roads, {-30.0, -3.6})) << "just on the sidewalk";
  EXPECT_FALSE(OnCarriageway(roads, {-5.3, -7.0})) << "the south-west corner's sidewalk";
  EXPECT_FALSE(OnCarriageway(roads, {-61.0, 0.0})) << "beyond the road's end";
  EXPECT_FALSE(OnCarriageway({}, {0.0, 0.0})) << "no map: no carriageway";
}

}  // namespace
}  // namespace lookout::risk
