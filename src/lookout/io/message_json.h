#pragma once

// Messages to and from the JSON of the recording (schemas in json_schemas.h). The encoding is
// deterministic: the same message always gives the same bytes (nlohmann::json prints doubles
// in their shortest round-trip form and objects with sorted keys).

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/core/messages.h"
#include "lookout/risk/risk_assessment.h"
#include "lookout/risk/warning_levels.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/truth.h"
#include "lookout/tracking/tracker.h"

namespace lookout::io {

nlohmann::json TimeToJson(TimeNs t);
// Throws lookout::InputError(source, 0, field, ...) on a malformed value.
TimeNs TimeFromJson(const nlohmann::json& j, const std::string& source);

nlohmann::json LidarScanToJson(const LidarScan& scan, const std::string& frame_id);
LidarScan LidarScanFromJson(const nlohmann::json& j, const std::string& source);

nlohmann::json StereoFrameToJson(const StereoFrame& frame, const std::string& frame_id);
StereoFrame StereoFrameFromJson(const nlohmann::json& j, const std::string& source);

nlohmann::json EgoOdometryToJson(const EgoOdometry& odometry);
EgoOdometry EgoOdometryFromJson(const nlohmann::json& j, const std::string& source);

nlohmann::json TruthFrameToJson(const sim::TruthFrame& frame);

// foxglove.FrameTransform of `child` in `parent`.
nlohmann::json FrameTransformToJson(TimeNs t, const std::string& parent, const std::string& child,
                                    const Pose2& pose);
// foxglove.PoseInFrame.
nlohmann::json PoseInFrameToJson(TimeNs t, const std::string& frame_id, const Pose2& pose);
// foxglove.SceneUpdate drawing the truth: actors as boxes or cylinders with their ids.
nlohmann::json TruthSceneToJson(const sim::TruthFrame& frame);
// foxglove.SceneUpdate drawing the static world: polygons as extruded outlines, circles as
// cylinders. Sent once; the entities have no lifetime.
nlohmann::json StaticWorldToJson(TimeNs t, const std::vector<sim::Shape>& shapes);

struct AnnotatedPerson;  // replay_log.h
// foxglove.SceneUpdate drawing people annotated on a real log in `frame_id`: a cylinder of a
// person's size at each, labelled with the annotation's id. Short-lived: an annotation holds for
// its scan only.
nlohmann::json PeopleSceneToJson(TimeNs t, const std::string& frame_id,
                                 std::span<const AnnotatedPerson> people);

// foxglove.SceneUpdate drawing lidar objects in `frame_id` (the vehicle frame): the extent as
// an outline coloured by the most likely class (faint when not dynamic), the front segment in
// white, the velocity as an arrow, a label "id class", and the object's numbers as metadata.
// Each update first deletes every entity of the topic (object ids hold within a frame only).
nlohmann::json LidarObjectsSceneToJson(const LidarObjectFrame& frame, const std::string& frame_id);

// foxglove.SceneUpdate drawing the confirmed tracks in `frame_id` (the odometry frame): a
// circle of the class's colour (dashed look: faint while coasting), the velocity as an arrow
// (0.5 s long), a label "id class", and the track's numbers as metadata. Each update first
// deletes every entity of the topic: a track that ended is gone.
nlohmann::json TracksSceneToJson(TimeNs t, const std::vector<tracking::Track>& tracks,
                                 const std::string& frame_id);

// lookout.RiskAssessment: the ego as the risk stage interpreted it, and per object its TTC,
// risk, collision probability and PET, the overall risk and the warning level (odometry frame).
nlohmann::json RiskAssessmentToJson(TimeNs t, const risk::EgoInput& ego,
                                    const risk::RiskAssessment& assessment,
                                    risk::WarningLevel level);

// lookout.WarningEvent: a change of warning level, the object and its TTC (null when none).
nlohmann::json WarningEventToJson(const risk::WarningEvent& event);

// One byte per cell of a grid layer, in GridGeometry order (row 0 at the lowest y).
struct GridLayer8 {
  std::string name;
  std::vector<std::uint8_t> values;
};
// foxglove.Grid of uint8 layers, interleaved cell by cell; `geometry.origin_m` is the lower-left
// corner of cell (0, 0) in `frame_id`. Every layer must have geometry.CellCount() values.
nlohmann::json GridToJson(TimeNs t, const std::string& frame_id, const GridGeometry& geometry,
                          const std::vector<GridLayer8>& layers);

}  // namespace lookout::io
