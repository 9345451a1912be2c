#include "lookout/io/scenario_loader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/io/default_scenario.h"

namespace lookout::io {
namespace {

constexpr double kPi = std::numbers::pi;

// A valid scenario of six lines; most refusal tests append a few lines to it, so that the line
// a message names is easy to count: the first appended line is line 7.
constexpr std::string_view kMinimal = R"(format: 1
name: minimal
duration: 10
ego:
  path: [[0, 0], [20, 0]]
  speed: 5
)";

std::string Minimal(std::string_view appended) {
  return std::string(kMinimal) + std::string(appended);
}

// Loads `yaml` expecting an InputError that names test.yaml, `line` and `field`, with a
// problem containing `problem`; the message must read "test.yaml:LINE: FIELD: ...".
testing::AssertionResult Refused(std::string_view yaml, int line, std::string_view field,
                                 std::string_view problem) {
  try {
    LoadScenarioText(yaml, "test.yaml");
  } catch (const InputError& e) {
    std::string prefix = line > 0 ? fmt::format("test.yaml:{}: ", line) : "test.yaml: ";
    if (!field.empty()) prefix += fmt::format("{}: ", field);
    const std::string what = e.what();
    if (e.file() == "test.yaml" && e.line() == line && e.field() == field &&
        what.starts_with(prefix) && e.problem().find(problem) != std::string::npos) {
      return testing::AssertionSuccess();
    }
    return testing::AssertionFailure()
           << "expected \"" << prefix << "..." << problem << "...\", got \"" << what << "\"";
  } catch (const std::exception& e) {
    return testing::AssertionFailure() << "threw something other than InputError: " << e.what();
  }
  return testing::AssertionFailure() << "loaded without error";
}

// ---------------------------------------------------------------------------------------------
// Files that load

TEST(ScenarioLoaderTest, MinimalFileGetsEveryDefault) {
  const sim::Scenario s = LoadScenarioText(kMinimal, "min.yaml");
  EXPECT_EQ(s.format, 1);
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.duration_s, 10.0);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.source, "min.yaml");
  EXPECT_FALSE(s.world.preset.has_value());
  EXPECT_TRUE(s.world.obstacles.empty());
  EXPECT_EQ(s.ego.length_m, 4.6);
  EXPECT_EQ(s.ego.width_m, 1.9);
  ASSERT_EQ(s.ego.path.size(), 2u);
  EXPECT_EQ(s.ego.path[1], Eigen::Vector2d(20, 0));
  EXPECT_TRUE(s.actors.empty());
  EXPECT_FALSE(s.expect.warning.has_value());
  EXPECT_FALSE(s.expect.warn_before_s.has_value());
  // Sensor defaults are the struct's, which are the format page's.
  const sim::Sensors defaults;
  EXPECT_EQ(s.sensors.lidar.fov_rad, defaults.lidar.fov_rad);
  EXPECT_EQ(s.sensors.stereo.max_depth_m, defaults.stereo.max_depth_m);
  EXPECT_EQ(s.sensors.odometry.rate_hz, defaults.odometry.rate_hz);
}

TEST(ScenarioLoaderTest, ConstantSpeedIsAOnePointProfile) {
  const sim::Scenario s = LoadScenarioText(kMinimal, "min.yaml");
  ASSERT_EQ(s.ego.speed.points.size(), 1u);
  EXPECT_EQ(s.ego.speed.points[0], Eigen::Vector2d(0.0, 5.0));
  EXPECT_EQ(s.ego.speed.At(7.0), 5.0);
}

// The example on docs/scenario-format.md, verbatim apart from choosing `speed_profile` for the
// ego (the page shows both as alternatives).
constexpr std::string_view kFormatPageExample =
    R"(format: 1                      # required; any other value is refused
name: left-turn-across-path    # required, [a-z0-9-]+
description: Ego drives straight at 40 km/h; an oncoming car turns left across its path.
duration: 12.0                 # required, s, > 0
seed: 7                        # optional (default 0): every random draw derives from it

world:                          # optional
  preset: four_way
  obstacles:
    - {kind: building, polygon: [[-40, 10], [-10, 10], [-10, 40], [-40, 40]]}
    - {kind: pole, center: [8, -6], radius: 0.15}
    - {kind: parked_car, center: [5, -4.5], heading: 0, length: 4.5, width: 1.8}
    - {kind: sign, center: [12, -5], radius: 0.1}

ego:                            # required
  length: 4.6                   # optional, defaults shown
  width: 1.9
  path: [[-60, -1.75], [60, -1.75]]       # required, >= 2 waypoints; the vehicle follows it
  speed_profile: [[0, 11.1], [4, 11.1], [6, 0]]   # (t, v) pairs, linear in between

