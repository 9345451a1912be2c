#include "lookout/app/grid_scoring.h"

#include "lookout/app/stereo_class_evidence.h"
#include "lookout/eval/statistics.h"

namespace lookout::app {
namespace {

eval::GridClassOfObjectClass GridClassTable() {
  eval::GridClassOfObjectClass table{};
  for (std::size_t i = 0; i < kAllObjectClasses.size(); ++i) {
    table[i] = static_cast<int>(GridClassOf(kAllObjectClasses[i]));
  }
  return table;
}

// The most probable class of each cell, window order.
std::vector<std::uint8_t> MostLikelyClass(const grid::ExtendedGrid& grid) {
  std::array<std::vector<float>, grid::kGridClassCount> pmf;
  for (std::size_t c = 0; c < pmf.size(); ++c) {
    pmf[c] = grid.layers().CopyInWindowOrder(grid.ids().class_pmf[c]);
  }
  std::vector<std::uint8_t> best(pmf[0].size(), 0);
  for (std::size_t i = 0; i < best.size(); ++i) {
    for (std::size_t c = 1; c < pmf.size(); ++c) {
      if (pmf[c][i] > pmf[best[i]][i]) best[i] = static_cast<std::uint8_t>(c);
    }
  }
  return best;
}

}  // namespace

eval::GridBelief BeliefOf(const grid::ExtendedGrid& grid) {
  const grid::GridLayers& layers = grid.layers();
  const grid::FilterLayerIds& ids = grid.ids();
  eval::GridBelief b;
  b.geometry = grid.geometry().WindowGeometry();
  b.occupancy = layers.CopyInWindowOrder(ids.occupancy);
  b.velocity_x_mps = layers.CopyInWindowOrder(ids.velocity_x_mps);
  b.velocity_y_mps = layers.CopyInWindowOrder(ids.velocity_y_mps);
  b.velocity_confidence = layers.CopyInWindowOrder(ids.velocity_confidence);
  return b;
}

GridScorer::GridScorer(const Pose2& world_from_odom, const std::vector<sim::Shape>& static_world,
                       double lidar_max_range_m)
    : odom_from_world_(world_from_odom.Inverse()),
      static_world_odom_(eval::ShapesIn(static_world, odom_from_world_)),
      lidar_max_range_m_(lidar_max_range_m),
      class_accuracy_(GridClassTable()) {}

void GridScorer::Observe(const GridStage& stage, const sim::TruthFrame& truth_world) {
  if (!stage.last_sensor_pose()) return;
  const sim::TruthFrame truth = eval::TruthFrameIn(truth_world, odom_from_world_);
  belief_ = BeliefOf(stage.grid());
  const sim::TruthRaster raster = sim::RasteriseTruth(truth, static_world_odom_, belief_.geometry);
  visibility_.Observe(truth, belief_.geometry);
  velocity_.AddFrame(belief_, raster);
  // The figure: velocities scored once an actor has been visible for a second, the
  // time any filter needs to learn a velocity from positions.
  velocity_after_1s_.AddFrame(belief_, raster, visibility_.AfterFirstVisible(1.0, truth.stamp));
  false_dynamic_.AddFrame(belief_, raster);
  brier_.AddFrame(belief_, raster,
                  eval::WithinRangeMask(belief_.geometry, stage.last_sensor_pose()->translation,
                                        lidar_max_range_m_));
  retention_.AddFrame(truth, belief_, raster);
  class_accuracy_.AddFrame(belief_.occupancy, MostLikelyClass(stage.grid()), raster, truth.actors);
}

void GridScorer::Report(std::map<std::string, double>& metrics, const GridStage& stage) const {
  auto put = [&metrics](const char* key, const std::optional<double>& value) {
    if (value) metrics[key] = *value;
  };
  put("grid.velocity_rmse_mps", velocity_.Value());
  put("grid.velocity_rmse_after_1s_mps", velocity_after_1s_.Value());
  put("grid.static_false_dynamic_rate", false_dynamic_.Value());
  put("grid.occupancy_brier", brier_.Value());
  put("grid.occluded_retention_s", retention_.Value());
  put("grid.class_accuracy", class_accuracy_.Value());
  if (!stage.cycle_ms().empty()) metrics["grid.cycle_ms_median"] = eval::Median(stage.cycle_ms());
}

}  // namespace lookout::app
