#pragma once

// The extended grid as a pipeline stage: odometry feeds the ego pose (dead reckoning, through
// the EgoPoseSource interface the lidar chain will also implement), and each lidar scan runs
// one cycle: scroll the window to the ego, compute the inverse sensor model, update the filter
// (docs/extended-grid.md steps 1-8).

#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/app/stage.h"
#include "lookout/core/dead_reckoning.h"
#include "lookout/grid/extended_grid.h"
#include "lookout/grid/grid_options.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::app {

class GridStage : public Stage {
 public:
  explicit GridStage(const grid::GridOptions& grid_options = {},
                     const grid::FilterOptions& filter_options = {});

  void OnOdometry(const EgoOdometry& odometry) override;
  void OnLidar(const LidarScan& scan) override;

  const grid::ExtendedGrid& grid() const { return grid_; }
  // The lidar's pose in the odometry frame at the last cycle; nullopt before the first.
  const std::optional<Pose2>& last_sensor_pose() const { return last_sensor_pose_; }
  // Wall time of each grid cycle (ISM and filter), ms.
  const std::vector<double>& cycle_ms() const { return cycle_ms_; }
  // Scans that could not be used: no ego pose for their time (odometry missing or stopped).
  std::int64_t skipped_scans() const { return skipped_scans_; }

 private:
  grid::GridOptions options_;
  DeadReckoning ego_;
  grid::ExtendedGrid grid_;
  grid::MeasurementGrid measurement_;
  std::optional<TimeNs> last_stamp_;
  std::optional<Pose2> last_sensor_pose_;
  std::vector<double> cycle_ms_;
  std::int64_t skipped_scans_ = 0;
};

}  // namespace lookout::app
