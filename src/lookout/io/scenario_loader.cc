#include "lookout/io/scenario_loader.h"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/core/object_class.h"
#include "lookout/io/default_scenario.h"

namespace lookout::io {
namespace {

using Eigen::Vector2d;

// Limits the format does not state but the simulator needs: without them a file could make it
// allocate without bound (trajectories are sampled every 10 ms over the whole duration, a lidar
// scan has fov / resolution beams, frames come at rate_hz) or integrate positions to infinity.
// Each is far beyond any junction scenario.
constexpr std::size_t kMaxInputBytes = std::size_t{1} << 20;
constexpr double kMaxDuration_s = 3600.0;
constexpr double kMaxCoordinate_m = 100'000.0;
constexpr double kMaxSpeed_mps = 100.0;
constexpr double kMaxSize_m = 100.0;  // footprints, radii, sensor mount offsets, noise
constexpr double kMaxRate_hz = 1000.0;
constexpr double kMinResolution_deg = 0.01;
constexpr double kMaxFalseObjectsPerFrame = 100.0;
// A path segment shorter than this has no direction to follow (and a polygon edge no normal).
constexpr double kMinSegment_m = 1e-3;

constexpr double kDegToRad = std::numbers::pi / 180.0;

// yaml-cpp's tags: "?" for a plain scalar, "!" for a quoted one, else the explicit tag.
constexpr std::string_view kPlainTag = "?";
constexpr std::string_view kIntTag = "tag:yaml.org,2002:int";
constexpr std::string_view kFloatTag = "tag:yaml.org,2002:float";
constexpr std::string_view kBoolTag = "tag:yaml.org,2002:bool";

// A YAML node and where it sits: the file, its field path ("actors[1].path[0]") and its 1-based
// line. Copy-assignment is deleted because yaml-cpp's Node::operator= writes through to the
// node it refers to, which would silently change the document.
struct Field {
  YAML::Node node;
  std::string path;
  int line = 0;
  const std::string* source = nullptr;

  Field(YAML::Node n, std::string p, int fallback_line, const std::string* s)
      : node(std::move(n)), path(std::move(p)), line(LineOf(node, fallback_line)), source(s) {}
  Field(const Field&) = default;
  Field& operator=(const Field&) = delete;

 private:
  // A null value (`speed:` with nothing after it) carries the mark of the next token, which may
  // be lines further down: such nodes are reported at their key's line instead.
  static int LineOf(const YAML::Node& n, int fallback_line) {
    if (!n.IsDefined() || n.IsNull() || n.Mark().is_null()) return fallback_line;
    return n.Mark().line + 1;
  }
};

[[noreturn]] void Fail(const Field& f, const std::string& problem) {
  throw InputError(*f.source, f.line, f.path, problem);
}

Field ElementOf(const Field& list, std::size_t index, const YAML::Node& node) {
  return Field(node, fmt::format("{}[{}]", list.path, index), list.line, list.source);
}

std::string KeyPath(const Field& parent, std::string_view key) {
  return parent.path.empty() ? std::string(key) : fmt::format("{}.{}", parent.path, key);
}

// How a node looks, for "expected X, got Y" messages. Long or odd text is cut short so that a
// message stays one readable line.
std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return "nothing";
    case YAML::NodeType::Sequence:
      return fmt::format("a list of {}", node.size());
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      break;
  }
  constexpr std::size_t kMaxShown = 40;
  std::string text;
  for (const char c : node.Scalar()) {
    if (text.size() == kMaxShown) {
      text += "...";
      break;
    }
    text += (c >= ' ' && c <= '~') ? c : '?';
  }
  return node.Tag() == kPlainTag ? fmt::format("'{}'", text)
                                 : fmt::format("the string \"{}\"", text);
}

[[noreturn]] void FailType(const Field& f, std::string_view expected) {
  if (f.node.IsNull()) Fail(f, fmt::format("has no value (expected {})", expected));
  Fail(f, fmt::format("expected {}, got {}", expected, Describe(f.node)));
}

// ---------------------------------------------------------------------------------------------
// Scalars

bool IsPlainOrTagged(const YAML::Node& node, std::string_view tag) {
  return node.IsScalar() && (node.Tag() == kPlainTag || node.Tag() == tag);
}

