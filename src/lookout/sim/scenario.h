#pragma once

// A scenario as docs/scenario-format.md (version 1) defines it, after defaults are applied.
// io/scenario_loader.h builds it from YAML and checks it; the simulator takes it as given.
// Field names carry their units; every angle here is in radians (the file's *_deg fields are
// converted on load).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"

namespace lookout::sim {

// Speed over scenario time: (t, v) pairs, t strictly increasing, linear in between, held
// constant before the first pair and after the last. A constant speed is one pair (0, v).
struct SpeedProfile {
  std::vector<Eigen::Vector2d> points;  // (t_s, v_mps)

  static SpeedProfile Constant(double speed_mps) { return {{Eigen::Vector2d(0.0, speed_mps)}}; }
  double At(double t_s) const;
};

enum class ObstacleKind { kBuilding, kPole, kParkedCar, kSign };

struct Obstacle {
  ObstacleKind kind = ObstacleKind::kBuilding;
  std::vector<Eigen::Vector2d> polygon;               // building
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  // pole, sign, parked_car
  double radius_m = 0.0;                               // pole, sign
  double heading_rad = 0.0;                            // parked_car
  double length_m = 0.0;                               // parked_car
  double width_m = 0.0;                                // parked_car
};

struct World {
  std::optional<std::string> preset;  // "four_way" or none
  std::vector<Obstacle> obstacles;
};

struct EgoSpec {
  double length_m = 4.6;
  double width_m = 1.9;
  std::vector<Eigen::Vector2d> path;
  SpeedProfile speed;
};

struct ActorSpec {
  std::string id;
  ObjectClass object_class = ObjectClass::kCar;  // car, truck, cyclist or pedestrian
  double length_m = 0.0;  // boxes (car, truck, cyclist); class defaults in DefaultLength()
  double width_m = 0.0;
  double radius_m = 0.3;  // pedestrians are circles
  std::vector<Eigen::Vector2d> path;
  SpeedProfile speed;
  double start_s = 0.0;
  double stop_s = 0.0;  // the loader sets the scenario's duration when absent
};

// Default footprints by class, used when the file gives none.
double DefaultLength(ObjectClass c);
double DefaultWidth(ObjectClass c);

struct LidarOptions {
  double x_m = 2.2, y_m = 0.0, yaw_rad = 0.0;
  double fov_rad = 160.0 * 3.14159265358979323846 / 180.0;
  double max_range_m = 150.0;
  double resolution_rad = 0.25 * 3.14159265358979323846 / 180.0;
  double rate_hz = 12.5;
  double range_noise_m = 0.03;  // standard deviation
  double dropout = 0.005;       // probability that a beam returns nothing
};

struct StereoOptions {
  double x_m = 0.8, y_m = 0.0, yaw_rad = 0.0;
  double fov_rad = 70.0 * 3.14159265358979323846 / 180.0;
  double max_depth_m = 35.0;
  double rate_hz = 20.0;
  double miss_rate = 0.05;       // probability that a visible actor is not reported
  double false_rate = 0.1;       // expected false objects per frame
  double class_accuracy = 0.9;   // probability that the reported class is the true one
};

struct OdometryOptions {
  double rate_hz = 50.0;
  double speed_noise_mps = 0.05;        // standard deviation
  double yaw_rate_noise_radps = 0.005;  // standard deviation
};

struct Sensors {
  LidarOptions lidar;
  StereoOptions stereo;
  OdometryOptions odometry;
};

struct Expectation {
  std::optional<bool> warning;
  std::optional<double> warn_before_s;
};

struct Scenario {
  int format = 1;
  std::string name;
  std::string description;
  double duration_s = 0.0;
  std::uint64_t seed = 0;
  World world;
  EgoSpec ego;
  std::vector<ActorSpec> actors;
  Sensors sensors;
  Expectation expect;
  std::string source;  // the file it came from, for messages; "<default>" for the built-in one
};

}  // namespace lookout::sim
