#pragma once

// Pictures of the extended grid's belief maps (docs/extended-grid.md, "what comes out"): the
// occupancy, the paper's Fig. 6 speed map, and the class map. One pixel per cell.
//
// Input: layers in window order over a GridGeometry (index iy * width + ix, as
// ScrollingGridGeometry::WindowGeometry and GridLayers::CopyInWindowOrder give), x east and y
// north in the odometry frame. Output: image row 0 is the top, i.e. the cells of the largest
// iy (north up, east right), pixel (x, y) = cell (ix = x, iy = height - 1 - y).
//
// Every function throws std::invalid_argument when a non-empty layer does not hold
// geometry.CellCount() values or the geometry is empty.

#include <array>
#include <cstdint>
#include <span>

#include "lookout/core/grid_geometry.h"
#include "lookout/io/png_writer.h"

namespace lookout::io {

// (a) Occupancy as grayscale: gray = round(255 (1 - O)), so O = 1 is black, O = 0 white and the
// 0.5 prior mid grey (128). O is clamped to [0, 1]; NaN is drawn as unknown (0.5).
Image8 RenderOccupancy(const GridGeometry& geometry, std::span<const float> occupancy);

struct SpeedMapOptions {
  // Brightness saturates here: 20 m/s, the fastest car the grid must track (issue 3).
  double max_speed_mps = 20.0;
  // Weights that darken what the grid does not believe: the occupancy evidence max(0, 2 O - 1)
  // (free and unknown cells are black, a certain cell full bright) and the velocity confidence
  // (a newly born cell, confidence 0, is black). Each is used when enabled and its layer given.
  bool weight_by_occupancy = true;
  bool weight_by_confidence = true;
};

// (b) The speed map of the paper's Fig. 6, in HSV with full saturation:
//   hue = direction of the velocity, counter-clockwise from east as the frame's yaw:
//         east (+x) 0 deg red, north (+y) 90 deg chartreuse (128, 255, 0), west 180 deg cyan,
//         south 270 deg violet (128, 0, 255); hue = atan2(vy, vx) in [0, 360);
//   value (brightness) = min(speed / max_speed_mps, 1) x the weights of SpeedMapOptions.
// Still cells (speed 0) and, when weighted, empty cells are black. Occupancy and confidence may
// be empty spans (that weight is then not applied).
Image8 RenderSpeedMap(const GridGeometry& geometry, std::span<const float> velocity_x_mps,
                      std::span<const float> velocity_y_mps, std::span<const float> occupancy,
                      std::span<const float> velocity_confidence,
                      const SpeedMapOptions& options = {});

// The HSV colour of the speed map for one velocity at brightness `value` in [0, 1]; exposed for
// legends and tests.
std::array<std::uint8_t, 3> SpeedColor(double velocity_x_mps, double velocity_y_mps, double value);

// (c) The class map: per cell the index of its most probable class, in the grid's class-layer
// order (grid::GridClass): 0 static, 1 pedestrian, 2 cyclist, 3 vehicle, 4 unknown. Any other
// index (kNoClass) is drawn as the background. When `occupancy` is given, cells with O <= 0.5
// (free or unknown: their class says nothing) are background too.
inline constexpr std::uint8_t kNoClass = 255;
inline constexpr int kClassPaletteSize = 5;
// Fixed palette, RGB, chosen to stay distinct for common colour-vision deficiencies.
inline constexpr std::array<std::array<std::uint8_t, 3>, kClassPaletteSize> kClassPalette = {{
    {160, 160, 160},  // static: grey
    {230, 25, 75},    // pedestrian: red
    {255, 225, 25},   // cyclist: yellow
    {0, 130, 200},    // vehicle: blue
    {145, 30, 180},   // unknown: purple
}};
inline constexpr std::array<std::uint8_t, 3> kClassBackground = {0, 0, 0};

Image8 RenderClassMap(const GridGeometry& geometry, std::span<const std::uint8_t> class_index,
                      std::span<const float> occupancy = {});

}  // namespace lookout::io
