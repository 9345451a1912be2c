#include "lookout/io/message_json.h"

#include <cmath>
#include <stdexcept>
#include <limits>

#include "lookout/core/input_error.h"
#include "lookout/io/base64.h"
#include "lookout/io/replay_log.h"

namespace lookout::io {
namespace {

using nlohmann::json;

json QuaternionFromYaw(double yaw) {
  return {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(yaw / 2.0)}, {"w", std::cos(yaw / 2.0)}};
}

json Pose3FromPose2(const Pose2& p) {
  return {{"position", {{"x", p.x()}, {"y", p.y()}, {"z", 0.0}}},
          {"orientation", QuaternionFromYaw(p.yaw)}};
}

json Color(double r, double g, double b, double a) {
  return {{"r", r}, {"g", g}, {"b", b}, {"a", a}};
}

json Mount(const Pose2& p) { return {{"x", p.x()}, {"y", p.y()}, {"yaw", p.yaw}}; }

json StateToJson(const sim::KinematicState& s) {
  const Eigen::Vector2d v = s.Velocity();
  return {{"x", s.pose.x()},           {"y", s.pose.y()},
          {"yaw", s.pose.yaw},         {"speed", s.speed_mps},
          {"yaw_rate", s.yaw_rate_radps}, {"acceleration", s.acceleration_mps2},
          {"vx", v.x()},               {"vy", v.y()}};
}

json FootprintToJson(const sim::Shape& shape) {
  if (shape.kind == sim::Shape::Kind::kCircle) {
    return {
        {"circle", {{"x", shape.center.x()}, {"y", shape.center.y()}, {"radius", shape.radius}}}};
  }
  json ring = json::array();
  for (const Eigen::Vector2d& v : shape.vertices) ring.push_back({v.x(), v.y()});
  return {{"polygon", ring}};
}

// Field access that names the field in the error, for the readers below.
const json& Field(const json& j, const char* name, const std::string& source) {
  if (!j.is_object() || !j.contains(name)) {
    throw InputError(source, 0, name, "missing field");
  }
  return j.at(name);
}

double NumberField(const json& j, const char* name, const std::string& source) {
  const json& f = Field(j, name, source);
  if (!f.is_number()) throw InputError(source, 0, name, "expected a number");
  return f.get<double>();
}

Pose2 MountFromJson(const json& j, const std::string& source) {
  const json& m = Field(j, "mount", source);
  return Pose2(NumberField(m, "x", source), NumberField(m, "y", source),
               NumberField(m, "yaw", source));
}

}  // namespace

json TimeToJson(TimeNs t) {
  return {{"sec", t / kNanosPerSecond}, {"nsec", t % kNanosPerSecond}};
}

TimeNs TimeFromJson(const json& j, const std::string& source) {
  const json& sec = Field(j, "sec", source);
  const json& nsec = Field(j, "nsec", source);
  if (!sec.is_number_integer() || !nsec.is_number_integer()) {
    throw InputError(source, 0, "timestamp", "sec and nsec must be integers");
  }
  return sec.get<TimeNs>() * kNanosPerSecond + nsec.get<TimeNs>();
}

json LidarScanToJson(const LidarScan& scan, const std::string& frame_id) {
  json ranges = json::array();
  for (const float r : scan.ranges_m) {
    // JSON has no infinity: a beam without a return is null (see the schema).
    if (std::isfinite(r)) {
      ranges.push_back(r);
    } else {
      ranges.push_back(nullptr);
    }
  }
  const double end_angle =
      scan.ranges_m.empty() ? scan.angle_min_rad : scan.BeamAngle(scan.ranges_m.size() - 1);
  return {{"timestamp", TimeToJson(scan.stamp)},
          {"frame_id", frame_id},
          {"pose", Pose3FromPose2(Pose2())},
          {"start_angle", scan.angle_min_rad},
          {"end_angle", end_angle},
          {"angle_increment", scan.angle_increment_rad},
          {"range_max", scan.max_range_m},
          {"ranges", std::move(ranges)},
          {"intensities", json::array()},
          {"mount", Mount(scan.mount)}};
}

