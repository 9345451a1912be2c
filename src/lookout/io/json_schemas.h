#pragma once

// The JSON Schemas of the recorded topics (docs/recording.md). Where Foxglove has a schema
// that fits (LaserScan, FrameTransform, PoseInFrame, SceneUpdate, Grid) the recording uses its
// name and fields, so Foxglove draws the data; Lookout's own messages (stereo objects,
// odometry, ground truth) have schemas named lookout.*.

#include <string>

namespace lookout::io {

struct JsonSchema {
  std::string name;  // e.g. "foxglove.LaserScan"
  std::string text;  // the JSON Schema document, compact
};

JsonSchema FoxgloveLaserScanSchema();
JsonSchema FoxgloveFrameTransformSchema();
JsonSchema FoxglovePoseInFrameSchema();
JsonSchema FoxgloveSceneUpdateSchema();
JsonSchema FoxgloveGridSchema();
JsonSchema LookoutStereoFrameSchema();
JsonSchema LookoutEgoOdometrySchema();
JsonSchema LookoutTruthFrameSchema();
JsonSchema LookoutRiskAssessmentSchema();
JsonSchema LookoutWarningEventSchema();

}  // namespace lookout::io