// YAML's spellings of infinity and not-a-number (core schema): refused by name, since
// std::from_chars would not read them (it takes C's "inf" and "nan", which YAML calls strings).
bool IsYamlInfinityOrNan(std::string_view text) {
  std::string_view body = text;
  if (!body.empty() && (body.front() == '-' || body.front() == '+')) body.remove_prefix(1);
  return body == ".inf" || body == ".Inf" || body == ".INF" || text == ".nan" || text == ".NaN" ||
         text == ".NAN";
}

// Any finite number, written plainly (a quoted "12" is a string, as in YAML).
double Number(const Field& f) {
  if (!IsPlainOrTagged(f.node, kFloatTag) && !IsPlainOrTagged(f.node, kIntTag)) {
    FailType(f, "a number");
  }
  const std::string& text = f.node.Scalar();
  if (IsYamlInfinityOrNan(text)) Fail(f, fmt::format("must be a finite number, got {}", text));
  // from_chars takes no '+' but does take "inf" and "nan": after an optional sign, a YAML
  // number starts with a digit or a point.
  std::string_view body = text;
  if (!body.empty() && body.front() == '+') body.remove_prefix(1);
  const std::size_t first = !body.empty() && body.front() == '-' ? 1 : 0;
  if (body.size() <= first ||
      !(std::isdigit(static_cast<unsigned char>(body[first])) || body[first] == '.')) {
    FailType(f, "a number");
  }
  double value = 0.0;
  const char* end = body.data() + body.size();
  const auto [ptr, ec] = std::from_chars(body.data(), end, value);
  if (ec == std::errc::result_out_of_range) Fail(f, fmt::format("{} is out of range", text));
  if (ec != std::errc{} || ptr != end || !std::isfinite(value)) FailType(f, "a number");
  return value;
}

double NumberIn(const Field& f, double min, double max, std::string_view unit = "") {
  const double v = Number(f);
  if (v < min || v > max) Fail(f, fmt::format("must be in [{}, {}]{}, got {}", min, max, unit, v));
  return v;
}

// (0, max]: sizes, rates, ranges, durations.
double Positive(const Field& f, double max, std::string_view unit) {
  const double v = Number(f);
  if (v <= 0.0) Fail(f, fmt::format("must be > 0, got {}", v));
  if (v > max) Fail(f, fmt::format("must be at most {} {}, got {}", max, unit, v));
  return v;
}

// [0, max]: speeds, times, noise levels.
double NonNegative(const Field& f, double max, std::string_view unit) {
  const double v = Number(f);
  if (v < 0.0) Fail(f, fmt::format("must be >= 0, got {}", v));
  if (v > max) Fail(f, fmt::format("must be at most {} {}, got {}", max, unit, v));
  return v;
}

double Probability(const Field& f) { return NumberIn(f, 0.0, 1.0); }

double Coordinate(const Field& f) { return NumberIn(f, -kMaxCoordinate_m, kMaxCoordinate_m, " m"); }

// A decimal integer (YAML core schema: optional sign, digits).
template <typename Int>
Int Integer(const Field& f, std::string_view expected) {
  if (!IsPlainOrTagged(f.node, kIntTag)) FailType(f, expected);
  std::string_view text = f.node.Scalar();
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  Int value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc::result_out_of_range) {
    Fail(f, fmt::format("{} is out of range for {}", f.node.Scalar(), expected));
  }
  if (ec != std::errc{} || ptr != end) FailType(f, expected);
  return value;
}

bool Bool(const Field& f) {
  if (IsPlainOrTagged(f.node, kBoolTag)) {
    const std::string& t = f.node.Scalar();
    if (t == "true" || t == "True" || t == "TRUE") return true;
    if (t == "false" || t == "False" || t == "FALSE") return false;
  }
  FailType(f, "true or false");
}

// Any scalar is text: `id: 7` is the id "7".
std::string String(const Field& f) {
  if (!f.node.IsScalar()) FailType(f, "a string");
  return f.node.Scalar();
}

// ---------------------------------------------------------------------------------------------
// Mappings and lists

