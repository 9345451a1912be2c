#include "lookout/core/pose2.h"

#include <gtest/gtest.h>

#include <random>

namespace lookout {
namespace {

TEST(Pose2Test, ComposeWithInverseIsIdentity) {
  const unsigned seed = 20261122;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 100; ++i) {
    const Pose2 a(u(rng), u(rng), u(rng));
    const Pose2 id = a * a.Inverse();
    ASSERT_NEAR(id.x(), 0.0, 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_NEAR(id.y(), 0.0, 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_NEAR(id.yaw, 0.0, 1e-12) << "seed " << seed << " draw " << i;
  }
}

TEST(Pose2Test, AppliesRotationThenTranslation) {
  const Pose2 p(1.0, 2.0, kPi / 2.0);
  const Eigen::Vector2d q = p * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 3.0, 1e-12);
}

TEST(Pose2Test, WrapAngleStaysInHalfOpenInterval) {
  EXPECT_NEAR(WrapAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(WrapAngle(-3.0 * kPi / 2.0), kPi / 2.0, 1e-12);
  EXPECT_NEAR(WrapAngle(kPi), -kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(0.25), 0.25, 1e-15);
}

}  // namespace
}  // namespace lookout