actors:                          # optional list
  - id: car1                     # required, unique
    class: car                   # car | truck | cyclist | pedestrian
    length: 4.5                  # boxes: car, truck, cyclist (defaults by class)
    width: 1.8
    path: [[60, 1.75], [5, 1.75], [-1.75, -5], [-1.75, -60]]
    speed: 8.0                   # or speed_profile, as for ego
    start: 0.0                   # s: the actor exists from this time, at its first waypoint
    stop: 12.0                   # optional: removed after this time

sensors:                         # optional; defaults are the seed vehicle's
  lidar:    {x: 2.2, y: 0.0, yaw: 0.0, fov_deg: 160, max_range: 150, resolution_deg: 0.25,
             rate_hz: 12.5, range_noise: 0.03, dropout: 0.005}
  stereo:   {x: 0.8, y: 0.0, yaw: 0.0, fov_deg: 70, max_depth: 35, rate_hz: 20,
             miss_rate: 0.05, false_rate: 0.1, class_accuracy: 0.9}
  odometry: {rate_hz: 50, speed_noise: 0.05, yaw_rate_noise: 0.005}

expect:                          # optional: what the scoring checks
  warning: true                  # a collision warning must (true) or must not (false) be raised
  warn_before: 6.5               # s, scenario time by which a required warning must be raised
)";

TEST(ScenarioLoaderTest, LoadsTheFormatPageExample) {
  const sim::Scenario s = LoadScenarioText(kFormatPageExample, "doc.yaml");
  EXPECT_EQ(s.name, "left-turn-across-path");
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.world.preset, "four_way");
  ASSERT_EQ(s.world.obstacles.size(), 4u);
  EXPECT_EQ(s.world.obstacles[0].kind, sim::ObstacleKind::kBuilding);
  EXPECT_EQ(s.world.obstacles[0].polygon.size(), 4u);
  EXPECT_EQ(s.world.obstacles[1].kind, sim::ObstacleKind::kPole);
  EXPECT_EQ(s.world.obstacles[1].radius_m, 0.15);
  EXPECT_EQ(s.world.obstacles[2].kind, sim::ObstacleKind::kParkedCar);
  EXPECT_EQ(s.world.obstacles[2].center_m, Eigen::Vector2d(5, -4.5));
  EXPECT_EQ(s.world.obstacles[3].kind, sim::ObstacleKind::kSign);
  ASSERT_EQ(s.ego.speed.points.size(), 3u);
  EXPECT_EQ(s.ego.speed.points[2], Eigen::Vector2d(6, 0));
  ASSERT_EQ(s.actors.size(), 1u);
  EXPECT_EQ(s.actors[0].id, "car1");
  EXPECT_EQ(s.actors[0].object_class, ObjectClass::kCar);
  EXPECT_EQ(s.actors[0].path.size(), 4u);
  EXPECT_EQ(s.actors[0].stop_s, 12.0);
  EXPECT_NEAR(s.sensors.lidar.fov_rad, 160.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(s.sensors.lidar.resolution_rad, 0.25 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(s.sensors.stereo.fov_rad, 70.0 * kPi / 180.0, 1e-12);
  EXPECT_EQ(s.sensors.stereo.false_rate, 0.1);
  EXPECT_EQ(s.sensors.odometry.yaw_rate_noise_radps, 0.005);
  EXPECT_EQ(s.expect.warning, true);
  EXPECT_EQ(s.expect.warn_before_s, 6.5);
}

TEST(ScenarioLoaderTest, DegreesBecomeRadians) {
  const sim::Scenario s = LoadScenarioText(Minimal(R"(sensors:
  lidar: {fov_deg: 90, resolution_deg: 0.5}
  stereo: {fov_deg: 360}
)"),
                                           "t.yaml");
  EXPECT_NEAR(s.sensors.lidar.fov_rad, kPi / 2.0, 1e-12);
  EXPECT_NEAR(s.sensors.lidar.resolution_rad, kPi / 360.0, 1e-12);
  EXPECT_NEAR(s.sensors.stereo.fov_rad, 2.0 * kPi, 1e-12);
}

TEST(ScenarioLoaderTest, EachSensorFieldDefaultsOnItsOwn) {
  const sim::Scenario s = LoadScenarioText(Minimal(R"(sensors:
  lidar: {max_range: 80}
  odometry: {speed_noise: 0.1}
)"),
                                           "t.yaml");
  const sim::Sensors defaults;
  EXPECT_EQ(s.sensors.lidar.max_range_m, 80.0);
  EXPECT_EQ(s.sensors.lidar.x_m, defaults.lidar.x_m);
  EXPECT_EQ(s.sensors.lidar.rate_hz, defaults.lidar.rate_hz);
  EXPECT_EQ(s.sensors.lidar.dropout, defaults.lidar.dropout);
  EXPECT_EQ(s.sensors.odometry.speed_noise_mps, 0.1);
  EXPECT_EQ(s.sensors.odometry.rate_hz, defaults.odometry.rate_hz);
  EXPECT_EQ(s.sensors.stereo.class_accuracy, defaults.stereo.class_accuracy);
}

TEST(ScenarioLoaderTest, ActorsGetDefaultsByClass) {
  const sim::Scenario s = LoadScenarioText(Minimal(R"(actors:
  - {id: c, class: car, path: [[0, 5], [10, 5]], speed: 1}
  - {id: t, class: truck, path: [[0, 5], [10, 5]], speed: 1, start: 2}
  - {id: b, class: cyclist, path: [[0, 5], [10, 5]], speed: 1, stop: 4}
  - {id: p, class: pedestrian, path: [[0, 5], [10, 5]], speed: 1}
  - {id: k, class: pedestrian, radius: 0.25, path: [[0, 5], [10, 5]], speed: 1}
)"),
                                           "t.yaml");
  ASSERT_EQ(s.actors.size(), 5u);
  EXPECT_EQ(s.actors[0].length_m, sim::DefaultLength(ObjectClass::kCar));
  EXPECT_EQ(s.actors[0].width_m, sim::DefaultWidth(ObjectClass::kCar));
  EXPECT_EQ(s.actors[1].object_class, ObjectClass::kTruck);
  EXPECT_EQ(s.actors[1].length_m, sim::DefaultLength(ObjectClass::kTruck));
  EXPECT_EQ(s.actors[2].width_m, sim::DefaultWidth(ObjectClass::kCyclist));
  EXPECT_EQ(s.actors[3].radius_m, 0.3);
  EXPECT_EQ(s.actors[4].radius_m, 0.25);
  EXPECT_EQ(s.actors[0].start_s, 0.0);
  EXPECT_EQ(s.actors[0].stop_s, 10.0);  // the scenario's duration
  EXPECT_EQ(s.actors[1].start_s, 2.0);
  EXPECT_EQ(s.actors[2].stop_s, 4.0);
}

TEST(ScenarioLoaderTest, ZeroSpeedIsAllowed) {
  const sim::Scenario s = LoadScenarioText(Minimal(R"(actors:
  - {id: p, class: pedestrian, path: [[0, 5], [10, 5]], speed: 0}
)"),
                                           "t.yaml");
  EXPECT_EQ(s.actors[0].speed.At(3.0), 0.0);
}

TEST(ScenarioLoaderTest, ParkedCarFootprintDefaultsToACar) {
  const sim::Scenario s = LoadScenarioText(Minimal(R"(world:
  obstacles:
    - {kind: parked_car, center: [5, -4.5]}
)"),
                                           "t.yaml");
  ASSERT_EQ(s.world.obstacles.size(), 1u);
  EXPECT_EQ(s.world.obstacles[0].length_m, sim::DefaultLength(ObjectClass::kCar));
  EXPECT_EQ(s.world.obstacles[0].heading_rad, 0.0);
}

TEST(ScenarioLoaderTest, AcceptsYamlNumberSpellings) {
  const sim::Scenario s = LoadScenarioText(R"(format: 1
name: spellings
duration: +1.2e1
seed: 18446744073709551615
ego: {path: [[-.5, 0], [20., 0]], speed: !!float 5}
)",
                                           "t.yaml");
  EXPECT_EQ(s.duration_s, 12.0);
  EXPECT_EQ(s.seed, 18446744073709551615u);
  EXPECT_EQ(s.ego.path[0].x(), -0.5);
}