// One YAML mapping's entries. Keys must be plain, unique names, and a caller states which keys
// it knows (OnlyKeys): an unknown or repeated key is refused, because a typo would otherwise
// fall back to a default without a word.
class Mapping {
 public:
  explicit Mapping(const Field& f) : field_(f) {
    if (!f.node.IsMap()) FailType(f, "a mapping");
    std::unordered_map<std::string, int> key_lines;
    for (YAML::const_iterator it = f.node.begin(); it != f.node.end(); ++it) {
      const Field key(it->first, f.path, f.line, f.source);
      if (!it->first.IsScalar())
        Fail(key, fmt::format("a key must be a name, got {}", Describe(it->first)));
      const std::string& name = it->first.Scalar();
      // A map, not a scan of the entries: a file may hold many keys (up to the size limit).
      const auto [first, inserted] = key_lines.emplace(name, key.line);
      if (!inserted) {
        Fail(Field(it->first, KeyPath(f, name), f.line, f.source),
             fmt::format("repeated key (first at line {})", first->second));
      }
      entries_.push_back({name, key.line, Field(it->second, KeyPath(f, name), key.line, f.source)});
    }
  }

  void OnlyKeys(std::initializer_list<std::string_view> allowed) const {
    for (const Entry& e : entries_) {
      bool known = false;
      std::string list;
      for (const std::string_view k : allowed) {
        known = known || k == e.key;
        list += list.empty() ? std::string(k) : fmt::format(", {}", k);
      }
      if (!known) {
        throw InputError(*field_.source, e.key_line, KeyPath(field_, e.key),
                         fmt::format("unknown key (allowed here: {})", list));
      }
    }
  }

  std::optional<Field> Get(std::string_view key) const {
    for (const Entry& e : entries_) {
      if (e.key == key) return e.value;
    }
    return std::nullopt;
  }

  Field Require(std::string_view key) const {
    if (std::optional<Field> f = Get(key)) return *f;
    throw InputError(*field_.source, field_.line, KeyPath(field_, key), "required but missing");
  }

  const Field& field() const { return field_; }

 private:
  struct Entry {
    std::string key;
    int key_line;
    Field value;
  };
  Field field_;
  std::vector<Entry> entries_;
};

std::vector<Field> List(const Field& f) {
  if (!f.node.IsSequence()) FailType(f, "a list");
  std::vector<Field> elements;
  elements.reserve(f.node.size());
  std::size_t i = 0;
  for (YAML::const_iterator it = f.node.begin(); it != f.node.end(); ++it, ++i) {
    elements.push_back(ElementOf(f, i, *it));
  }
  return elements;
}

// A list of exactly `n` elements: [x, y] points, (t, v) pairs.
std::vector<Field> Tuple(const Field& f, std::size_t n, std::string_view shape) {
  if (!f.node.IsSequence() || f.node.size() != n) FailType(f, shape);
  return List(f);
}

Vector2d Point(const Field& f) {
  const std::vector<Field> xy = Tuple(f, 2, "a point [x, y]");
  return {Coordinate(xy[0]), Coordinate(xy[1])};
}

// ---------------------------------------------------------------------------------------------
// Sections of the format

std::vector<Vector2d> ParsePath(const Field& f) {
  const std::vector<Field> elements = List(f);
  if (elements.size() < 2) {
    Fail(f, fmt::format("needs at least 2 waypoints, got {}", elements.size()));
  }
  std::vector<Vector2d> path;
  path.reserve(elements.size());
  for (const Field& e : elements) {
    const Vector2d p = Point(e);
    // The follower takes its heading from the segment ahead; a zero-length one has none.
    if (!path.empty() && (p - path.back()).norm() < kMinSegment_m) {
      Fail(e, "repeats the previous waypoint (a zero-length segment)");
    }
    path.push_back(p);
  }
  return path;
}

sim::SpeedProfile ParseProfile(const Field& f) {
  const std::vector<Field> elements = List(f);
  if (elements.empty()) Fail(f, "needs at least one [t, v] pair");
  sim::SpeedProfile profile;
  for (const Field& e : elements) {
    const std::vector<Field> tv = Tuple(e, 2, "a pair [t, v]");
    const double t = NonNegative(tv[0], kMaxDuration_s, "s");
    const double v = NonNegative(tv[1], kMaxSpeed_mps, "m/s");
    // Interpolation divides by the time step: equal or backward times are refused.
    if (!profile.points.empty() && t <= profile.points.back().x()) {
      Fail(e, fmt::format("times must increase strictly: {} follows {}", t,
                          profile.points.back().x()));
    }
    profile.points.emplace_back(t, v);
  }
  return profile;
}