LidarScan LidarScanFromJson(const json& j, const std::string& source) {
  LidarScan scan;
  scan.stamp = TimeFromJson(Field(j, "timestamp", source), source);
  scan.angle_min_rad = NumberField(j, "start_angle", source);
  scan.angle_increment_rad = NumberField(j, "angle_increment", source);
  scan.max_range_m = NumberField(j, "range_max", source);
  scan.mount = MountFromJson(j, source);
  const json& ranges = Field(j, "ranges", source);
  if (!ranges.is_array()) throw InputError(source, 0, "ranges", "expected an array");
  scan.ranges_m.reserve(ranges.size());
  for (const json& r : ranges) {
    if (r.is_null()) {
      scan.ranges_m.push_back(std::numeric_limits<float>::infinity());
    } else if (r.is_number()) {
      scan.ranges_m.push_back(r.get<float>());
    } else {
      throw InputError(source, 0, "ranges", "expected numbers or null");
    }
  }
  return scan;
}

json StereoFrameToJson(const StereoFrame& frame, const std::string& frame_id) {
  json objects = json::array();
  for (const StereoObject& o : frame.objects) {
    const Eigen::Matrix2d& c = o.center_covariance;
    objects.push_back({{"id", o.id},
                       {"class", std::string(ToString(o.object_class))},
                       {"center", {{"x", o.center_m.x()}, {"y", o.center_m.y()}}},
                       {"yaw", o.yaw_rad},
                       {"length", o.length_m},
                       {"width", o.width_m},
                       {"speed_longitudinal", o.speed_longitudinal_mps},
                       {"speed_lateral", o.speed_lateral_mps},
                       {"center_covariance", {c(0, 0), c(0, 1), c(1, 0), c(1, 1)}},
                       {"yaw_variance", o.yaw_variance},
                       {"speed_variance", o.speed_variance},
                       {"history", o.history}});
  }
  return {{"timestamp", TimeToJson(frame.stamp)},
          {"frame_id", frame_id},
          {"mount", Mount(frame.mount)},
          {"objects", std::move(objects)}};
}

StereoFrame StereoFrameFromJson(const json& j, const std::string& source) {
  StereoFrame frame;
  frame.stamp = TimeFromJson(Field(j, "timestamp", source), source);
  frame.mount = MountFromJson(j, source);
  const json& objects = Field(j, "objects", source);
  if (!objects.is_array()) throw InputError(source, 0, "objects", "expected an array");
  for (const json& o : objects) {
    StereoObject s;
    const json& id = Field(o, "id", source);
    if (!id.is_number_unsigned()) throw InputError(source, 0, "id", "expected an unsigned integer");
    s.id = id.get<std::uint32_t>();
    const json& cls = Field(o, "class", source);
    const auto parsed = cls.is_string() ? ParseObjectClass(cls.get<std::string>()) : std::nullopt;
    if (!parsed) throw InputError(source, 0, "class", "unknown object class");
    s.object_class = *parsed;
    const json& center = Field(o, "center", source);
    s.center_m = {NumberField(center, "x", source), NumberField(center, "y", source)};
    s.yaw_rad = NumberField(o, "yaw", source);
    s.length_m = NumberField(o, "length", source);
    s.width_m = NumberField(o, "width", source);
    s.speed_longitudinal_mps = NumberField(o, "speed_longitudinal", source);
    s.speed_lateral_mps = NumberField(o, "speed_lateral", source);
    const json& cov = Field(o, "center_covariance", source);
    if (!cov.is_array() || cov.size() != 4) {
      throw InputError(source, 0, "center_covariance", "expected 4 numbers");
    }
    for (int k = 0; k < 4; ++k) {
      const json& v = cov[static_cast<std::size_t>(k)];
      if (!v.is_number()) throw InputError(source, 0, "center_covariance", "expected numbers");
      s.center_covariance(k / 2, k % 2) = v.get<double>();
    }
    s.yaw_variance = NumberField(o, "yaw_variance", source);
    s.speed_variance = NumberField(o, "speed_variance", source);
    const json& history = Field(o, "history", source);
    if (!history.is_number_unsigned()) {
      throw InputError(source, 0, "history", "expected an unsigned integer");
    }
    s.history = history.get<std::uint32_t>();
    frame.objects.push_back(s);
  }
  return frame;
}