TEST(ScenarioLoaderTest, DefaultScenarioIsTheLeftTurnFile) {
  const sim::Scenario s = LoadDefaultScenario();
  EXPECT_EQ(s.name, "left-turn-across-path");
  EXPECT_EQ(s.source, kDefaultScenarioSource);
  EXPECT_EQ(s.expect.warning, true);
}

TEST(ScenarioLoaderTest, LoadsAFileAndNamesItInMessages) {
  const std::filesystem::path dir = testing::TempDir();
  const std::string path = (dir / fmt::format("loader-test-{}.yaml", getpid())).string();
  {
    std::ofstream out(path);
    out << kMinimal << "colour: red\n";
  }
  try {
    LoadScenarioFile(path);
    ADD_FAILURE() << "loaded a file with an unknown key";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), 7);
    EXPECT_EQ(e.field(), "colour");
  }
  {
    std::ofstream out(path);
    out << kMinimal;
  }
  EXPECT_EQ(LoadScenarioFile(path).source, path);
  std::filesystem::remove(path);
}

TEST(ScenarioLoaderTest, FileThatCannotBeOpened) {
  try {
    LoadScenarioFile("/nonexistent/dir/none.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/dir/none.yaml");
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.field(), "");
    EXPECT_NE(e.problem().find("cannot open"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LoadScenarioFile(testing::TempDir()), InputError);  // a directory
}

// Every file of the catalogue loads, is named after its file, and says what it expects.
TEST(ScenarioLoaderTest, CatalogueLoadsAndNamesMatchFiles) {
  const std::filesystem::path dir = std::filesystem::path(LOOKOUT_SOURCE_DIR) / "scenarios";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    const sim::Scenario s = LoadScenarioFile(entry.path().string());
    EXPECT_EQ(s.name, entry.path().stem().string());
    EXPECT_FALSE(s.description.empty());
    ASSERT_TRUE(s.expect.warning.has_value());
    EXPECT_EQ(s.expect.warn_before_s.has_value(), *s.expect.warning);
  }
  EXPECT_GE(count, 12);
}