// Exactly one of `speed` and `speed_profile`, for the ego and every actor.
sim::SpeedProfile ParseSpeed(const Mapping& m) {
  const std::optional<Field> constant = m.Get("speed");
  const std::optional<Field> profile = m.Get("speed_profile");
  if (constant && profile) Fail(*profile, "give either speed or speed_profile, not both");
  if (constant) return sim::SpeedProfile::Constant(NonNegative(*constant, kMaxSpeed_mps, "m/s"));
  if (profile) return ParseProfile(*profile);
  throw InputError(*m.field().source, m.field().line, KeyPath(m.field(), "speed"),
                   "required but missing (give speed or speed_profile)");
}

sim::EgoSpec ParseEgo(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"length", "width", "path", "speed", "speed_profile"});
  sim::EgoSpec ego;
  if (const auto v = m.Get("length")) ego.length_m = Positive(*v, kMaxSize_m, "m");
  if (const auto v = m.Get("width")) ego.width_m = Positive(*v, kMaxSize_m, "m");
  ego.path = ParsePath(m.Require("path"));
  ego.speed = ParseSpeed(m);
  return ego;
}

ObjectClass ParseActorClass(const Field& f) {
  const std::string name = String(f);
  // ParseObjectClass also knows the stereo sensor's "pole" and "unknown", which are not actors.
  const std::optional<ObjectClass> c = ParseObjectClass(name);
  if (!c || (*c != ObjectClass::kCar && *c != ObjectClass::kTruck && *c != ObjectClass::kCyclist &&
             *c != ObjectClass::kPedestrian)) {
    Fail(f, fmt::format("unknown class {} (expected car, truck, cyclist or pedestrian)",
                        Describe(f.node)));
  }
  return *c;
}

sim::ActorSpec ParseActor(const Mapping& m, double duration_s) {
  m.OnlyKeys({"id", "class", "length", "width", "radius", "path", "speed", "speed_profile", "start",
              "stop"});
  sim::ActorSpec a;
  const Field id = m.Require("id");
  a.id = String(id);
  if (a.id.empty()) Fail(id, "must not be empty");
  a.object_class = ParseActorClass(m.Require("class"));
  a.length_m = sim::DefaultLength(a.object_class);
  a.width_m = sim::DefaultWidth(a.object_class);
  // The two footprint shapes take different fields; one given for the wrong shape is a mistake
  // that would otherwise be ignored.
  if (a.object_class == ObjectClass::kPedestrian) {
    for (const std::string_view key : {"length", "width"}) {
      if (const auto v = m.Get(key)) Fail(*v, "pedestrians are circles: give radius instead");
    }
    if (const auto v = m.Get("radius")) a.radius_m = Positive(*v, kMaxSize_m, "m");
  } else {
    if (const auto v = m.Get("radius")) {
      Fail(*v, fmt::format("only pedestrians have a radius; a {} is a box (length, width)",
                           ToString(a.object_class)));
    }
    if (const auto v = m.Get("length")) a.length_m = Positive(*v, kMaxSize_m, "m");
    if (const auto v = m.Get("width")) a.width_m = Positive(*v, kMaxSize_m, "m");
  }
  a.path = ParsePath(m.Require("path"));
  a.speed = ParseSpeed(m);
  if (const auto v = m.Get("start")) {
    a.start_s = NonNegative(*v, duration_s, "s (the scenario's duration)");
  }
  a.stop_s = duration_s;
  if (const auto v = m.Get("stop")) {
    a.stop_s = NonNegative(*v, kMaxDuration_s, "s");
    if (a.stop_s < a.start_s) {
      Fail(*v, fmt::format("must not be before start ({} s), got {}", a.start_s, a.stop_s));
    }
  }
  return a;
}

std::vector<sim::ActorSpec> ParseActors(const Field& f, double duration_s) {
  std::vector<sim::ActorSpec> actors;
  std::unordered_map<std::string, int> id_lines;  // for the duplicate message
  for (const Field& e : List(f)) {
    const Mapping m(e);
    actors.push_back(ParseActor(m, duration_s));
    const Field id = m.Require("id");
    const auto [first, inserted] = id_lines.emplace(actors.back().id, id.line);
    if (!inserted) {
      Fail(id, fmt::format("duplicate actor id '{}' (first at line {})", actors.back().id,
                           first->second));
    }
  }
  return actors;
}

