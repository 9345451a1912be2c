#include "lookout/risk/junction_scene.h"

#include <gtest/gtest.h>

namespace lookout::risk {
namespace {

// The benchmark's scene: the same seed, the same road users; every one usable by AssessRisk.
TEST(JunctionSceneTest, SeededAndUsable) {
  const auto a = JunctionRoadUsers(30, 7), b = JunctionRoadUsers(30, 7);
  ASSERT_EQ(a.size(), 30u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position_m, b[i].position_m);
    EXPECT_EQ(a[i].velocity_mps, b[i].velocity_mps);
  }
  EXPECT_EQ(a[0].object_class, ObjectClass::kCar);
  EXPECT_EQ(a[1].object_class, ObjectClass::kCyclist);
  EXPECT_EQ(a[2].object_class, ObjectClass::kPedestrian);
  EXPECT_NE(JunctionRoadUsers(30, 8)[0].position_m, a[0].position_m);
  EXPECT_EQ(AssessRisk(EgoInput{}, a, RiskOptions{}).dropped, 0u);
}

}  // namespace
}  // namespace lookout::risk
