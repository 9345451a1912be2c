#include "lookout/io/mot_challenge.h"

#include <gtest/gtest.h>

#include <string>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

// The field and line an InputError names for `text`, or "no error".
std::string Refusal(const std::string& text) {
  try {
    ParseMotChallenge(text, "test.txt");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test.txt");
    return std::to_string(e.line()) + ":" + e.field();
  }
  return "no error";
}

TEST(MotChallenge, ReadsAllTenColumns) {
  const auto rows = ParseMotChallenge(
      "1,1,88,99,61.08,218.56,1,4.4852,5.5016,0\n"
      "1, 2, 181, 95, 75.808, 227.01, -1, -1, -1, -1\r\n",
      "gt.txt");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].frame, 1);
  EXPECT_EQ(rows[0].id, 1);
  EXPECT_DOUBLE_EQ(rows[0].bb_left, 88.0);
  EXPECT_DOUBLE_EQ(rows[0].bb_top, 99.0);
  EXPECT_DOUBLE_EQ(rows[0].bb_width, 61.08);
  EXPECT_DOUBLE_EQ(rows[0].bb_height, 218.56);
  EXPECT_DOUBLE_EQ(rows[0].conf, 1.0);
  EXPECT_DOUBLE_EQ(rows[0].x, 4.4852);
  EXPECT_DOUBLE_EQ(rows[0].y, 5.5016);
  EXPECT_DOUBLE_EQ(rows[0].z, 0.0);
  EXPECT_EQ(rows[0].line, 1);
  EXPECT_EQ(rows[1].id, 2);
  EXPECT_DOUBLE_EQ(rows[1].conf, -1.0);
  EXPECT_EQ(rows[1].line, 2);
}

TEST(MotChallenge, ShortRowsBlankLinesAndWholeNumbersWrittenAsDecimals) {
  const auto rows = ParseMotChallenge("\n3.0,7,1,2,3,4\n\n   \n4,-1,1,2,3,4,0.5,1,0.25", "det.txt");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].frame, 3);
  EXPECT_EQ(rows[0].line, 2);
  EXPECT_DOUBLE_EQ(rows[0].conf, -1.0);  // not given
  EXPECT_DOUBLE_EQ(rows[0].z, -1.0);
  EXPECT_EQ(rows[1].id, -1);
  EXPECT_EQ(rows[1].line, 5);
  EXPECT_DOUBLE_EQ(rows[1].y, 0.25);
  EXPECT_DOUBLE_EQ(rows[1].z, -1.0);
  EXPECT_TRUE(ParseMotChallenge("", "empty.txt").empty());
}

TEST(MotChallenge, RefusesMalformedLinesNamingLineAndField) {
  EXPECT_EQ(Refusal("1,1,1,1,1,1\n1,x,1,1,1,1\n"), "2:id");
  EXPECT_EQ(Refusal("1.5,1,1,1,1,1\n"), "1:frame");
  EXPECT_EQ(Refusal("-2,1,1,1,1,1\n"), "1:frame");
  EXPECT_EQ(Refusal("1,1,1,1,-3,1\n"), "1:bb_width");
  EXPECT_EQ(Refusal("1,1,1,1,3,-1\n"), "1:bb_height");
  EXPECT_EQ(Refusal("1,1,nan,1,1,1\n"), "1:bb_left");
  EXPECT_EQ(Refusal("1,1,1,inf,1,1\n"), "1:bb_top");
  EXPECT_EQ(Refusal("1,1,1,1,1,1,1e999\n"), "1:conf");
  EXPECT_EQ(Refusal("1,1,1,1,1,1,,1\n"), "1:conf");
  EXPECT_EQ(Refusal("\n\n1,1,1,1\n"), "3:bb_width");
  EXPECT_EQ(Refusal("1,1,1,1,1,1,1,1,1,1,1\n"), "1:z");
  EXPECT_EQ(Refusal("1,1,1,1,1,1,1,1,1,2 3\n"), "1:z");
  EXPECT_EQ(Refusal("1,99999999999999999999,1,1,1,1\n"), "1:id");
}

TEST(MotChallenge, UnreadableFileIsAnInputError) {
  EXPECT_THROW(ReadMotChallengeFile("/nonexistent/gt.txt"), InputError);
  EXPECT_THROW(ReadMotChallengeFile(LOOKOUT_SOURCE_DIR), InputError);
}

TEST(MotChallenge, ReadsThePyMotmetricsTestFiles) {
  const std::string dir = std::string(LOOKOUT_SOURCE_DIR) + "/../shared/data/mot/TUD-Campus/";
  const auto gt = ReadMotChallengeFile(dir + "gt.txt");
  const auto test = ReadMotChallengeFile(dir + "test.txt");
  EXPECT_EQ(gt.size(), 359u);  // wc -l
  EXPECT_FALSE(test.empty());
  EXPECT_EQ(gt.front().frame, 1);
  EXPECT_DOUBLE_EQ(gt.front().bb_width, 121.0);
}

}  // namespace
}  // namespace lookout::io
