#include "lookout/core/class_footprint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace lookout {
namespace {

TEST(ClassFootprints, BoxesByClassAndTheFirstInvalidField) {
  const ClassFootprints f;
  EXPECT_EQ(f.BoxOf(ObjectClass::kCar).length_m, 4.5);
  EXPECT_EQ(f.BoxOf(ObjectClass::kTruck).width_m, 2.5);
  EXPECT_EQ(f.BoxOf(ObjectClass::kCyclist).length_m, 1.8);
  EXPECT_EQ(f.BoxOf(ObjectClass::kPedestrian).width_m, 0.6);
  EXPECT_EQ(f.BoxOf(ObjectClass::kUnknown).length_m, f.car_length_m);
  EXPECT_FALSE(f.FirstInvalidField().has_value());

  ClassFootprints bad = f;
  bad.truck_width_m = 0.0;
  ASSERT_TRUE(bad.FirstInvalidField().has_value());
  EXPECT_EQ(std::string(*bad.FirstInvalidField()), "truck_width_m");
  bad.car_length_m = std::nan("");
  EXPECT_EQ(std::string(*bad.FirstInvalidField()), "car_length_m");
}

}  // namespace
}  // namespace lookout
