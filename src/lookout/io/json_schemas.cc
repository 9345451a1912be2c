#include "lookout/io/json_schemas.h"

#include <nlohmann/json.hpp>

namespace lookout::io {
namespace {

using nlohmann::json;

json Number() { return {{"type", "number"}}; }
json Integer() { return {{"type", "integer"}}; }
json String() { return {{"type", "string"}}; }
json Boolean() { return {{"type", "boolean"}}; }
json ArrayOf(json items) { return {{"type", "array"}, {"items", std::move(items)}}; }

json Object(json properties, const std::string& description = "") {
  json o = {{"type", "object"}, {"properties", std::move(properties)}};
  if (!description.empty()) o["description"] = description;
  return o;
}

json Time() {
  return Object({{"sec", {{"type", "integer"}, {"minimum", 0}}},
                 {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}},
                "seconds and nanoseconds since the start of the scenario or log");
}
json Duration() { return Object({{"sec", Integer()}, {"nsec", Integer()}}); }
json Vector3() { return Object({{"x", Number()}, {"y", Number()}, {"z", Number()}}); }
json Vector2() { return Object({{"x", Number()}, {"y", Number()}}); }
json Quaternion() {
  return Object({{"x", Number()}, {"y", Number()}, {"z", Number()}, {"w", Number()}});
}
json Pose() { return Object({{"position", Vector3()}, {"orientation", Quaternion()}}); }
json Color() {
  return Object({{"r", Number()}, {"g", Number()}, {"b", Number()}, {"a", Number()}});
}

JsonSchema Make(const std::string& name, const std::string& description, json properties) {
  json schema = Object(std::move(properties), description);
  schema["title"] = name;
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  return {name, schema.dump()};
}

}  // namespace

JsonSchema FoxgloveLaserScanSchema() {
  return Make("foxglove.LaserScan",
              "A single scan from a planar laser range-finder. A beam with no return "
              "(+infinity in REP 117) is written as null, since JSON has no infinity. "
              "range_max and angle_increment are Lookout's additions.",
              {{"timestamp", Time()},
               {"frame_id", String()},
               {"pose", Pose()},
               {"start_angle", Number()},
               {"end_angle", Number()},
               {"ranges", ArrayOf({{"type", json::array({"number", "null"})}})},
               {"intensities", ArrayOf(Number())},
               {"range_max", Number()},
               {"angle_increment", Number()}});
}

JsonSchema FoxgloveFrameTransformSchema() {
  return Make("foxglove.FrameTransform", "A transform between two reference frames in 3D space",
              {{"timestamp", Time()},
               {"parent_frame_id", String()},
               {"child_frame_id", String()},
               {"translation", Vector3()},
               {"rotation", Quaternion()}});
}

JsonSchema FoxglovePoseInFrameSchema() {
  return Make("foxglove.PoseInFrame", "A timestamped pose for an object or reference frame",
              {{"timestamp", Time()}, {"frame_id", String()}, {"pose", Pose()}});
}

JsonSchema FoxgloveSceneUpdateSchema() {
  const json cube = Object({{"pose", Pose()}, {"size", Vector3()}, {"color", Color()}});
  const json cylinder = Object({{"pose", Pose()},
                                {"size", Vector3()},
                                {"bottom_scale", Number()},
                                {"top_scale", Number()},
                                {"color", Color()}});
  const json line = Object({{"type", {{"type", "integer"}, {"enum", {0, 1, 2}}}},
                            {"pose", Pose()},
                            {"thickness", Number()},
                            {"scale_invariant", Boolean()},
                            {"points", ArrayOf(Vector3())},
                            {"color", Color()},
                            {"colors", ArrayOf(Color())},
                            {"indices", ArrayOf(Integer())}});
  const json arrow = Object({{"pose", Pose()},
                             {"shaft_length", Number()},
                             {"shaft_diameter", Number()},
                             {"head_length", Number()},
                             {"head_diameter", Number()},
                             {"color", Color()}});
  const json text = Object({{"pose", Pose()},
                            {"billboard", Boolean()},
                            {"font_size", Number()},
                            {"scale_invariant", Boolean()},
                            {"color", Color()},
                            {"text", String()}});
  const json entity =
      Object({{"timestamp", Time()},
              {"frame_id", String()},
              {"id", String()},
              {"lifetime", Duration()},
              {"frame_locked", Boolean()},
              {"metadata", ArrayOf(Object({{"key", String()}, {"value", String()}}))},
              {"arrows", ArrayOf(arrow)},
              {"cubes", ArrayOf(cube)},
              {"spheres", ArrayOf(Object({}))},
              {"cylinders", ArrayOf(cylinder)},
              {"lines", ArrayOf(line)},
              {"triangles", ArrayOf(Object({}))},
              {"texts", ArrayOf(text)},
              {"models", ArrayOf(Object({}))}});
  const json deletion = Object(
      {{"timestamp", Time()}, {"type", {{"type", "integer"}, {"enum", {0, 1}}}}, {"id", String()}});
  return Make("foxglove.SceneUpdate", "An update to the entities displayed in a 3D scene",
              {{"deletions", ArrayOf(deletion)}, {"entities", ArrayOf(entity)}});
}

JsonSchema FoxgloveGridSchema() {
  const json field = Object({{"name", String()}, {"offset", Integer()}, {"type", Integer()}});
  return Make("foxglove.Grid", "A 2D grid of data; data is base64 in JSON",
              {{"timestamp", Time()},
               {"frame_id", String()},
               {"pose", Pose()},
               {"column_count", Integer()},
               {"cell_size", Vector2()},
               {"row_stride", Integer()},
               {"cell_stride", Integer()},
               {"fields", ArrayOf(field)},
               {"data", {{"type", "string"}, {"contentEncoding", "base64"}}}});
}

JsonSchema LookoutStereoFrameSchema() {
  const json object = Object(
      {{"id", Integer()},
       {"class", {{"type", "string"},
                  {"enum", {"unknown", "pedestrian", "cyclist", "car", "truck", "pole"}}}},
       {"center", Vector2()},
       {"yaw", Number()},
       {"length", Number()},
       {"width", Number()},
       {"speed_longitudinal", Number()},
       {"speed_lateral", Number()},
       {"center_covariance", {{"type", "array"}, {"items", Number()}, {"minItems", 4},
                              {"maxItems", 4}, {"description", "row-major 2x2, m^2"}}},
       {"yaw_variance", Number()},
       {"speed_variance", Number()},
       {"history", Integer()}});
  return Make("lookout.StereoFrame",
              "Objects from the stereo camera, in the camera frame (x forward, y left; m, rad, "
              "m/s); mount is the camera's pose in the vehicle frame",
              {{"timestamp", Time()},
               {"frame_id", String()},
               {"mount", Object({{"x", Number()}, {"y", Number()}, {"yaw", Number()}})},
               {"objects", ArrayOf(object)}});
}

JsonSchema LookoutEgoOdometrySchema() {
  return Make("lookout.EgoOdometry", "Wheel speed (m/s) and yaw rate (rad/s) of the ego vehicle",
              {{"timestamp", Time()}, {"speed", Number()}, {"yaw_rate", Number()}});
}

JsonSchema LookoutRiskAssessmentSchema() {
  const json nullable = {{"type", json::array({"number", "null"})}};
  const json ego = Object({{"x", Number()},
                           {"y", Number()},
                           {"yaw", Number()},
                           {"speed", Number()},
                           {"acceleration", Number()},
                           {"yaw_rate", Number()},
                           {"route", {{"type", "boolean"}}}},
                          "the ego as the risk stage interpreted it, odometry frame: m, rad, m/s, "
                          "m/s^2, rad/s; route: predicted along its intended route");
  const json object = Object({{"id", Number()},
                              {"ttc", nullable},
                              {"risk", Number()},
                              {"collision_probability", Number()},
                              {"pet", nullable}},
                             "a confirmed track: TTC and PET in s (null: none in the horizon)");
  return Make("lookout.RiskAssessment",
              "One risk step (seed 004 VIII): per track its TTC, risk indicator, collision "
              "probability and post-encroachment time; the risk of the earliest potential "
              "collision and the warning level",
              {{"timestamp", Time()},
               {"ego", ego},
               {"objects", ArrayOf(object)},
               {"earliest", nullable},
               {"risk", Number()},
               {"dropped", Number()},
               {"level", String()}});
}

JsonSchema LookoutWarningEventSchema() {
  const json nullable = {{"type", json::array({"number", "null"})}};
  return Make("lookout.WarningEvent",
              "A change of the warning level (none, information, warning), naming the track of "
              "the earliest potential collision and its TTC in s",
              {{"timestamp", Time()},
               {"level", String()},
               {"object_id", nullable},
               {"ttc", nullable}});
}

JsonSchema LookoutTruthFrameSchema() {
  const json state = Object({{"x", Number()},
                             {"y", Number()},
                             {"yaw", Number()},
                             {"speed", Number()},
                             {"yaw_rate", Number()},
                             {"acceleration", Number()},
                             {"vx", Number()},
                             {"vy", Number()}},
                            "world frame: m, rad, m/s, rad/s, m/s^2");
  const json footprint = Object({{"polygon", ArrayOf(ArrayOf(Number()))},
                                 {"circle", Object({{"x", Number()}, {"y", Number()},
                                                    {"radius", Number()}})}},
                                "either a polygon ring [[x, y], ...] or a circle");
  const json actor = Object({{"id", String()},
                             {"class", String()},
                             {"state", state},
                             {"footprint", footprint},
                             {"visible_fraction_lidar", Number()},
                             {"visible_fraction_stereo", Number()},
                             {"contact_time", {{"type", json::array({"number", "null"})}}}});
  return Make("lookout.TruthFrame", "Ground truth of the simulator at one instant (world frame)",
              {{"timestamp", Time()},
               {"ego", Object({{"state", state}, {"footprint", footprint}})},
               {"actors", ArrayOf(actor)}});
}

}  // namespace lookout::io
