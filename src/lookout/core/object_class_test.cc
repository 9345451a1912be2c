#include "lookout/core/object_class.h"

#include <gtest/gtest.h>

namespace lookout {
namespace {

TEST(ObjectClassTest, NamesRoundTrip) {
  for (const ObjectClass c : kAllObjectClasses) {
    ASSERT_EQ(ParseObjectClass(ToString(c)), c) << ToString(c);
  }
  EXPECT_FALSE(ParseObjectClass("bus").has_value());
  EXPECT_FALSE(ParseObjectClass("Car").has_value());
}

}  // namespace
}  // namespace lookout
