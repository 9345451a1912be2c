#include "lookout/risk/junction_scene.h"

#include <cmath>
#include <numbers>

#include "lookout/core/random.h"

namespace lookout::risk {

std::vector<ObjectInput> JunctionRoadUsers(int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<ObjectInput> out;
  for (int i = 0; i < count; ++i) {
    ObjectInput o;
    o.id = static_cast<std::uint32_t>(i);
    const int kind = i % 3;
    o.object_class = kind == 0 ? ObjectClass::kCar
                     : kind == 1 ? ObjectClass::kCyclist
                                 : ObjectClass::kPedestrian;
    const double heading = rng.Uniform(-std::numbers::pi, std::numbers::pi);
    const double speed = kind == 0 ? rng.Uniform(5.0, 15.0) : kind == 1 ? rng.Uniform(3.0, 7.0)
                                                                         : rng.Uniform(0.5, 2.0);
    o.position_m = {rng.Uniform(-5.0, 60.0), rng.Uniform(-20.0, 20.0)};
    o.velocity_mps = speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    o.position_covariance = Eigen::Matrix2d::Identity() * rng.Uniform(0.01, 0.5);
    o.velocity_covariance = Eigen::Matrix2d::Identity() * rng.Uniform(0.01, 1.0);
    out.push_back(o);
  }
  return out;
}

}  // namespace lookout::risk