json EgoOdometryToJson(const EgoOdometry& odometry) {
  return {{"timestamp", TimeToJson(odometry.stamp)},
          {"speed", odometry.speed_mps},
          {"yaw_rate", odometry.yaw_rate_radps}};
}

EgoOdometry EgoOdometryFromJson(const json& j, const std::string& source) {
  EgoOdometry o;
  o.stamp = TimeFromJson(Field(j, "timestamp", source), source);
  o.speed_mps = NumberField(j, "speed", source);
  o.yaw_rate_radps = NumberField(j, "yaw_rate", source);
  return o;
}

json TruthFrameToJson(const sim::TruthFrame& frame) {
  json actors = json::array();
  for (const sim::ActorTruth& a : frame.actors) {
    actors.push_back(
        {{"id", a.id},
         {"class", std::string(ToString(a.object_class))},
         {"state", StateToJson(a.state)},
         {"footprint", FootprintToJson(a.footprint)},
         {"visible_fraction_lidar", a.visible_fraction_lidar},
         {"visible_fraction_stereo", a.visible_fraction_stereo},
         {"contact_time", a.contact_time_s ? json(*a.contact_time_s) : json(nullptr)}});
  }
  return {{"timestamp", TimeToJson(frame.stamp)},
          {"ego",
           {{"state", StateToJson(frame.ego.state)},
            {"footprint", FootprintToJson(frame.ego.footprint)}}},
          {"actors", std::move(actors)}};
}

json FrameTransformToJson(TimeNs t, const std::string& parent, const std::string& child,
                          const Pose2& pose) {
  return {{"timestamp", TimeToJson(t)},
          {"parent_frame_id", parent},
          {"child_frame_id", child},
          {"translation", {{"x", pose.x()}, {"y", pose.y()}, {"z", 0.0}}},
          {"rotation", QuaternionFromYaw(pose.yaw)}};
}

json PoseInFrameToJson(TimeNs t, const std::string& frame_id, const Pose2& pose) {
  return {{"timestamp", TimeToJson(t)}, {"frame_id", frame_id}, {"pose", Pose3FromPose2(pose)}};
}

namespace {

// A closed outline of a polygon at height z as a foxglove line loop (type 1).
json Outline(const std::vector<Eigen::Vector2d>& ring, const json& color, double z) {
  json points = json::array();
  for (const Eigen::Vector2d& v : ring) points.push_back({{"x", v.x()}, {"y", v.y()}, {"z", z}});
  return {{"type", 1},
          {"pose", Pose3FromPose2(Pose2())},
          {"thickness", 0.1},
          {"scale_invariant", false},
          {"points", std::move(points)},
          {"color", color},
          {"colors", json::array()},
          {"indices", json::array()}};
}

json Cylinder(const Eigen::Vector2d& c, double radius, double height, const json& color) {
  return {{"pose", Pose3FromPose2(Pose2(c, 0.0))},
          {"size", {{"x", 2.0 * radius}, {"y", 2.0 * radius}, {"z", height}}},
          {"bottom_scale", 1.0},
          {"top_scale", 1.0},
          {"color", color}};
}

json Entity(TimeNs t, const std::string& id, const std::string& frame_id) {
  return {{"timestamp", TimeToJson(t)},
          {"frame_id", frame_id},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},
          {"frame_locked", false},
          {"metadata", json::array()},
          {"arrows", json::array()},
          {"cubes", json::array()},
          {"spheres", json::array()},
          {"cylinders", json::array()},
          {"lines", json::array()},
          {"triangles", json::array()},
          {"texts", json::array()},
          {"models", json::array()}};
}

json ColorForClass(ObjectClass c) {
  switch (c) {
    case ObjectClass::kPedestrian: return Color(1.0, 0.55, 0.1, 0.9);
    case ObjectClass::kCyclist: return Color(0.9, 0.2, 0.8, 0.9);
    case ObjectClass::kTruck: return Color(0.2, 0.4, 1.0, 0.9);
    default: return Color(0.2, 0.8, 1.0, 0.9);
  }
}

}  // namespace

