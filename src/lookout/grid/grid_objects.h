#pragma once

// Objects out of the extended grid's cycle (docs/extended-grid.md "What comes out"; the grid
// issue's item 5; docs/grid.md "Objects out of the grid"): rigid clusters of dynamic cells
// become LidarObjects, the dynamic-object list the fusion and tracking chain of seed 004 takes
// from the lidar. Three named stages, each a pure function of the grid's layers:
//   1. DynamicCellMask: a cell is dynamic when it is believed occupied (O > min_occupancy) and
//      moves (|V| > min_speed_mps with confidence >= min_velocity_confidence);
//   2. FindRigidClusters: connected components of dynamic cells over the rigidity links of
//      eq. 15 (8-neighbourhood, link > min_link), by breadth-first search in window order;
//      clusters of fewer than min_cells cells are dropped;
//   3. DescribeCluster: centroid, front segment, extent, velocity and class of one cluster,
//      each with its uncertainty, in the vehicle frame.
// The paper suggests k-means outside the cycle; connected components over D need no number of
// clusters and no seeds, and D already says which neighbours move as one.
//
// Deterministic: one thread, cells visited in window order (row by row from the window's
// lower-left cell), neighbours in kNeighbourOffsets order; ids number the clusters in the order
// of their first cell. The extraction costs one pass over the window (docs/PERFORMANCE.md).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/grid/extended_grid.h"

namespace lookout::grid {

struct GridObjectOptions {
  // Believed occupied: O > min_occupancy. The filter's own "worth moving" level (0.6): a cell
  // at the 0.5 prior, or a free cell a little above it, is not an object.
  double min_occupancy = 0.6;
  // Moving: |V| > min_speed_mps (the contract's 0.5 m/s of "moving") with a velocity confidence
  // of at least min_velocity_confidence (the grid metrics' "with confidence": the grid holds
  // the velocity more likely than not; newly seen occupancy has confidence 0).
  double min_speed_mps = 0.5;
  double min_velocity_confidence = 0.5;
  // Linked: D > min_link between two dynamic 8-neighbours, D taken as the larger of the two
  // cells' links to each other (the links are carried with the mass, so the two may differ).
  // D = sum_a P(a) P'(a) is at most sum_a P(a)^2: about 0.3 for the sharp pmfs of a tracked
  // cell, 0.01-0.05 for the coarse window of newly seen occupancy; 0.05 keeps the tracked links
  // and cuts most untracked ones.
  double min_link = 0.05;
  // Clusters of fewer cells are dropped: 3 cells of 0.15 m is less than a pedestrian's
  // footprint seen by a scan (a leg is 1-2 cells); single dynamic cells are mostly the static
  // world's false-dynamic noise (docs/grid.md, known fault 1).
  int min_cells = 3;

  // Throws lookout::InputError(source, 0, "grid.objects.<field>", ...) for the first field
  // out of range.
  void Validate(const std::string& source = "grid object options") const;
};

// Stage 1: 1 for dynamic cells, 0 otherwise, in storage order (GridLayers' order).
std::vector<std::uint8_t> DynamicCellMask(const GridLayers& layers, const FilterLayerIds& ids,
                                          const GridObjectOptions& options);

// One rigid cluster: its cells as storage indices, in the order the search reached them.
struct GridCluster {
  std::vector<std::size_t> cells;
};

// Stage 2: the clusters of `dynamic` (DynamicCellMask) of at least options.min_cells cells,
// in window order of their first cell.
std::vector<GridCluster> FindRigidClusters(const GridLayers& layers, const FilterLayerIds& ids,
                                           const std::vector<std::uint8_t>& dynamic,
                                           const GridObjectOptions& options);

// Where the grid and the lidar were at the cycle the objects come from.
struct ObjectFrameContext {
  TimeNs stamp = 0;
  Pose2 ego_pose;     // vehicle frame in the odometry frame (the grid's frame)
  Pose2 lidar_mount;  // lidar frame in the vehicle frame
  double dt_s = 0.08; // the cycle's time step: one cell per cycle is cell_size / dt_s m/s
};

// Stage 3: one cluster as a LidarObject in the vehicle frame (messages.h), id 0. Definitions:
//   - centroid: occupancy-weighted mean of the cells' centres; range and bearing of it from the
//     lidar's origin, bearing in the lidar frame;
//   - front segment: the cells at the cluster's two extreme bearings as seen from the lidar
//     (the nearest one where several share a bearing): the ends of what the laser sees of the
//     object; point_m is its middle, with covariance (cell^2 / 12) I (a cell's quantisation)
//     plus the cells' occupancy-weighted spatial covariance over their effective count
//     n_eff = (sum O)^2 / sum O^2 (how well the cluster pins a position down);
//   - extent: the minimum-area rectangle about the cells' squares (min_area_rectangle.h), yaw
//     along its length, turned to point along the velocity when the object moves;
//   - velocity: occupancy-weighted mean of the cells' velocities; covariance the weighted spread
//     over n_eff, plus (cell / dt)^2 / 12 I: the velocities come from displacements of whole
//     cells, a quantisation the cells of one body share, so it does not average out;
//   - class: occupancy-weighted mean of the cells' pmfs, the grid's five classes mapped onto
//     ObjectClass: pedestrian, cyclist as such, vehicle -> car, static and unknown -> unknown
//     (a moving cluster the grid calls static is an object of unknown kind); truck and pole 0;
//   - dynamic: |velocity| > options.min_speed_mps.
LidarObject DescribeCluster(const ExtendedGrid& grid, const GridCluster& cluster,
                            const ObjectFrameContext& context, const GridObjectOptions& options);

// The three stages: every rigid cluster of the grid's current state as a LidarObjectFrame,
// ids 0, 1, ... in cluster order.
LidarObjectFrame ExtractGridObjects(const ExtendedGrid& grid, const ObjectFrameContext& context,
                                    const GridObjectOptions& options);

// The grid's class pmf as LidarObject::class_pmf (see DescribeCluster), normalised.
std::array<double, kAllObjectClasses.size()> ToObjectClassPmf(
    const std::array<double, kGridClassCount>& grid_pmf);

}  // namespace lookout::grid