// ---------------------------------------------------------------------------------------------
// Files that are refused: one test per rule, each checking the line and field named.

TEST(ScenarioLoaderRefusesTest, EmptyFile) {
  EXPECT_TRUE(Refused("", 0, "", "empty"));
  EXPECT_TRUE(Refused("# only a comment\n", 0, "", "empty"));
}

TEST(ScenarioLoaderRefusesTest, YamlSyntaxErrorAtItsLine) {
  EXPECT_TRUE(Refused(Minimal("actors: [{id: a\nseed: 1\n"), 8, "", "YAML syntax error"));
}

TEST(ScenarioLoaderRefusesTest, BadIndentationIsASyntaxError) {
  EXPECT_TRUE(Refused("format: 1\nname: x\n  duration: 3\n", 3, "", "YAML syntax error"));
}

// yaml-cpp's LoadAll never returns on these (found by fuzzing); the loader must refuse them.
TEST(ScenarioLoaderRefusesTest, StrayCommaOutsideACollection) {
  EXPECT_TRUE(Refused(",", 1, "", "YAML syntax error: unexpected ','"));
  EXPECT_TRUE(Refused("\n\n, format: 1\n", 3, "", "YAML syntax error: unexpected ','"));
}

TEST(ScenarioLoaderRefusesTest, StrayCommaAfterAFlowMapping) {
  EXPECT_TRUE(Refused("{format: 1, name: x},\n", 1, "", "YAML syntax error: unexpected ','"));
}

TEST(ScenarioLoaderRefusesTest, TopLevelNotAMapping) {
  EXPECT_TRUE(Refused("- format: 1\n", 1, "", "expected a mapping"));
}

TEST(ScenarioLoaderRefusesTest, MoreThanOneDocument) {
  EXPECT_TRUE(Refused(Minimal("---\nformat: 1\n"), 7, "", "more than one YAML document"));
}

TEST(ScenarioLoaderRefusesTest, TooLargeInput) {
  EXPECT_TRUE(
      Refused(Minimal("#" + std::string(std::size_t{1} << 20, 'x') + "\n"), 0, "", "limited to"));
}

TEST(ScenarioLoaderRefusesTest, UnknownTopLevelKey) {
  EXPECT_TRUE(Refused(Minimal("durration: 3\n"), 7, "durration", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInEgo) {
  EXPECT_TRUE(Refused(Minimal("  heading: 0\n"), 7, "ego.heading", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInActor) {
  EXPECT_TRUE(Refused(Minimal(R"(actors:
  - id: a
    class: car
    path: [[0, 5], [10, 5]]
    speeed: 3
)"),
                      11, "actors[0].speeed", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInWorld) {
  EXPECT_TRUE(Refused(Minimal("world:\n  preset: four_way\n  roads: 2\n"), 9, "world.roads",
                      "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInObstacle) {
  // A field of another kind is unknown for this one.
  EXPECT_TRUE(Refused(Minimal(R"(world:
  obstacles:
    - {kind: pole, center: [8, -6], radius: 0.15}
    - {kind: sign, center: [8, -6], radius: 0.1,
       polygon: [[0, 0], [1, 0], [1, 1]]}
)"),
                      11, "world.obstacles[1].polygon", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownSensor) {
  EXPECT_TRUE(
      Refused(Minimal("sensors:\n  radar: {rate_hz: 10}\n"), 8, "sensors.radar", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInLidar) {
  EXPECT_TRUE(
      Refused(Minimal("sensors:\n  lidar:\n    fov: 90\n"), 9, "sensors.lidar.fov", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInStereo) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {max_range: 30}\n"), 8,
                      "sensors.stereo.max_range", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInOdometry) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  odometry: {noise: 1}\n"), 8, "sensors.odometry.noise",
                      "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, UnknownKeyInExpect) {
  EXPECT_TRUE(Refused(Minimal("expect:\n  warning: false\n  warn_after: 3\n"), 9,
                      "expect.warn_after", "unknown key"));
}

TEST(ScenarioLoaderRefusesTest, RepeatedKey) {
  EXPECT_TRUE(Refused(Minimal("duration: 12\n"), 7, "duration", "repeated key (first at line 3)"));
}

TEST(ScenarioLoaderRefusesTest, KeyThatIsNotAName) {
  EXPECT_TRUE(Refused(Minimal("[a, b]: 1\n"), 7, "", "a key must be a name"));
}

TEST(ScenarioLoaderRefusesTest, StringWhereNumber) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: ten\n", 3, "duration",
                      "expected a number, got 'ten'"));
}

TEST(ScenarioLoaderRefusesTest, QuotedNumberIsAString) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: \"10\"\n", 3, "duration",
                      "expected a number, got the string \"10\""));
}

TEST(ScenarioLoaderRefusesTest, NumberWithTrailingText) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 10s\n", 3, "duration", "expected a number"));
}

TEST(ScenarioLoaderRefusesTest, CSpellingOfInfinityIsNotANumber) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: inf\n", 3, "duration", "expected a number"));
}

TEST(ScenarioLoaderRefusesTest, ScalarWhereList) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  path: 5\n  speed: 1\n", 5,
                      "ego.path", "expected a list"));
}

TEST(ScenarioLoaderRefusesTest, MappingWhereList) {
  EXPECT_TRUE(
      Refused(Minimal("actors:\n  id: a\n"), 8, "actors", "expected a list, got a mapping"));
}

TEST(ScenarioLoaderRefusesTest, ListWhereString) {
  EXPECT_TRUE(Refused("format: 1\nname: [a, b]\n", 2, "name", "expected a string, got a list"));
}

TEST(ScenarioLoaderRefusesTest, ScalarWhereMapping) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego: fast\n", 4, "ego",
                      "expected a mapping, got 'fast'"));
}

