#pragma once

// The processing stages and how messages reach them. The runner (runner.h) owns the clock and
// calls the pipeline with every sensor message in timestamp order; each stage sees each
// message at its own sensor's rate. A lidar scan closes a cycle: the stages that run per scan
// (the grid now; objects, fusion, tracking and risk as they land) run then, and the runner
// times that whole step.

#include <memory>
#include <optional>
#include <vector>

#include "lookout/app/grid_stage.h"
#include "lookout/app/lidar_chain_stage.h"
#include "lookout/app/risk_stage.h"
#include "lookout/app/stage.h"
#include "lookout/app/tracking_stage.h"
#include "lookout/core/messages.h"
#include "lookout/fusion/fusion_engine.h"
#include "lookout/lidar/lidar_chain_options.h"

namespace lookout::app {

// Where the grid's ego pose comes from (docs/lidar-chain.md compares them).
enum class EgoPoseMode {
  kLidarLocalisation,  // the lidar chain's particle filter (needs lidar_chain)
  kDeadReckoning,      // the grid's own integration of the wheel odometry
};

// Which lidar objects the pipeline fuses, scores and records (docs/lidar-chain.md).
enum class LidarObjectSource {
  kGrid,          // the grid's rigid clusters of dynamic cells (needs grid)
  kSegmentation,  // the lidar chain's scan segmentation (needs lidar_chain)
};

struct PipelineOptions {
  bool grid = true;  // the extended grid (docs/extended-grid.md), with its objects
  grid::FilterOptions grid_filter;  // its filter (grid/filter_options.h)
  // How the grid's rigid clusters become lidar objects (grid/grid_objects.h).
  grid::GridObjectOptions grid_objects;
  // The camera's classes as evidence for the grid's class layer (app/stereo_class_evidence.h);
  // stereo_class.enabled = false leaves the class layer to the grid's own cues.
  StereoClassEvidenceOptions stereo_class;
  // The lidar chain (docs/lidar-chain.md): localisation, moving and static hits,
  // segmentation. Runs before the grid on every scan.
  bool lidar_chain = true;
  lidar::LidarChainOptions lidar_chain_options;
  // Dead reckoning by default: on the catalogue the grid's velocities are better with its
  // smoother scan-to-scan motion (docs/lidar-chain.md).
  EgoPoseMode ego_pose = EgoPoseMode::kDeadReckoning;
  // The segmentation's objects by default: with them the tracker and the risk stage reach
  // their goals on more scenarios (docs/lidar-chain.md, 2026-12-03); the grid's objects do not
  // yet hold fast vehicles (docs/grid.md).
  LidarObjectSource lidar_objects = LidarObjectSource::kSegmentation;
  // Lidar/stereo fusion of each cycle's lidar objects with the latest stereo frame
  // (docs/fusion.md); needs a source of lidar objects.
  bool fusion = true;
  fusion::FusionOptions fusion_options;
  // Tracking of the fused objects in the odometry frame (app/tracking_stage.h); needs fusion.
  bool tracking = true;
  TrackingStageOptions tracking_options;
  // Collision risk and warnings from the tracks (app/risk_stage.h); needs tracking.
  bool risk = true;
  RiskStageOptions risk_options;

  // Throws lookout::InputError naming the option when a choice needs a part that is off.
  void Validate() const;
};

class Pipeline {
 public:
  Pipeline() = default;  // no built-in stage: tests assemble their own with Add()
  explicit Pipeline(const PipelineOptions& options);  // the built-in stages the options name

  // Any stage, run after the built-in ones (tests add probes this way).
  void Add(std::unique_ptr<Stage> stage) { stages_.push_back(std::move(stage)); }
  std::size_t size() const { return stages_.size(); }

  // The grid stage, or nullptr when the pipeline runs without it.
  const GridStage* grid() const { return grid_; }
  // The lidar chain stage, or nullptr when the pipeline runs without it.
  const LidarChainStage* lidar_chain() const { return lidar_chain_; }
  // The lidar objects of the last cycle (vehicle frame) from the source the options chose, or
  // nullptr before the first cycle or without that source. Check its stamp: a scan the source
  // had to skip leaves the previous frame here.
  const LidarObjectFrame* lidar_objects() const;
  // The chosen source of lidar objects, and whether it runs.
  LidarObjectSource object_source() const { return object_source_; }
  bool lidar_objects_available() const;
  // The fused objects of the last cycle whose lidar objects were fused, or nullptr; and the
  // engine (its statistics, the stereo objects it used). nullptr without fusion.
  const fusion::FusedObjectFrame* fused_objects() const {
    return fused_ ? &*fused_ : nullptr;
  }
  const fusion::FusionEngine* fusion() const { return fusion_ ? &*fusion_ : nullptr; }
  // The tracking and risk stages, or nullptr without them. Both run on each fused frame; check
  // their last_stamp() against the scan's.
  const TrackingStage* tracking() const { return tracking_ ? &*tracking_ : nullptr; }
  const RiskStage* risk() const { return risk_ ? &*risk_ : nullptr; }
  // The ego's intended route, odometry frame (RiskStage::SetRoute); ignored without risk.
  void SetEgoRoute(std::vector<Eigen::Vector2d> route_m);
  // The carriageways of the ego's map, odometry frame (RiskStage::SetCarriageways); ignored
  // without risk.
  void SetCarriageways(risk::Carriageways roads_m);
  // The buildings of the ego's map, odometry frame (TrackingStage::SetBuildings); ignored
  // without tracking.
  void SetBuildings(BuildingOutlines buildings_m);

  void OnOdometry(const EgoOdometry& odometry);
  void OnStereo(const StereoFrame& frame);
  void OnLidar(const LidarScan& scan);

 private:
  std::vector<std::unique_ptr<Stage>> stages_;
  const GridStage* grid_ = nullptr;  // owned by stages_
  const LidarChainStage* lidar_chain_ = nullptr;  // owned by stages_
  LidarObjectSource object_source_ = LidarObjectSource::kSegmentation;
  std::optional<fusion::FusionEngine> fusion_;
  StereoFrame latest_stereo_;
  bool stereo_received_ = false;
  std::optional<fusion::FusedObjectFrame> fused_;
  std::optional<TrackingStage> tracking_;
  std::optional<RiskStage> risk_;
};

}  // namespace lookout::app