double SignedArea(const std::vector<Vector2d>& polygon) {
  double twice_area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vector2d& a = polygon[i];
    const Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice_area;
}

std::vector<Vector2d> ParsePolygon(const Field& f) {
  const std::vector<Field> elements = List(f);
  if (elements.size() < 3)
    Fail(f, fmt::format("needs at least 3 vertices, got {}", elements.size()));
  std::vector<Vector2d> polygon;
  for (const Field& e : elements) {
    const Vector2d p = Point(e);
    if (!polygon.empty() && (p - polygon.back()).norm() < kMinSegment_m) {
      Fail(e, "repeats the previous vertex (a zero-length edge)");
    }
    polygon.push_back(p);
  }
  // The polygon closes itself; a repeated first vertex would be a zero-length closing edge.
  if ((polygon.back() - polygon.front()).norm() < kMinSegment_m) {
    Fail(elements.back(), "repeats the first vertex (the polygon closes itself)");
  }
  if (std::abs(SignedArea(polygon)) < kMinSegment_m * kMinSegment_m) {
    Fail(f, "has no area (its vertices are collinear)");
  }
  return polygon;
}

sim::Obstacle ParseObstacle(const Field& f) {
  const Mapping m(f);
  const Field kind = m.Require("kind");
  const std::string name = String(kind);
  sim::Obstacle o;
  if (name == "building") {
    m.OnlyKeys({"kind", "polygon"});
    o.kind = sim::ObstacleKind::kBuilding;
    o.polygon = ParsePolygon(m.Require("polygon"));
  } else if (name == "pole" || name == "sign") {
    m.OnlyKeys({"kind", "center", "radius"});
    o.kind = name == "pole" ? sim::ObstacleKind::kPole : sim::ObstacleKind::kSign;
    o.center_m = Point(m.Require("center"));
    o.radius_m = Positive(m.Require("radius"), kMaxSize_m, "m");
  } else if (name == "parked_car") {
    m.OnlyKeys({"kind", "center", "heading", "length", "width"});
    o.kind = sim::ObstacleKind::kParkedCar;
    o.center_m = Point(m.Require("center"));
    // A parked car is a car: its footprint defaults to one, facing east.
    o.length_m = sim::DefaultLength(ObjectClass::kCar);
    o.width_m = sim::DefaultWidth(ObjectClass::kCar);
    if (const auto v = m.Get("heading")) o.heading_rad = Number(*v);
    if (const auto v = m.Get("length")) o.length_m = Positive(*v, kMaxSize_m, "m");
    if (const auto v = m.Get("width")) o.width_m = Positive(*v, kMaxSize_m, "m");
  } else {
    Fail(kind, fmt::format("unknown obstacle kind {} (expected building, pole, parked_car or sign)",
                           Describe(kind.node)));
  }
  return o;
}

sim::World ParseWorld(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"preset", "obstacles"});
  sim::World world;
  if (const auto v = m.Get("preset")) {
    const std::string preset = String(*v);
    if (preset != "four_way")
      Fail(*v, fmt::format("unknown preset '{}' (expected four_way)", preset));
    world.preset = preset;
  }
  if (const auto v = m.Get("obstacles")) {
    for (const Field& e : List(*v)) world.obstacles.push_back(ParseObstacle(e));
  }
  return world;
}

// (0, 360] degrees, returned in radians.
double FieldOfView(const Field& f) {
  const double deg = Number(f);
  if (deg <= 0.0 || deg > 360.0) Fail(f, fmt::format("must be in (0, 360] degrees, got {}", deg));
  return deg * kDegToRad;
}

double Rate(const Field& f) { return Positive(f, kMaxRate_hz, "Hz"); }

double MountOffset(const Field& f) { return NumberIn(f, -kMaxSize_m, kMaxSize_m, " m"); }