json TruthSceneToJson(const sim::TruthFrame& frame) {
  json entities = json::array();
  for (const sim::ActorTruth& a : frame.actors) {
    json e = Entity(frame.stamp, a.id, "world");
    const json color = ColorForClass(a.object_class);
    if (a.footprint.kind == sim::Shape::Kind::kCircle) {
      e["cylinders"].push_back(Cylinder(a.footprint.center, a.footprint.radius, 1.7, color));
    } else {
      e["lines"].push_back(Outline(a.footprint.vertices, color, 0.0));
    }
    e["texts"].push_back({{"pose", Pose3FromPose2(a.state.pose)},
                          {"billboard", true},
                          {"font_size", 14.0},
                          {"scale_invariant", true},
                          {"color", Color(1, 1, 1, 1)},
                          {"text", a.id}});
    // A short lifetime, so actors that leave the scenario vanish from the display.
    e["lifetime"] = {{"sec", 0}, {"nsec", 200'000'000}};
    entities.push_back(std::move(e));
  }
  json ego = Entity(frame.stamp, "ego", "world");
  ego["lines"].push_back(Outline(frame.ego.footprint.vertices, Color(0.3, 1.0, 0.3, 1.0), 0.0));
  ego["lifetime"] = {{"sec", 0}, {"nsec", 200'000'000}};
  entities.push_back(std::move(ego));
  return {{"deletions", json::array()}, {"entities", std::move(entities)}};
}

json StaticWorldToJson(TimeNs t, const std::vector<sim::Shape>& shapes) {
  json entities = json::array();
  const json wall = Color(0.6, 0.6, 0.6, 1.0);
  const json post = Color(0.9, 0.9, 0.3, 1.0);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const sim::Shape& s = shapes[i];
    json e = Entity(t, "static-" + std::to_string(i), "world");
    if (s.kind == sim::Shape::Kind::kCircle) {
      e["cylinders"].push_back(Cylinder(s.center, s.radius, 2.5, post));
    } else {
      e["lines"].push_back(Outline(s.vertices, wall, 0.0));
    }
    entities.push_back(std::move(e));
  }
  return {{"deletions", json::array()}, {"entities", std::move(entities)}};
}

json PeopleSceneToJson(TimeNs t, const std::string& frame_id,
                       std::span<const AnnotatedPerson> people) {
  json entities = json::array();
  const json color = Color(0.3, 1.0, 0.3, 0.8);
  for (const AnnotatedPerson& p : people) {
    json e = Entity(t, "person-" + std::to_string(p.id), frame_id);
    e["cylinders"].push_back(Cylinder(p.position_m, 0.25, 1.7, color));
    e["texts"].push_back({{"pose", Pose3FromPose2(Pose2(p.position_m, 0.0))},
                          {"billboard", true},
                          {"font_size", 14.0},
                          {"scale_invariant", true},
                          {"color", Color(1, 1, 1, 1)},
                          {"text", std::to_string(p.id)}});
    e["lifetime"] = {{"sec", 0}, {"nsec", 200'000'000}};
    entities.push_back(std::move(e));
  }
  return {{"deletions", json::array()}, {"entities", std::move(entities)}};
}

namespace {

// A polyline through `points` at height z: foxglove line type 0 (strip).
json Strip(const std::vector<Eigen::Vector2d>& points, const json& color, double thickness,
           double z) {
  json line = Outline(points, color, z);
  line["type"] = 0;
  line["thickness"] = thickness;
  return line;
}

// One number as the text of a metadata value: JSON's shortest round-trip form, so the same
// value always gives the same bytes.
json Meta(const std::string& key, const json& value) {
  return {{"key", key}, {"value", value.is_string() ? value.get<std::string>() : value.dump()}};
}

json Matrix2ToJson(const Eigen::Matrix2d& m) {
  return json::array({m(0, 0), m(0, 1), m(1, 0), m(1, 1)});
}

}  // namespace