TEST(ScenarioLoaderRefusesTest, WaypointThatIsNotAPair) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [1, 2, 3]]\n  speed: 1\n", 5,
              "ego.path[1]", "expected a point [x, y], got a list of 3"));
}

TEST(ScenarioLoaderRefusesTest, NumberWhereBool) {
  EXPECT_TRUE(
      Refused(Minimal("expect:\n  warning: 1\n"), 8, "expect.warning", "expected true or false"));
}

TEST(ScenarioLoaderRefusesTest, NegativeSeed) {
  EXPECT_TRUE(Refused(Minimal("seed: -1\n"), 7, "seed", "expected a non-negative integer"));
}

TEST(ScenarioLoaderRefusesTest, FractionalSeed) {
  EXPECT_TRUE(Refused(Minimal("seed: 1.5\n"), 7, "seed", "expected a non-negative integer"));
}

TEST(ScenarioLoaderRefusesTest, KeyWithoutValue) {
  // yaml-cpp marks a null at the next token; the message names the key's own line.
  EXPECT_TRUE(Refused(Minimal("description:\n\n\nseed: 1\n"), 7, "description", "has no value"));
}

TEST(ScenarioLoaderRefusesTest, MissingFormat) {
  EXPECT_TRUE(Refused("name: x\nduration: 3\n", 1, "format", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingName) {
  EXPECT_TRUE(Refused("format: 1\nduration: 3\nego: {path: [[0, 0], [1, 0]], speed: 1}\n", 1,
                      "name", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingDuration) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nego: {path: [[0, 0], [1, 0]], speed: 1}\n", 1,
                      "duration", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingEgo) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\n", 1, "ego", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingEgoPath) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  speed: 1\n", 5, "ego.path",
                      "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingEgoSpeed) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [1, 0]]\n", 5,
                      "ego.speed", "give speed or speed_profile"));
}

TEST(ScenarioLoaderRefusesTest, MissingActorId) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {class: car, path: [[0, 5], [10, 5]], speed: 1}\n"), 8,
                      "actors[0].id", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingActorClass) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {id: a, path: [[0, 5], [10, 5]], speed: 1}\n"), 8,
                      "actors[0].class", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingActorPath) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {id: a, class: car, speed: 1}\n"), 8, "actors[0].path",
                      "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingActorSpeed) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - id: a\n    class: car\n    path: [[0, 5], [10, 5]]\n"),
                      8, "actors[0].speed", "give speed or speed_profile"));
}

