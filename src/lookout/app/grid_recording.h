#pragma once

// The extended grid's belief as the recording's uint8 layers (`/grid/belief`, docs/recording.md;
// the grid issue's item 7): occupancy, the speed map of the paper's Fig. 6 as two layers (speed
// and direction, so that a viewer can draw hue = direction, brightness = speed), the velocity
// confidence, the class layer (most likely class and its probability), the rigidity layer
// (the strongest of a cell's eight links) and the cells of the bodies carried through a shadow
// (grid/hidden_bodies.h). Cells in window order (GridGeometry order).

#include <vector>

#include "lookout/grid/extended_grid.h"
#include "lookout/io/message_json.h"

namespace lookout::app {

// Speeds at or above this are recorded as 255.
inline constexpr double kRecordedFullSpeed_mps = 20.0;

// The byte of a velocity's direction: atan2(vy, vx) over [-pi, pi) as 0..255 (0 = along -x,
// 128 = along +x, counter-clockwise), 0 for a zero velocity. Pure.
std::uint8_t DirectionByte(double vx_mps, double vy_mps);

// The layers, in this order: occupancy (O x 255), speed (0-20 m/s as 0-255), direction
// (DirectionByte), confidence (x 255), class (the index of the most likely class,
// grid::GridClass order), class_probability (its probability x 255), rigidity (max over the
// eight links of D, x 255), hidden (255 on a cell a carried hidden body holds, else 0).
std::vector<io::GridLayer8> GridLayersToRecord(const grid::ExtendedGrid& grid);

}  // namespace lookout::app
