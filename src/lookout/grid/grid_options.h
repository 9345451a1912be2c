#pragma once

// Options of the grid module, one plain struct with defaults and units in the names. The
// filter stages (docs/extended-grid.md steps 2-8) add their fields here as they are built.

#include <string>

namespace lookout::grid {

// The inverse sensor model's probabilities, docs/extended-grid.md step 1. The paper uses 1 and
// 0; exact 0 and 1 make every later Bayes step degenerate (a cell once "certain" can never be
// revised), hence values strictly inside (0, 1).
struct InverseSensorModelOptions {
  double p_hit = 0.7;   // P(occupied | the cell holds a beam's impact)
  double p_free = 0.3;  // P(occupied | a beam crossed the cell before its impact)
  // A beam with no return (+inf, or a range at or beyond max range) says the space along it is
  // free, but it is weaker evidence than a return: it is also what a dropout (0.5 % of the
  // simulated beams), a dark or specular surface, or rain gives. So it marks cells free only up
  // to no_return_free_range_m, with p_free_no_return, between p_free and 0.5. Set the range to
  // 0 to ignore no-return beams altogether.
  double p_free_no_return = 0.4;
  double no_return_free_range_m = 30.0;
  // Two consecutive beams whose impacts lie at most this far apart can hit one surface: the
  // cells along the segment between the impacts are then hits too. Why: a wall seen at a
  // grazing angle is hit only where the beams land, and those points slide along the wall at
  // the ego's speed as it drives (at bearing theta the impact on a wall parallel to the motion
  // sits at x_ego + d / tan(theta)); without the segment the filter tracks that sliding pattern
  // and calls the wall dynamic. The price: a gap narrower than this between two objects at the
  // same depth is filled. The same distance decides when a beam without return lies in front
  // of one surface (a dropout, see inverse_sensor_model.h). 0 turns the segments off.
  double surface_gap_m = 1.0;
  // ...but two impacts within surface_gap_m are also one object's edge and another's face
  // behind it (a give-way sign 0.7 m in front of a walker at 18 m): one beam's last return on
  // the nearer, the next beam's on the farther, and the segment between them runs along the
  // beams. Joined, it was a line of hits across the depth jump that tied the walker to the
  // sign, and the grid read the walker as still as the sign (docs/grid.md, "A depth jump is no
  // surface"). So a segment is a surface when its impacts lie within Borges and Aldon's
  // breakpoint distance (core/breakpoint_distance.h: the spacing on a surface seen at
  // surface_incidence_rad, plus the range noise; the lidar segmentation's rule), or, for a
  // surface seen more obliquely (a wall along the road far ahead), when the surface goes on in
  // line past one of its ends: the previous beam's impact before the first, or the next
  // beam's after the second, within surface_gap_m and turned by at most surface_max_turn_rad.
  // A wall at a grazing angle is a run of collinear impacts; a depth jump turns by about a
  // right angle from the faces on either side of it.
  double surface_incidence_rad = 10.0 * 3.14159265358979323846 / 180.0;
  double surface_range_noise_m = 0.09;  // three sigmas of the scanner's range noise
  // 20 degrees: the direction of a 0.2 m segment between impacts with 2 cm of range noise
  // scatters by up to about 12 degrees.
  double surface_max_turn_rad = 0.35;

  // Throws lookout::InputError naming the first field out of range; `prefix` is the field path
  // of this struct ("grid.inverse_sensor_model").
  void Validate(const std::string& source, const std::string& prefix) const;
};

struct GridOptions {
  // 400 x 400 cells of 0.15 m: a 60 m x 60 m window around the ego (the benchmark size).
  double cell_size_m = 0.15;
  int width_cells = 400;   // along the odometry frame's x
  int height_cells = 400;  // along the odometry frame's y
  InverseSensorModelOptions inverse_sensor_model;

  // Throws lookout::InputError(source, 0, "grid.<field>", problem) for the first field out of
  // range. `source` names where the options came from (a file, a flag).
  void Validate(const std::string& source = "grid options") const;
};

// Upper bound on width_cells and height_cells: keeps every storage index within int range
// (16384^2 = 2^28 cells, 1 GiB per float layer, 2.4 km at 0.15 m).
inline constexpr int kMaxGridSideCells = 16384;

}  // namespace lookout::grid