json LidarObjectsSceneToJson(const LidarObjectFrame& frame, const std::string& frame_id) {
  // Velocity arrows are as long as the distance covered in this time: readable for a walker
  // (0.7 m at 1.4 m/s) without a car's arrow crossing the junction.
  constexpr double kArrowSeconds = 0.5;
  json entities = json::array();
  for (const LidarObject& o : frame.objects) {
    std::size_t best = 0;
    for (std::size_t c = 1; c < o.class_pmf.size(); ++c) {
      if (o.class_pmf[c] > o.class_pmf[best]) best = c;
    }
    const ObjectClass object_class = kAllObjectClasses[best];
    json e = Entity(frame.stamp, "lidar-object-" + std::to_string(o.id), frame_id);
    json color = ColorForClass(object_class);
    if (!o.dynamic) color["a"] = 0.35;
    const Pose2 box(o.centroid_m, o.yaw_rad);
    const double hl = o.length_m / 2.0, hw = o.width_m / 2.0;
    e["lines"].push_back(Outline({box * Eigen::Vector2d(-hl, -hw), box * Eigen::Vector2d(hl, -hw),
                                  box * Eigen::Vector2d(hl, hw), box * Eigen::Vector2d(-hl, hw)},
                                 color, 0.0));
    e["lines"].push_back(
        Strip({o.front_start_m, o.front_end_m}, Color(1.0, 1.0, 1.0, 1.0), 0.15, 0.05));
    const double speed = o.velocity_mps.norm();
    if (speed > 0.0) {
      const double length = speed * kArrowSeconds;
      const Pose2 at(o.centroid_m, std::atan2(o.velocity_mps.y(), o.velocity_mps.x()));
      e["arrows"].push_back({{"pose", Pose3FromPose2(at)},
                             {"shaft_length", 0.8 * length},
                             {"shaft_diameter", 0.1},
                             {"head_length", 0.2 * length},
                             {"head_diameter", 0.3},
                             {"color", color}});
    }
    const std::string label = std::to_string(o.id) + " " + std::string(ToString(object_class));
    e["texts"].push_back({{"pose", Pose3FromPose2(Pose2(o.point_m, 0.0))},
                          {"billboard", true},
                          {"font_size", 12.0},
                          {"scale_invariant", true},
                          {"color", Color(1, 1, 1, 1)},
                          {"text", label}});
    // The object's numbers, for inspection in Foxglove's entity panel (vehicle frame, SI).
    e["metadata"] = json::array(
        {Meta("class", std::string(ToString(object_class))),
         Meta("class_pmf", json(o.class_pmf)),
         Meta("dynamic", o.dynamic),
         Meta("cell_count", o.cell_count),
         Meta("point", json::array({o.point_m.x(), o.point_m.y()})),
         Meta("point_covariance", Matrix2ToJson(o.point_covariance)),
         Meta("centroid", json::array({o.centroid_m.x(), o.centroid_m.y()})),
         Meta("range", o.range_m),
         Meta("bearing", o.bearing_rad),
         Meta("yaw", o.yaw_rad),
         Meta("length", o.length_m),
         Meta("width", o.width_m),
         Meta("velocity", json::array({o.velocity_mps.x(), o.velocity_mps.y()})),
         Meta("velocity_covariance", Matrix2ToJson(o.velocity_covariance))});
    entities.push_back(std::move(e));
  }
  // Ids are unique within a frame only: every update replaces the previous frame's objects.
  return {{"deletions", json::array({{{"timestamp", TimeToJson(frame.stamp)},
                                      {"type", 1},
                                      {"id", ""}}})},
          {"entities", std::move(entities)}};
}