TEST(ScenarioLoaderRefusesTest, MissingObstacleKind) {
  EXPECT_TRUE(Refused(Minimal("world:\n  obstacles:\n    - {center: [1, 1], radius: 1}\n"), 9,
                      "world.obstacles[0].kind", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, MissingObstacleField) {
  EXPECT_TRUE(Refused(Minimal("world:\n  obstacles:\n    - {kind: pole, center: [1, 1]}\n"), 9,
                      "world.obstacles[0].radius", "required but missing"));
}

TEST(ScenarioLoaderRefusesTest, FormatOtherThanOne) {
  // Refused as a format, not for keys a later format might add.
  EXPECT_TRUE(Refused("name: x\nformat: 2\nlanes: 3\n", 2, "format", "unsupported format 2"));
}

TEST(ScenarioLoaderRefusesTest, FormatNotAnInteger) {
  EXPECT_TRUE(Refused("format: 1.0\n", 1, "format", "expected the integer 1"));
}

TEST(ScenarioLoaderRefusesTest, NameWithCapitals) {
  EXPECT_TRUE(Refused("format: 1\nname: Left_Turn\n", 2, "name", "must match [a-z0-9-]+"));
}

TEST(ScenarioLoaderRefusesTest, EmptyName) {
  EXPECT_TRUE(Refused("format: 1\nname: ''\n", 2, "name", "must match [a-z0-9-]+"));
}

TEST(ScenarioLoaderRefusesTest, ZeroDuration) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 0\n", 3, "duration", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeDuration) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: -4\n", 3, "duration", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, DurationBeyondLimit) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 1e9\n", 3, "duration", "must be at most"));
}

TEST(ScenarioLoaderRefusesTest, EgoPathWithOneWaypoint) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0]]\n  speed: 1\n", 5,
                      "ego.path", "at least 2 waypoints"));
}

TEST(ScenarioLoaderRefusesTest, ActorPathWithOneWaypoint) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {id: a, class: car, path: [[0, 5]], speed: 1}\n"), 8,
                      "actors[0].path", "at least 2 waypoints"));
}

TEST(ScenarioLoaderRefusesTest, RepeatedWaypoint) {
  EXPECT_TRUE(Refused(R"(format: 1
name: x
duration: 3
ego:
  path:
    - [0, 0]
    - [5, 0]
    - [5, 0]
  speed: 1
)",
                      8, "ego.path[2]", "zero-length segment"));
}

TEST(ScenarioLoaderRefusesTest, UnknownClass) {
  EXPECT_TRUE(
      Refused(Minimal("actors:\n  - {id: a, class: bus, path: [[0, 5], [1, 5]], speed: 1}\n"), 8,
              "actors[0].class", "unknown class 'bus'"));
}

TEST(ScenarioLoaderRefusesTest, StereoOnlyClassIsNotAnActor) {
  EXPECT_TRUE(
      Refused(Minimal("actors:\n  - {id: a, class: pole, path: [[0, 5], [1, 5]], speed: 1}\n"), 8,
              "actors[0].class", "unknown class 'pole'"));
}

TEST(ScenarioLoaderRefusesTest, UnknownObstacleKind) {
  EXPECT_TRUE(Refused(Minimal("world:\n  obstacles:\n    - {kind: tree, center: [1, 1]}\n"), 9,
                      "world.obstacles[0].kind", "unknown obstacle kind 'tree'"));
}

TEST(ScenarioLoaderRefusesTest, UnknownPreset) {
  EXPECT_TRUE(
      Refused(Minimal("world: {preset: roundabout}\n"), 7, "world.preset", "unknown preset"));
}

TEST(ScenarioLoaderRefusesTest, DuplicateActorIds) {
  EXPECT_TRUE(Refused(Minimal(R"(actors:
  - {id: a, class: car, path: [[0, 5], [10, 5]], speed: 1}
  - {id: b, class: car, path: [[0, 9], [10, 9]], speed: 1}
  - {id: a, class: car, path: [[0, 13], [10, 13]], speed: 1}
)"),
                      10, "actors[2].id", "duplicate actor id 'a' (first at line 8)"));
}

TEST(ScenarioLoaderRefusesTest, EmptyActorId) {
  EXPECT_TRUE(
      Refused(Minimal("actors:\n  - {id: '', class: car, path: [[0, 5], [1, 5]], speed: 1}\n"), 8,
              "actors[0].id", "must not be empty"));
}

TEST(ScenarioLoaderRefusesTest, NotANumber) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: .nan\n", 3, "duration", "finite"));
}

TEST(ScenarioLoaderRefusesTest, InfiniteCoordinate) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [-.inf, 0]]\n", 5,
                      "ego.path[1][0]", "finite"));
}

TEST(ScenarioLoaderRefusesTest, InfiniteSpeed) {
  EXPECT_TRUE(
      Refused(Minimal("actors:\n  - {id: a, class: car, path: [[0, 5], [1, 5]], speed: .Inf}\n"), 8,
              "actors[0].speed", "finite"));
}

TEST(ScenarioLoaderRefusesTest, OverflowingNumber) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 1e999\n", 3, "duration", "out of range"));
}

TEST(ScenarioLoaderRefusesTest, CoordinateBeyondLimit) {
  EXPECT_TRUE(Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [1e7, 0]]\n", 5,
                      "ego.path[1][0]", "must be in [-100000, 100000] m"));
}

