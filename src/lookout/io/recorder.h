#pragma once

// The recording of a run: every sensor message, the ground truth and the static world, as an
// MCAP file that Foxglove opens (docs/recording.md lists the topics). Stage outputs get their
// topics as the stages land.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/io/mcap_writer.h"
#include "lookout/io/message_json.h"
#include "lookout/io/replay_log.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/truth.h"

namespace lookout::io {

// Topic names, as docs/recording.md lists them.
namespace topics {
inline constexpr const char* kLidarScan = "/lidar/scan";
inline constexpr const char* kStereoObjects = "/stereo/objects";
inline constexpr const char* kOdometry = "/odometry";
inline constexpr const char* kTransforms = "/tf";
inline constexpr const char* kTruthEgo = "/truth/ego";
inline constexpr const char* kTruthActors = "/truth/actors";
inline constexpr const char* kTruthScene = "/truth/scene";
inline constexpr const char* kWorldStatic = "/world/static";
inline constexpr const char* kGridBelief = "/grid/belief";
inline constexpr const char* kLidarObjects = "/lidar/objects";
inline constexpr const char* kTracks = "/tracks";
inline constexpr const char* kRiskAssessment = "/risk/assessment";
inline constexpr const char* kRiskWarnings = "/risk/warnings";
inline constexpr const char* kTruthPeople = "/truth/people";
}  // namespace topics

// Frame names (docs/conventions.md).
namespace frames {
inline constexpr const char* kWorld = "world";
inline constexpr const char* kVehicle = "base_link";
inline constexpr const char* kLidar = "lidar";
inline constexpr const char* kStereo = "stereo";
inline constexpr const char* kOdom = "odom";
}  // namespace frames

class Recorder {
 public:
  // Writes PATH (through PATH.part; see McapWriter).
  explicit Recorder(const std::string& path, McapWriterOptions options = {});

  // Once, at the start: the static world and the sensor mounts.
  void WriteStaticWorld(TimeNs t, const std::vector<sim::Shape>& shapes);
  void WriteMounts(TimeNs t, const Pose2& lidar_mount, const Pose2& stereo_mount);

  void Write(const LidarScan& scan);
  void Write(const StereoFrame& frame);
  void Write(const EgoOdometry& odometry);
  // Truth: the actors, their scene drawing, the ego pose and the world -> base_link transform.
  void Write(const sim::TruthFrame& truth);
  // A transform on /tf: `child` in `parent`.
  void WriteTransform(TimeNs t, const char* parent, const char* child, const Pose2& pose);
  // The grid's belief as a foxglove.Grid in the odometry frame.
  void WriteGrid(TimeNs t, const GridGeometry& geometry, const std::vector<GridLayer8>& layers);

  // The lidar objects of one cycle as a foxglove.SceneUpdate in the vehicle frame.
  void Write(const LidarObjectFrame& objects);
  // People annotated on a real log's scan, as a foxglove.SceneUpdate in the vehicle frame.
  void Write(const PeopleFrame& people);

  // The confirmed tracks of one cycle as a foxglove.SceneUpdate in the odometry frame.
  void Write(TimeNs t, const std::vector<tracking::Track>& tracks);
  // One risk step, and a change of warning level.
  void Write(TimeNs t, const risk::EgoInput& ego, const risk::RiskAssessment& assessment,
             risk::WarningLevel level);
  void Write(const risk::WarningEvent& event);

  // Messages written per topic so far.
  const std::map<std::string, std::uint64_t>& message_counts() const { return counts_; }

  void Finish() { writer_.Finish(); }

 private:
  void Emit(std::uint16_t channel, const char* topic, TimeNs t, const nlohmann::json& message);

  McapWriter writer_;
  std::map<std::string, std::uint64_t> counts_;
  std::uint16_t lidar_ = 0, stereo_ = 0, odometry_ = 0, tf_ = 0, truth_ego_ = 0,
                truth_actors_ = 0, truth_scene_ = 0, world_ = 0, grid_ = 0, lidar_objects_ = 0,
                tracks_ = 0, risk_ = 0, warnings_ = 0, truth_people_ = 0;
};

}  // namespace lookout::io
