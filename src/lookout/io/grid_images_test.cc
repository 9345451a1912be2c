#include "lookout/io/grid_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "lookout/io/mcap_test_support.h"

namespace lookout::io {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

GridGeometry Geometry(int width, int height) {
  GridGeometry g;
  g.origin_m = Eigen::Vector2d(-1.0, 2.0);
  g.cell_size_m = 0.5;
  g.width = width;
  g.height = height;
  return g;
}

std::size_t Cell(const GridGeometry& g, int ix, int iy) {
  return static_cast<std::size_t>(g.LinearIndex({ix, iy}));
}

Rgb PixelRgb(const Image8& image, int x, int y) {
  const std::size_t o = image.Offset(x, y);
  return {image.pixels[o], image.pixels[o + 1], image.pixels[o + 2]};
}

TEST(GridImagesTest, OccupancyGrayNorthUp) {
  const GridGeometry g = Geometry(4, 3);
  std::vector<float> o(12, 0.5f);
  o[Cell(g, 0, 2)] = 1.0f;  // north-west corner cell
  o[Cell(g, 0, 0)] = 0.0f;  // south-west
  o[Cell(g, 3, 0)] = std::numeric_limits<float>::quiet_NaN();
  o[Cell(g, 3, 2)] = 2.0f;  // clamped
  const Image8 image = RenderOccupancy(g, o);
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 3);
  EXPECT_EQ(image.format, PixelFormat::kGray8);
  EXPECT_EQ(image.pixels[image.Offset(0, 0)], 0);    // top-left = max y: black
  EXPECT_EQ(image.pixels[image.Offset(0, 2)], 255);  // bottom-left: white
  EXPECT_EQ(image.pixels[image.Offset(1, 1)], 128);  // prior: mid grey
  EXPECT_EQ(image.pixels[image.Offset(3, 2)], 128);  // NaN: unknown
  EXPECT_EQ(image.pixels[image.Offset(3, 0)], 0);
}

TEST(GridImagesTest, SpeedColorHueWheelCounterClockwiseFromEast) {
  EXPECT_EQ(SpeedColor(1.0, 0.0, 1.0), (Rgb{255, 0, 0}));    // east: hue 0, red
  EXPECT_EQ(SpeedColor(0.0, 1.0, 1.0), (Rgb{128, 255, 0}));  // north: hue 90
  const double c = std::cos(2.0 * std::numbers::pi / 3.0);
  const double s = std::sin(2.0 * std::numbers::pi / 3.0);
  EXPECT_EQ(SpeedColor(c, s, 1.0), (Rgb{0, 255, 0}));         // hue 120: green
  EXPECT_EQ(SpeedColor(-1.0, 0.0, 1.0), (Rgb{0, 255, 255}));  // west: cyan
  EXPECT_EQ(SpeedColor(c, -s, 1.0), (Rgb{0, 0, 255}));        // hue 240: blue
  EXPECT_EQ(SpeedColor(0.0, -1.0, 1.0), (Rgb{128, 0, 255}));  // south: hue 270, violet
  EXPECT_EQ(SpeedColor(1.0, -1e-9, 1.0), (Rgb{255, 0, 0}));   // just below east: still red
  EXPECT_EQ(SpeedColor(1.0, 0.0, 0.5), (Rgb{128, 0, 0}));     // brightness scales value
  EXPECT_EQ(SpeedColor(0.0, 0.0, 0.0), (Rgb{0, 0, 0}));
  EXPECT_EQ(SpeedColor(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0), (Rgb{0, 0, 0}));
}

TEST(GridImagesTest, SpeedMapKnownField) {
  const GridGeometry g = Geometry(4, 2);
  std::vector<float> vx(8, 0.0f), vy(8, 0.0f);
  vx[Cell(g, 0, 0)] = 10.0f;   // east, half the max speed
  vy[Cell(g, 1, 0)] = 25.0f;   // north, saturated
  vx[Cell(g, 2, 0)] = -20.0f;  // west
  vy[Cell(g, 3, 0)] = -20.0f;  // south
  vx[Cell(g, 1, 1)] = 20.0f;   // north-east, hue 45
  vy[Cell(g, 1, 1)] = 20.0f;
  const Image8 image = RenderSpeedMap(g, vx, vy, {}, {});
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.format, PixelFormat::kRgb8);
  // Row iy = 0 is the bottom image row (y = 1).
  EXPECT_EQ(PixelRgb(image, 0, 1), (Rgb{128, 0, 0}));
  EXPECT_EQ(PixelRgb(image, 1, 1), (Rgb{128, 255, 0}));
  EXPECT_EQ(PixelRgb(image, 2, 1), (Rgb{0, 255, 255}));
  EXPECT_EQ(PixelRgb(image, 3, 1), (Rgb{128, 0, 255}));
  EXPECT_EQ(PixelRgb(image, 0, 0), (Rgb{0, 0, 0}));  // still: black
  EXPECT_EQ(PixelRgb(image, 1, 0), (Rgb{255, 191, 0}));
}

