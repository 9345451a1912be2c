#include "lookout/grid/extended_grid.h"

#include <tbb/parallel_invoke.h>

#include <array>
#include <cassert>
#include <chrono>
#include <span>

#include "lookout/grid/association_prediction.h"
#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/interaction_constraints.h"
#include "lookout/grid/measurement_weighting.h"
#include "lookout/grid/occupancy_update.h"
#include "lookout/grid/rigidity_update.h"
#include "lookout/grid/velocity_update.h"

namespace lookout::grid {
namespace {

using Clock = std::chrono::steady_clock;

double MsBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

}  // namespace

ExtendedGrid::ExtendedGrid(const ScrollingGridGeometry& geometry, const FilterOptions& options)
    : options_(options), layers_(geometry), flow_(options.scan_flow) {
  options_.Validate();
  ids_ = AddFilterLayers(layers_);
  workspace_.Resize(geometry.CellCount());
}

void ExtendedGrid::Update(const MeasurementGrid& z, double dt_s) {
  assert(z.geometry.window_origin() == geometry().window_origin());
  assert(z.p_occupied.size() == geometry().CellCount());
  assert(dt_s > 0.0);
  const WindowIndexer indexer(geometry());

  const Clock::time_point start = Clock::now();
  // The scan pair's preparation and the hit counts (for the clusters' stage) are serial passes;
  // the sources' collection reads neither.
  Associations associations;
  std::vector<std::size_t> hits_now;
  tbb::parallel_invoke(
      [&] { flow_.Prepare(z); },
      [&] { associations = CollectSources(layers_, ids_, indexer, z, dt_s, options_); },
      [&] { hits_now = CountHitScans(z, layers_.Values(ids_.hit_scans)); });
  PredictFromSources(indexer, dt_s, geometry().cell_size_m(), options_, &flow_, associations);  // 2
  WeightByMeasurement(z, associations);                                                    // 3
  MapSources(associations, workspace_);
  // The target index and the update list are serial passes: each runs on one thread beside a
  // parallel stage that does not read it (the rigidity blur reads Pw and the source map; the
  // constraints read no update list), whose blocks go to whichever thread is free.
  TargetIndex targets;
  RigidityBlur blur;
  tbb::parallel_invoke(
      [&] { targets = BuildTargetIndex(associations, workspace_); },
      [&] { blur = BlurForRigidity(associations, indexer, workspace_, options_); });
  std::vector<UpdateCell> cells;
  tbb::parallel_invoke(
      [&] { cells = BuildUpdateList(targets, associations, z, workspace_); },
      [&] { ApplyConstraints(indexer, targets, workspace_, options_, blur, associations); });  // 4

  UpdateOccupancy(associations, targets, cells, z, options_, layers_.Values(ids_.occupancy),
                  layers_.Values(ids_.seen));                                              // 5
  // Velocity and links are carried only where mass moved (MovedCells).
  const std::span<const UpdateCell> moved = MovedCells(cells);
  UpdateVelocity(associations, targets, moved, dt_s, geometry().cell_size_m(), options_, z,
                 layers_.Values(ids_.occupancy), layers_.Values(ids_.seen),
                 VelocityLayers{layers_.Values(ids_.velocity_x_mps),
                                layers_.Values(ids_.velocity_y_mps),
                                layers_.Values(ids_.velocity_confidence)});                // 6
  std::array<std::span<float>, kNeighbourCount> rigidity;
  for (std::size_t d = 0; d < kNeighbourCount; ++d) rigidity[d] = layers_.Values(ids_.rigidity[d]);
  // The clusters' dynamic cells, a serial pass over the window, beside the links: it reads no
  // rigidity layer.
  std::vector<std::uint8_t> dynamic;
  tbb::parallel_invoke(
      [&] { UpdateRigidity(associations, targets, moved, indexer, workspace_, rigidity); },  // 7
      [&] { dynamic = ClusterMotionMask(layers_, ids_, flow_, options_.cluster_motion); });
  // Beyond the paper: each rigid cluster measured whole (cluster_motion.h).
  const ClusterStageOutput found =
      ApplyClusterMotion(layers_, ids_, z, flow_, dt_s, options_.known_confidence,
                         options_.cluster_motion, hits_now, dynamic);
  const Clock::time_point motion_done = Clock::now();
  // Beyond the paper: the bodies going into a shadow remembered, those in one carried whole
  // (hidden_bodies.h).
  hidden_.Update(layers_, ids_, z, dt_s, found, options_.cluster_motion.staying_min_hit_scans,
                 options_.hidden_bodies);
  const Clock::time_point hidden_done = Clock::now();
  std::array<std::span<float>, kGridClassCount> classes;
  for (std::size_t c = 0; c < kGridClassCount; ++c) classes[c] = layers_.Values(ids_.class_pmf[c]);
  UpdateClasses(associations, targets, cells, geometry(), indexer, options_,
                ClassInputs{layers_.Values(ids_.occupancy), layers_.Values(ids_.seen),
                            layers_.Values(ids_.velocity_x_mps),
                            layers_.Values(ids_.velocity_y_mps),
                            layers_.Values(ids_.velocity_confidence), z.p_occupied},
                stereo_, classes);                                                         // 8
  stereo_.clear();
  ClearSourceMap(associations, workspace_);
  flow_.Remember(z);
  const Clock::time_point done = Clock::now();

  stats_.motion_ms = MsBetween(start, motion_done);
  stats_.hidden_bodies_ms = MsBetween(motion_done, hidden_done);
  stats_.classes_ms = MsBetween(hidden_done, done);
  stats_.sources = associations.SourceCount();
  stats_.associations = associations.EntryCount();
  stats_.updated_cells = cells.size();
}

}  // namespace lookout::grid