json TracksSceneToJson(TimeNs t, const std::vector<tracking::Track>& tracks,
                       const std::string& frame_id) {
  constexpr double kArrowSeconds = 0.5;  // as the lidar objects' arrows
  json entities = json::array();
  for (const tracking::Track& track : tracks) {
    json e = Entity(t, "track-" + std::to_string(track.id), frame_id);
    json color = ColorForClass(track.object_class);
    if (track.coasting) color["a"] = 0.35;
    const Eigen::Vector2d p = track.Position(), v = track.Velocity();
    e["cylinders"].push_back(Cylinder(p, 0.5, 0.2, color));
    const double speed = v.norm();
    if (speed > 0.0) {
      const double length = speed * kArrowSeconds;
      e["arrows"].push_back({{"pose", Pose3FromPose2(Pose2(p, std::atan2(v.y(), v.x())))},
                             {"shaft_length", 0.8 * length},
                             {"shaft_diameter", 0.1},
                             {"head_length", 0.2 * length},
                             {"head_diameter", 0.3},
                             {"color", color}});
    }
    e["texts"].push_back({{"pose", Pose3FromPose2(Pose2(p, 0.0))},
                          {"billboard", true},
                          {"font_size", 12.0},
                          {"scale_invariant", true},
                          {"color", Color(1, 1, 1, 1)},
                          {"text", std::to_string(track.id) + " " +
                                       std::string(ToString(track.object_class))}});
    e["metadata"] = json::array(
        {Meta("class", std::string(ToString(track.object_class))),
         Meta("position", json::array({p.x(), p.y()})),
         Meta("velocity", json::array({v.x(), v.y()})),
         Meta("position_covariance", Matrix2ToJson(track.state.cov.topLeftCorner<2, 2>())),
         Meta("velocity_covariance", Matrix2ToJson(track.state.cov.block<2, 2>(2, 2))),
         Meta("updates", track.updates),
         Meta("misses", track.misses),
         Meta("coasting", track.coasting)});
    entities.push_back(std::move(e));
  }
  return {{"deletions", json::array({{{"timestamp", TimeToJson(t)}, {"type", 1}, {"id", ""}}})},
          {"entities", std::move(entities)}};
}

namespace {

json OptionalNumber(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

}  // namespace

json RiskAssessmentToJson(TimeNs t, const risk::EgoInput& ego,
                          const risk::RiskAssessment& assessment, risk::WarningLevel level) {
  json objects = json::array();
  for (const risk::ObjectRisk& o : assessment.objects) {
    objects.push_back({{"id", o.id},
                       {"ttc", OptionalNumber(o.ttc_s)},
                       {"risk", o.risk},
                       {"collision_probability", o.collision_probability},
                       {"pet", OptionalNumber(o.pet_s)}});
  }
  const json earliest =
      assessment.earliest ? json(assessment.objects[*assessment.earliest].id) : json(nullptr);
  return {{"timestamp", TimeToJson(t)},
          {"ego",
           {{"x", ego.position_m.x()},
            {"y", ego.position_m.y()},
            {"yaw", ego.yaw_rad},
            {"speed", ego.speed_mps},
            {"acceleration", ego.acceleration_mps2},
            {"yaw_rate", ego.yaw_rate_radps},
            {"route", !ego.route_m.empty()}}},
          {"objects", std::move(objects)},
          {"earliest", earliest},
          {"risk", assessment.risk},
          {"dropped", assessment.dropped},
          {"level", risk::ToString(level)}};
}

json WarningEventToJson(const risk::WarningEvent& event) {
  return {{"timestamp", TimeToJson(event.stamp)},
          {"level", risk::ToString(event.level)},
          {"object_id", event.object_id ? json(*event.object_id) : json(nullptr)},
          {"ttc", OptionalNumber(event.ttc_s)}};
}

json GridToJson(TimeNs t, const std::string& frame_id, const GridGeometry& geometry,
                const std::vector<GridLayer8>& layers) {
  constexpr int kUint8 = 1;  // foxglove.NumericType
  const auto cells = static_cast<std::size_t>(geometry.CellCount());
  const std::size_t stride = layers.size();
  std::vector<std::uint8_t> data(cells * stride);
  json fields = json::array();
  for (std::size_t f = 0; f < layers.size(); ++f) {
    if (layers[f].values.size() != cells) {
      throw std::invalid_argument("grid layer " + layers[f].name + " has the wrong size");
    }
    fields.push_back({{"name", layers[f].name}, {"offset", f}, {"type", kUint8}});
    for (std::size_t c = 0; c < cells; ++c) data[c * stride + f] = layers[f].values[c];
  }
  return {{"timestamp", TimeToJson(t)},
          {"frame_id", frame_id},
          {"pose", Pose3FromPose2(Pose2(geometry.origin_m, 0.0))},
          {"column_count", geometry.width},
          {"cell_size", {{"x", geometry.cell_size_m}, {"y", geometry.cell_size_m}}},
          {"row_stride", static_cast<std::size_t>(geometry.width) * stride},
          {"cell_stride", stride},
          {"fields", std::move(fields)},
          {"data", Base64Encode(data)}};
}

}  // namespace lookout::io
