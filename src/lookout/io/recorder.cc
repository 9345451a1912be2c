#include "lookout/io/recorder.h"

#include "lookout/io/json_schemas.h"
#include "lookout/io/message_json.h"

namespace lookout::io {
namespace {

std::uint16_t AddJsonChannel(McapWriter& writer, const char* topic, const JsonSchema& schema) {
  const std::uint16_t schema_id = writer.AddSchema(schema.name, "jsonschema", schema.text);
  return writer.AddChannel(schema_id, topic, "json");
}

}  // namespace

Recorder::Recorder(const std::string& path, McapWriterOptions options)
    : writer_(path, std::move(options)) {
  // Schemas are shared by name: a schema used by two topics is written once.
  const JsonSchema transform = FoxgloveFrameTransformSchema();
  const JsonSchema scene = FoxgloveSceneUpdateSchema();
  const std::uint16_t transform_id =
      writer_.AddSchema(transform.name, "jsonschema", transform.text);
  const std::uint16_t scene_id = writer_.AddSchema(scene.name, "jsonschema", scene.text);

  lidar_ = AddJsonChannel(writer_, topics::kLidarScan, FoxgloveLaserScanSchema());
  stereo_ = AddJsonChannel(writer_, topics::kStereoObjects, LookoutStereoFrameSchema());
  odometry_ = AddJsonChannel(writer_, topics::kOdometry, LookoutEgoOdometrySchema());
  tf_ = writer_.AddChannel(transform_id, topics::kTransforms, "json");
  truth_ego_ = AddJsonChannel(writer_, topics::kTruthEgo, FoxglovePoseInFrameSchema());
  truth_actors_ = AddJsonChannel(writer_, topics::kTruthActors, LookoutTruthFrameSchema());
  truth_scene_ = writer_.AddChannel(scene_id, topics::kTruthScene, "json");
  world_ = writer_.AddChannel(scene_id, topics::kWorldStatic, "json");
  grid_ = AddJsonChannel(writer_, topics::kGridBelief, FoxgloveGridSchema());
  lidar_objects_ = writer_.AddChannel(scene_id, topics::kLidarObjects, "json");
  tracks_ = writer_.AddChannel(scene_id, topics::kTracks, "json");
  risk_ = AddJsonChannel(writer_, topics::kRiskAssessment, LookoutRiskAssessmentSchema());
  warnings_ = AddJsonChannel(writer_, topics::kRiskWarnings, LookoutWarningEventSchema());
  truth_people_ = writer_.AddChannel(scene_id, topics::kTruthPeople, "json");
}

void Recorder::Emit(std::uint16_t channel, const char* topic, TimeNs t,
                    const nlohmann::json& message) {
  writer_.Write(channel, t, t, message.dump());
  ++counts_[topic];
}

void Recorder::WriteStaticWorld(TimeNs t, const std::vector<sim::Shape>& shapes) {
  Emit(world_, topics::kWorldStatic, t, StaticWorldToJson(t, shapes));
}

void Recorder::WriteMounts(TimeNs t, const Pose2& lidar_mount, const Pose2& stereo_mount) {
  Emit(tf_, topics::kTransforms, t,
       FrameTransformToJson(t, frames::kVehicle, frames::kLidar, lidar_mount));
  Emit(tf_, topics::kTransforms, t,
       FrameTransformToJson(t, frames::kVehicle, frames::kStereo, stereo_mount));
}

void Recorder::Write(const LidarScan& scan) {
  Emit(lidar_, topics::kLidarScan, scan.stamp, LidarScanToJson(scan, frames::kLidar));
}

void Recorder::Write(const StereoFrame& frame) {
  Emit(stereo_, topics::kStereoObjects, frame.stamp, StereoFrameToJson(frame, frames::kStereo));
}

void Recorder::Write(const EgoOdometry& odometry) {
  Emit(odometry_, topics::kOdometry, odometry.stamp, EgoOdometryToJson(odometry));
}

void Recorder::Write(const sim::TruthFrame& truth) {
  const Pose2& ego = truth.ego.state.pose;
  Emit(truth_actors_, topics::kTruthActors, truth.stamp, TruthFrameToJson(truth));
  Emit(truth_scene_, topics::kTruthScene, truth.stamp, TruthSceneToJson(truth));
  Emit(truth_ego_, topics::kTruthEgo, truth.stamp,
       PoseInFrameToJson(truth.stamp, frames::kWorld, ego));
  Emit(tf_, topics::kTransforms, truth.stamp,
       FrameTransformToJson(truth.stamp, frames::kWorld, frames::kVehicle, ego));
}

void Recorder::Write(const LidarObjectFrame& objects) {
  Emit(lidar_objects_, topics::kLidarObjects, objects.stamp,
       LidarObjectsSceneToJson(objects, frames::kVehicle));
}

void Recorder::Write(TimeNs t, const std::vector<tracking::Track>& tracks) {
  Emit(tracks_, topics::kTracks, t, TracksSceneToJson(t, tracks, frames::kOdom));
}

void Recorder::Write(TimeNs t, const risk::EgoInput& ego, const risk::RiskAssessment& assessment,
                     risk::WarningLevel level) {
  Emit(risk_, topics::kRiskAssessment, t, RiskAssessmentToJson(t, ego, assessment, level));
}

void Recorder::Write(const risk::WarningEvent& event) {
  Emit(warnings_, topics::kRiskWarnings, event.stamp, WarningEventToJson(event));
}

void Recorder::Write(const PeopleFrame& people) {
  Emit(truth_people_, topics::kTruthPeople, people.stamp,
       PeopleSceneToJson(people.stamp, frames::kVehicle, people.people));
}

void Recorder::WriteTransform(TimeNs t, const char* parent, const char* child, const Pose2& pose) {
  Emit(tf_, topics::kTransforms, t, FrameTransformToJson(t, parent, child, pose));
}

void Recorder::WriteGrid(TimeNs t, const GridGeometry& geometry,
                         const std::vector<GridLayer8>& layers) {
  Emit(grid_, topics::kGridBelief, t, GridToJson(t, frames::kOdom, geometry, layers));
}

}  // namespace lookout::io