TEST(ScenarioLoaderRefusesTest, ProfileTimesOutOfOrder) {
  EXPECT_TRUE(Refused(Minimal(R"(actors:
  - id: a
    class: car
    path: [[0, 5], [10, 5]]
    speed_profile:
      - [0, 5]
      - [3, 5]
      - [2, 0]
)"),
                      14, "actors[0].speed_profile[2]", "times must increase strictly"));
}

TEST(ScenarioLoaderRefusesTest, ProfileTimesRepeated) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed_profile: [[0, 5], [1, 4], [1, 3]]\n",
              6, "ego.speed_profile[2]", "times must increase strictly"));
}

TEST(ScenarioLoaderRefusesTest, ProfilePairOfWrongShape) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed_profile: [[0, 5], 4]\n",
              6, "ego.speed_profile[1]", "expected a pair [t, v]"));
}

TEST(ScenarioLoaderRefusesTest, EmptyProfile) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed_profile: []\n",
              6, "ego.speed_profile", "at least one [t, v] pair"));
}

TEST(ScenarioLoaderRefusesTest, NegativeProfileTime) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed_profile: [[-1, 5]]\n",
              6, "ego.speed_profile[0][0]", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeSpeed) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed: -2\n",
              6, "ego.speed", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeSpeedInProfile) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed_profile: [[0, 5], [2, -1]]\n",
              6, "ego.speed_profile[1][1]", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, SpeedBeyondLimit) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed: 340\n",
              6, "ego.speed", "must be at most 100"));
}

TEST(ScenarioLoaderRefusesTest, BothSpeedAndProfile) {
  EXPECT_TRUE(
      Refused("format: 1\nname: x\nduration: 3\nego:\n  path: [[0, 0], [9, 0]]\n"
              "  speed: 3\n  speed_profile: [[0, 3]]\n",
              7, "ego.speed_profile", "not both"));
}

TEST(ScenarioLoaderRefusesTest, ZeroEgoWidth) {
  EXPECT_TRUE(Refused(Minimal("  width: 0\n"), 7, "ego.width", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeActorLength) {
  EXPECT_TRUE(Refused(
      Minimal("actors:\n  - {id: a, class: car, length: -4, path: [[0, 5], [1, 5]], speed: 1}\n"),
      8, "actors[0].length", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, ZeroPedestrianRadius) {
  EXPECT_TRUE(Refused(
      Minimal(
          "actors:\n  - {id: a, class: pedestrian, radius: 0, path: [[0, 5], [1, 5]], speed: 1}\n"),
      8, "actors[0].radius", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, RadiusForABox) {
  EXPECT_TRUE(Refused(
      Minimal(
          "actors:\n  - {id: a, class: cyclist, radius: 0.3, path: [[0, 5], [1, 5]], speed: 1}\n"),
      8, "actors[0].radius", "only pedestrians have a radius"));
}

TEST(ScenarioLoaderRefusesTest, LengthForAPedestrian) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {id: a, class: pedestrian, width: 0.5, path: [[0, 5], "
                              "[1, 5]], speed: 1}\n"),
                      8, "actors[0].width", "pedestrians are circles"));
}

TEST(ScenarioLoaderRefusesTest, ZeroPoleRadius) {
  EXPECT_TRUE(
      Refused(Minimal("world:\n  obstacles:\n    - {kind: pole, center: [1, 1], radius: 0}\n"), 9,
              "world.obstacles[0].radius", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeParkedCarWidth) {
  EXPECT_TRUE(Refused(
      Minimal("world:\n  obstacles:\n    - {kind: parked_car, center: [1, 1], width: -1}\n"), 9,
      "world.obstacles[0].width", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, StopBeforeStart) {
  EXPECT_TRUE(Refused(Minimal("actors:\n  - {id: a, class: car, path: [[0, 5], [1, 5]], speed: "
                              "1,\n     start: 4, stop: 2}\n"),
                      9, "actors[0].stop", "must not be before start"));
}

TEST(ScenarioLoaderRefusesTest, NegativeStart) {
  EXPECT_TRUE(Refused(
      Minimal("actors:\n  - {id: a, class: car, path: [[0, 5], [1, 5]], speed: 1, start: -1}\n"), 8,
      "actors[0].start", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, StartAfterTheEnd) {
  EXPECT_TRUE(Refused(
      Minimal("actors:\n  - {id: a, class: car, path: [[0, 5], [1, 5]], speed: 1, start: 11}\n"), 8,
      "actors[0].start", "must be at most 10"));
}

TEST(ScenarioLoaderRefusesTest, ZeroLidarRate) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {rate_hz: 0}\n"), 8, "sensors.lidar.rate_hz",
                      "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeStereoRate) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {rate_hz: -20}\n"), 8, "sensors.stereo.rate_hz",
                      "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, ZeroOdometryRate) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  odometry:\n    rate_hz: 0\n"), 9,
                      "sensors.odometry.rate_hz", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, RateBeyondLimit) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {rate_hz: 1e6}\n"), 8, "sensors.lidar.rate_hz",
                      "must be at most 1000"));
}

TEST(ScenarioLoaderRefusesTest, DropoutAboveOne) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {dropout: 1.5}\n"), 8, "sensors.lidar.dropout",
                      "must be in [0, 1]"));
}

TEST(ScenarioLoaderRefusesTest, NegativeMissRate) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {miss_rate: -0.1}\n"), 8,
                      "sensors.stereo.miss_rate", "must be in [0, 1]"));
}