sim::LidarOptions ParseLidar(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"x", "y", "yaw", "fov_deg", "max_range", "resolution_deg", "rate_hz", "range_noise",
              "dropout"});
  sim::LidarOptions o;
  if (const auto v = m.Get("x")) o.x_m = MountOffset(*v);
  if (const auto v = m.Get("y")) o.y_m = MountOffset(*v);
  if (const auto v = m.Get("yaw")) o.yaw_rad = Number(*v);
  if (const auto v = m.Get("fov_deg")) o.fov_rad = FieldOfView(*v);
  if (const auto v = m.Get("max_range")) o.max_range_m = Positive(*v, kMaxCoordinate_m, "m");
  if (const auto v = m.Get("resolution_deg")) {
    // The scan has fov / resolution beams: a floor on the resolution bounds its size.
    const double deg = NumberIn(*v, kMinResolution_deg, 360.0, " degrees");
    o.resolution_rad = deg * kDegToRad;
  }
  if (o.resolution_rad > o.fov_rad) {
    // Only reachable when one of the two is given: the defaults are consistent.
    const std::optional<Field> where =
        m.Get("resolution_deg") ? m.Get("resolution_deg") : m.Get("fov_deg");
    Fail(*where, fmt::format("the resolution ({} deg) is coarser than the field of view ({} deg)",
                             o.resolution_rad / kDegToRad, o.fov_rad / kDegToRad));
  }
  if (const auto v = m.Get("rate_hz")) o.rate_hz = Rate(*v);
  if (const auto v = m.Get("range_noise")) o.range_noise_m = NonNegative(*v, kMaxSize_m, "m");
  if (const auto v = m.Get("dropout")) o.dropout = Probability(*v);
  return o;
}

sim::StereoOptions ParseStereo(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"x", "y", "yaw", "fov_deg", "max_depth", "rate_hz", "miss_rate", "false_rate",
              "class_accuracy"});
  sim::StereoOptions o;
  if (const auto v = m.Get("x")) o.x_m = MountOffset(*v);
  if (const auto v = m.Get("y")) o.y_m = MountOffset(*v);
  if (const auto v = m.Get("yaw")) o.yaw_rad = Number(*v);
  if (const auto v = m.Get("fov_deg")) o.fov_rad = FieldOfView(*v);
  if (const auto v = m.Get("max_depth")) o.max_depth_m = Positive(*v, kMaxCoordinate_m, "m");
  if (const auto v = m.Get("rate_hz")) o.rate_hz = Rate(*v);
  if (const auto v = m.Get("miss_rate")) o.miss_rate = Probability(*v);
  // An expected count per frame, not a probability.
  if (const auto v = m.Get("false_rate")) {
    o.false_rate = NonNegative(*v, kMaxFalseObjectsPerFrame, "per frame");
  }
  if (const auto v = m.Get("class_accuracy")) o.class_accuracy = Probability(*v);
  return o;
}

sim::OdometryOptions ParseOdometry(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"rate_hz", "speed_noise", "yaw_rate_noise"});
  sim::OdometryOptions o;
  if (const auto v = m.Get("rate_hz")) o.rate_hz = Rate(*v);
  if (const auto v = m.Get("speed_noise"))
    o.speed_noise_mps = NonNegative(*v, kMaxSpeed_mps, "m/s");
  if (const auto v = m.Get("yaw_rate_noise"))
    o.yaw_rate_noise_radps = NonNegative(*v, 10.0, "rad/s");
  return o;
}

sim::Sensors ParseSensors(const Field& f) {
  const Mapping m(f);
  m.OnlyKeys({"lidar", "stereo", "odometry"});
  sim::Sensors s;
  if (const auto v = m.Get("lidar")) s.lidar = ParseLidar(*v);
  if (const auto v = m.Get("stereo")) s.stereo = ParseStereo(*v);
  if (const auto v = m.Get("odometry")) s.odometry = ParseOdometry(*v);
  return s;
}

sim::Expectation ParseExpect(const Field& f, double duration_s) {
  const Mapping m(f);
  m.OnlyKeys({"warning", "warn_before"});
  sim::Expectation e;
  if (const auto v = m.Get("warning")) e.warning = Bool(*v);
  if (const auto v = m.Get("warn_before")) {
    // A deadline for a warning that must not be raised has no meaning: likely a slip.
    if (e.warning != true) Fail(*v, "only meaningful with warning: true");
    e.warn_before_s = NonNegative(*v, duration_s, "s (the scenario's duration)");
  }
  return e;
}

std::string ParseName(const Field& f) {
  const std::string name = String(f);
  const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
  });
  if (!ok) Fail(f, fmt::format("must match [a-z0-9-]+, got {}", Describe(f.node)));
  return name;
}