TEST(GridImagesTest, SpeedMapWeightsByOccupancyEvidenceAndConfidence) {
  const GridGeometry g = Geometry(3, 1);
  const std::vector<float> vx(3, 20.0f), vy(3, 0.0f);
  const std::vector<float> o = {0.75f, 0.5f, 1.0f};
  const std::vector<float> conf = {0.5f, 1.0f, 1.0f};
  const Image8 weighted = RenderSpeedMap(g, vx, vy, o, conf);
  EXPECT_EQ(PixelRgb(weighted, 0, 0), (Rgb{64, 0, 0}));  // 1 x 0.5 x 0.5
  EXPECT_EQ(PixelRgb(weighted, 1, 0), (Rgb{0, 0, 0}));   // unknown: black
  EXPECT_EQ(PixelRgb(weighted, 2, 0), (Rgb{255, 0, 0}));
  SpeedMapOptions plain;
  plain.weight_by_occupancy = false;
  plain.weight_by_confidence = false;
  const Image8 unweighted = RenderSpeedMap(g, vx, vy, o, conf, plain);
  EXPECT_EQ(PixelRgb(unweighted, 1, 0), (Rgb{255, 0, 0}));
}

TEST(GridImagesTest, ClassMapPaletteBackgroundAndFlip) {
  const GridGeometry g = Geometry(3, 2);
  std::vector<std::uint8_t> cls(6, kNoClass);
  cls[Cell(g, 0, 1)] = 1;  // pedestrian, top-left
  cls[Cell(g, 1, 1)] = 3;  // vehicle
  cls[Cell(g, 2, 1)] = 0;  // static
  cls[Cell(g, 0, 0)] = 2;  // cyclist
  cls[Cell(g, 1, 0)] = 4;  // unknown
  const Image8 image = RenderClassMap(g, cls);
  EXPECT_EQ(PixelRgb(image, 0, 0), kClassPalette[1]);
  EXPECT_EQ(PixelRgb(image, 1, 0), kClassPalette[3]);
  EXPECT_EQ(PixelRgb(image, 2, 0), kClassPalette[0]);
  EXPECT_EQ(PixelRgb(image, 0, 1), kClassPalette[2]);
  EXPECT_EQ(PixelRgb(image, 1, 1), kClassPalette[4]);
  EXPECT_EQ(PixelRgb(image, 2, 1), kClassBackground);
  // Occupancy gates the class: a free cell's argmax says nothing.
  std::vector<float> o(6, 0.9f);
  o[Cell(g, 0, 1)] = 0.5f;
  const Image8 gated = RenderClassMap(g, cls, o);
  EXPECT_EQ(PixelRgb(gated, 0, 0), kClassBackground);
  EXPECT_EQ(PixelRgb(gated, 1, 0), kClassPalette[3]);
  // The palette is distinct.
  for (int a = 0; a < kClassPaletteSize; ++a) {
    for (int b = a + 1; b < kClassPaletteSize; ++b) {
      EXPECT_NE(kClassPalette[static_cast<std::size_t>(a)],
                kClassPalette[static_cast<std::size_t>(b)]);
    }
  }
}

TEST(GridImagesTest, LayerSizeMismatchThrows) {
  const GridGeometry g = Geometry(3, 2);
  const std::vector<float> five(5, 0.0f), six(6, 0.0f);
  EXPECT_THROW(RenderOccupancy(g, five), std::invalid_argument);
  EXPECT_THROW(RenderSpeedMap(g, six, five, {}, {}), std::invalid_argument);
  EXPECT_THROW(RenderSpeedMap(g, six, six, five, {}), std::invalid_argument);
  EXPECT_THROW(RenderClassMap(g, std::vector<std::uint8_t>(5, 0)), std::invalid_argument);
  EXPECT_THROW(RenderOccupancy(Geometry(0, 2), {}), std::invalid_argument);
}

TEST(GridImagesTest, SpeedMapSurvivesAPngRoundTrip) {
  testing_support::TempDir dir;
  const GridGeometry g = Geometry(5, 4);
  std::vector<float> vx(20), vy(20);
  for (std::size_t i = 0; i < 20; ++i) {
    vx[i] = static_cast<float>(i) - 10.0f;
    vy[i] = 3.0f;
  }
  const Image8 image = RenderSpeedMap(g, vx, vy, {}, {});
  const std::string path = dir.File("speed.png");
  WritePng(path, image);
  const Image8 back = ReadPng(path);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 4);
}

}  // namespace
}  // namespace lookout::io
