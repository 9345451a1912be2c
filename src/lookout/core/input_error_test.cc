#include "lookout/core/input_error.h"

#include <gtest/gtest.h>

namespace lookout {
namespace {

TEST(InputErrorTest, MessageNamesFileLineAndField) {
  const InputError e("a.yaml", 12, "actors[1].speed", "expected a number");
  EXPECT_STREQ(e.what(), "a.yaml:12: actors[1].speed: expected a number");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.field(), "actors[1].speed");
}

TEST(InputErrorTest, OmitsLineAndFieldWhenAbsent) {
  EXPECT_STREQ(InputError("x.mcap", 0, "", "truncated").what(), "x.mcap: truncated");
  EXPECT_STREQ(InputError("--threads", 0, "threads", "must be >= 1").what(),
               "--threads: threads: must be >= 1");
}

}  // namespace
}  // namespace lookout