sim::Scenario ParseScenario(const Field& root) {
  const Mapping top(root);
  // The version first: a file from a later format should be refused as such, not for the
  // keys this version does not know.
  const Field format = top.Require("format");
  sim::Scenario s;
  s.format = Integer<int>(format, "the integer 1");
  if (s.format != 1)
    Fail(format, fmt::format("unsupported format {} (this program reads format 1)", s.format));
  top.OnlyKeys({"format", "name", "description", "duration", "seed", "world", "ego", "actors",
                "sensors", "expect"});
  s.source = *root.source;
  s.name = ParseName(top.Require("name"));
  if (const auto v = top.Get("description")) s.description = String(*v);
  s.duration_s = Positive(top.Require("duration"), kMaxDuration_s, "s");
  if (const auto v = top.Get("seed")) {
    s.seed = Integer<std::uint64_t>(*v, "a non-negative integer");
  }
  if (const auto v = top.Get("world")) s.world = ParseWorld(*v);
  s.ego = ParseEgo(top.Require("ego"));
  if (const auto v = top.Get("actors")) s.actors = ParseActors(*v, s.duration_s);
  if (const auto v = top.Get("sensors")) s.sensors = ParseSensors(*v);
  if (const auto v = top.Get("expect")) s.expect = ParseExpect(*v, s.duration_s);
  return s;
}

int MarkLine(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

// Parse events are ignored; only where each document starts is kept.
class DocumentStartRecorder final : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override { start = mark; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  YAML::Mark start;
};

// Refuses text that is not exactly one YAML document. This pass exists because yaml-cpp 0.7's
// LoadAll never returns on a stray ',' outside any collection (found by fuzzing): its parser
// reports an empty document without consuming the token, and LoadAll keeps collecting them
// until memory runs out. Here a document that starts where the previous one did is that stuck
// token, refused as the syntax error it is. Throws yaml-cpp's exceptions for other errors.
void CheckOneDocument(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStartRecorder recorder;
  std::vector<YAML::Mark> starts;
  // Three documents at most: a stuck token shows on the first repeat, and two are too many.
  while (starts.size() < 3 && parser.HandleNextDocument(recorder)) {
    if (!starts.empty() && recorder.start.pos == starts.back().pos) {
      const std::size_t pos = static_cast<std::size_t>(recorder.start.pos);
      const char c = pos < text.size() ? text[pos] : '?';
      throw InputError(
          source, MarkLine(recorder.start), "",
          fmt::format("YAML syntax error: unexpected '{}'", c >= ' ' && c <= '~' ? c : '?'));
    }
    starts.push_back(recorder.start);
  }
  if (starts.empty()) throw InputError(source, 0, "", "is empty (no YAML document)");
  if (starts.size() > 1) {
    throw InputError(source, MarkLine(starts[1]), "",
                     "holds more than one YAML document; a scenario is one");
  }
}

YAML::Node ParseOneDocument(const std::string& text, const std::string& source) {
  try {
    CheckOneDocument(text, source);
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(source, MarkLine(e.mark), "", fmt::format("YAML syntax error: {}", e.msg));
  }
}

}  // namespace

sim::Scenario LoadScenarioText(std::string_view yaml, const std::string& source) {
  // yaml-cpp builds the whole document in memory: bound what it is handed.
  if (yaml.size() > kMaxInputBytes) {
    throw InputError(source, 0, "",
                     fmt::format("is {} bytes; scenario files are limited to {} bytes", yaml.size(),
                                 kMaxInputBytes));
  }
  const Field root(ParseOneDocument(std::string(yaml), source), "", 1, &source);
  if (!root.node.IsMap())
    Fail(root, fmt::format("expected a mapping of scenario fields, got {}", Describe(root.node)));
  // The readers above only use node accessors that cannot throw on the checked node types;
  // this keeps that promise if one ever does: the only error a caller sees is InputError.
  try {
    return ParseScenario(root);
  } catch (const YAML::Exception& e) {
    throw InputError(source, MarkLine(e.mark), "", fmt::format("unexpected YAML error: {}", e.msg));
  }
}

sim::Scenario LoadScenarioFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path, 0, "", "cannot open: it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the file for reading");
  // Read one byte past the limit so that an oversized file is refused without reading it all.
  std::string text(kMaxInputBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw InputError(path, 0, "", "cannot read the file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  return LoadScenarioText(text, path);
}

sim::Scenario LoadDefaultScenario() {
  return LoadScenarioText(DefaultScenarioYaml(), std::string(kDefaultScenarioSource));
}

}  // namespace lookout::io
