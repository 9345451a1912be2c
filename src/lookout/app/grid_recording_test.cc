#include "lookout/app/grid_recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace lookout::app {
namespace {

TEST(GridRecordingTest, DirectionByteTurnsCounterClockwise) {
  EXPECT_EQ(DirectionByte(0.0, 0.0), 0);
  EXPECT_EQ(DirectionByte(-1.0, -1e-12), 0);   // just below -x: the start of the turn
  EXPECT_EQ(DirectionByte(0.0, -2.0), 64);     // -y
  EXPECT_EQ(DirectionByte(3.0, 0.0), 128);     // +x
  EXPECT_EQ(DirectionByte(0.0, 0.5), 192);     // +y
  EXPECT_EQ(DirectionByte(-1.0, 0.0), 0);      // exactly -x: +pi wraps to 0
  for (int k = 0; k < 256; ++k) {  // every byte's centre direction decodes back to itself
    const double a = -std::numbers::pi + (k + 0.5) * 2.0 * std::numbers::pi / 256.0;
    EXPECT_EQ(DirectionByte(std::cos(a), std::sin(a)), k) << "byte " << k;
  }
}

TEST(GridRecordingTest, LayersEncodeTheCellsState) {
  grid::ExtendedGrid g(grid::ScrollingGridGeometry(0.15, 4, 3, CellIndex{0, 0}));
  grid::GridLayers& layers = g.mutable_layers();
  const grid::FilterLayerIds& ids = g.ids();
  const std::size_t cell = g.geometry().StorageIndexOfLocal({2, 1});
  layers.Values(ids.occupancy)[cell] = 0.8f;
  layers.Values(ids.velocity_x_mps)[cell] = 0.0f;
  layers.Values(ids.velocity_y_mps)[cell] = 10.0f;  // half of full speed, along +y
  layers.Values(ids.velocity_confidence)[cell] = 0.5f;
  for (std::size_t c = 0; c < grid::kGridClassCount; ++c) {
    layers.Values(ids.class_pmf[c])[cell] = c == 3 ? 0.6f : 0.1f;
  }
  layers.Values(ids.rigidity[5])[cell] = 0.2f;

  const std::vector<io::GridLayer8> out = GridLayersToRecord(g);
  ASSERT_EQ(out.size(), 8u);
  const std::size_t i = 1 * 4 + 2;  // window order
  const auto at = [&](const char* name) {
    for (const io::GridLayer8& l : out) {
      if (l.name == name) {
        EXPECT_EQ(l.values.size(), 12u);
        return static_cast<int>(l.values[i]);
      }
    }
    ADD_FAILURE() << "no layer " << name;
    return -1;
  };
  EXPECT_EQ(at("occupancy"), 204);
  EXPECT_EQ(at("speed"), 128);
  EXPECT_EQ(at("direction"), 192);
  EXPECT_EQ(at("confidence"), 128);
  EXPECT_EQ(at("class"), 3);
  EXPECT_EQ(at("class_probability"), 153);
  EXPECT_EQ(at("rigidity"), 51);
  EXPECT_EQ(at("hidden"), 0);  // no body carried
  // An untouched cell: unknown occupancy, no speed, a uniform pmf (class 0 wins the tie).
  EXPECT_EQ(static_cast<int>(out[0].values[0]), 128);
  EXPECT_EQ(static_cast<int>(out[1].values[0]), 0);
  EXPECT_EQ(static_cast<int>(out[4].values[0]), 0);
  EXPECT_EQ(static_cast<int>(out[5].values[0]), 51);
}

}  // namespace
}  // namespace lookout::app