TEST(ScenarioLoaderRefusesTest, ClassAccuracyAboveOne) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {class_accuracy: 2}\n"), 8,
                      "sensors.stereo.class_accuracy", "must be in [0, 1]"));
}

TEST(ScenarioLoaderRefusesTest, NegativeFalseRate) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {false_rate: -1}\n"), 8,
                      "sensors.stereo.false_rate", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeNoise) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {range_noise: -0.03}\n"), 8,
                      "sensors.lidar.range_noise", "must be >= 0"));
}

TEST(ScenarioLoaderRefusesTest, ZeroFieldOfView) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {fov_deg: 0}\n"), 8, "sensors.lidar.fov_deg",
                      "(0, 360]"));
}

TEST(ScenarioLoaderRefusesTest, FieldOfViewAbove360) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {fov_deg: 361}\n"), 8, "sensors.stereo.fov_deg",
                      "(0, 360]"));
}

TEST(ScenarioLoaderRefusesTest, ZeroMaxRange) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {max_range: 0}\n"), 8, "sensors.lidar.max_range",
                      "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, NegativeMaxDepth) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  stereo: {max_depth: -35}\n"), 8,
                      "sensors.stereo.max_depth", "must be > 0"));
}

TEST(ScenarioLoaderRefusesTest, ZeroResolution) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {resolution_deg: 0}\n"), 8,
                      "sensors.lidar.resolution_deg", "must be in [0.01, 360]"));
}

TEST(ScenarioLoaderRefusesTest, ResolutionCoarserThanFieldOfView) {
  EXPECT_TRUE(Refused(Minimal("sensors:\n  lidar: {fov_deg: 10, resolution_deg: 20}\n"), 8,
                      "sensors.lidar.resolution_deg", "coarser than the field of view"));
}

TEST(ScenarioLoaderRefusesTest, BuildingWithTwoVertices) {
  EXPECT_TRUE(
      Refused(Minimal("world:\n  obstacles:\n    - {kind: building, polygon: [[0, 0], [1, 0]]}\n"),
              9, "world.obstacles[0].polygon", "at least 3 vertices"));
}

TEST(ScenarioLoaderRefusesTest, BuildingWithoutArea) {
  EXPECT_TRUE(Refused(
      Minimal("world:\n  obstacles:\n    - {kind: building, polygon: [[0, 0], [1, 0], [2, 0]]}\n"),
      9, "world.obstacles[0].polygon", "no area"));
}

TEST(ScenarioLoaderRefusesTest, BuildingThatRepeatsItsFirstVertex) {
  EXPECT_TRUE(Refused(Minimal("world:\n  obstacles:\n    - kind: building\n      polygon: [[0, 0], "
                              "[1, 0], [1, 1], [0, 0]]\n"),
                      10, "world.obstacles[0].polygon[3]", "repeats the first vertex"));
}

TEST(ScenarioLoaderRefusesTest, WarnBeforeWithoutRequiredWarning) {
  EXPECT_TRUE(Refused(Minimal("expect:\n  warning: false\n  warn_before: 3\n"), 9,
                      "expect.warn_before", "only meaningful with warning: true"));
}

TEST(ScenarioLoaderRefusesTest, WarnBeforeAfterTheEnd) {
  EXPECT_TRUE(Refused(Minimal("expect:\n  warning: true\n  warn_before: 30\n"), 9,
                      "expect.warn_before", "must be at most 10"));
}

// yaml-cpp's parser refuses nesting deeper than about 1000 levels; that, too, must reach the
// caller as an InputError, not as a yaml-cpp exception or a stack overflow.
TEST(ScenarioLoaderRefusesTest, DeepFlowNesting) {
  const std::size_t depth = 100'000;
  EXPECT_TRUE(
      Refused("format: 1\nname: " + std::string(depth, '[') + std::string(depth, ']') + "\n", 2, "",
              "YAML syntax error"));
}

TEST(ScenarioLoaderRefusesTest, DeepBlockNesting) {
  std::string yaml = "format: 1\nname: x\nduration: 3\nego:\n  path:\n";
  for (int i = 0; i < 5000; ++i) yaml += "    - ";
  EXPECT_TRUE(Refused(yaml + "1\n", 6, "", "YAML syntax error"));
}

}  // namespace
}  // namespace lookout::io
