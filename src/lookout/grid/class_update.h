#pragma once

// Step 8 of docs/extended-grid.md: the class layer (not built in the paper).
//
// Per cell a pmf C(x, c) over {static, pedestrian, cyclist, vehicle, unknown}:
//   1. class mass moves with the occupancy: C_pred(i) = S(i) Cbar(i) + (1 - S(i)) uniform, with
//      Cbar the w_ji-weighted mean of the sources' pmfs (the carrying rule of step 6);
//   2. evidence, in occupied cells (O >= active_occupancy), multiplied in:
//      - speed, tempered by the velocity confidence (L^conf): a static cell cannot move, a
//        pedestrian rarely exceeds 3 m/s, a cyclist rarely exceeds 10 m/s and is rarely slower
//        than 2 m/s when it moves, a vehicle is any speed;
//      - extent: a local proxy for the size of the rigid cluster, the number of occupied cells
//        this scan hits in a (2r + 1)^2 box around the cell (r = extent_radius_cells): a
//        pedestrian's or a cyclist's visible surface fills few cells, a vehicle's or a wall's
//        many (ClassInputs::measured; all occupied cells when it is empty);
//      - stereo: class likelihoods of camera objects (polygons in the grid frame), when given;
//   3. mixed with a uniform floor (class_floor) so that no class is ever ruled out for good.
// The unknown class has a flat mediocre likelihood under every cue: it wins only without
// evidence. The class pmf sets sigma_C of the next cycle's prediction (step 2).

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "lookout/grid/filter_options.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {

// A camera object in the grid (odometry) frame: its footprint polygon (any orientation,
// non-self-intersecting) and the likelihood of each class given the camera's detection.
struct StereoClassRegion {
  std::vector<Eigen::Vector2d> polygon_m;
  ClassPmf likelihood{};
};

// The speed cue's likelihood of each class at `speed_mps`, before tempering.
ClassPmf SpeedClassLikelihood(double speed_mps);
// The extent cue's likelihood of each class given `occupied_cells` in the box.
ClassPmf ExtentClassLikelihood(double occupied_cells, double box_side_cells);

struct ClassInputs {
  std::span<const float> occupancy;
  std::span<const float> seen;
  std::span<const float> velocity_x_mps;
  std::span<const float> velocity_y_mps;
  std::span<const float> confidence;
  // This scan's P(occupied | z) (MeasurementGrid::p_occupied); empty: every occupied cell is
  // taken for seen.
  std::span<const float> measured;
};

// Updates `class_pmf` (one layer per class) on the update cells. `geometry` locates the stereo
// polygons. Parallel over the update cells; deterministic.
void UpdateClasses(const Associations& associations, const TargetIndex& targets,
                   const std::vector<UpdateCell>& cells, const ScrollingGridGeometry& geometry,
                   const WindowIndexer& indexer, const FilterOptions& options,
                   const ClassInputs& in, const std::vector<StereoClassRegion>& stereo,
                   const std::array<std::span<float>, kGridClassCount>& class_pmf);

}  // namespace lookout::grid
