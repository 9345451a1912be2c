#include "lookout/core/grid_geometry.h"

#include <gtest/gtest.h>

namespace lookout {
namespace {

TEST(GridGeometryTest, CellCenterRoundTrips) {
  const GridGeometry g{Eigen::Vector2d(-30.0, -20.0), 0.15, 400, 300};
  for (int i = 0; i < g.CellCount(); i += 97) {
    const CellIndex c = g.FromLinear(i);
    ASSERT_EQ(g.LinearIndex(c), i);
    const auto back = g.CellAt(g.CellCenter(c));
    ASSERT_TRUE(back.has_value());
    ASSERT_EQ(*back, c);
  }
}

TEST(GridGeometryTest, PointsOutsideHaveNoCell) {
  const GridGeometry g{Eigen::Vector2d(0.0, 0.0), 1.0, 10, 5};
  EXPECT_FALSE(g.CellAt({-0.01, 1.0}).has_value());
  EXPECT_FALSE(g.CellAt({1.0, 5.0}).has_value());
  EXPECT_FALSE(g.CellAt({10.0, 1.0}).has_value());
  EXPECT_EQ(*g.CellAt({9.99, 4.99}), (CellIndex{9, 4}));
  EXPECT_EQ(*g.CellAt({0.0, 0.0}), (CellIndex{0, 0}));
}

}  // namespace
}  // namespace lookout
