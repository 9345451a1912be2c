#include "lookout/eval/mot_frame.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::eval {
namespace {

TEST(BoxIou, AnalyticOverlaps) {
  const Box a{0, 0, 10, 10};
  EXPECT_DOUBLE_EQ(BoxIou(a, a), 1.0);
  EXPECT_DOUBLE_EQ(BoxIou(a, Box{5, 0, 10, 10}), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(BoxIou(a, Box{5, 5, 10, 10}), 25.0 / 175.0);
  EXPECT_DOUBLE_EQ(BoxIou(a, Box{2, 2, 4, 4}), 16.0 / 100.0);  // inside
  EXPECT_DOUBLE_EQ(BoxIou(a, Box{10, 0, 10, 10}), 0.0);        // touching edges
  EXPECT_DOUBLE_EQ(BoxIou(a, Box{30, 30, 1, 1}), 0.0);
  EXPECT_DOUBLE_EQ(BoxIou(Box{1, 1, 0, 0}, Box{1, 1, 0, 0}), 0.0);  // empty boxes
}

TEST(IouFrame, DistanceIsOneMinusIouUpToTheThreshold) {
  const MotFrame f = IouFrame({{1, {0, 0, 10, 10}}, {2, {100, 100, 10, 10}}},
                              {{7, {0, 0, 10, 10}}, {8, {5, 0, 10, 10}}, {9, {0, 0, 10, 20}}}, 0.5);
  EXPECT_EQ(f.truth_ids, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(f.hypothesis_ids, (std::vector<std::int64_t>{7, 8, 9}));
  EXPECT_DOUBLE_EQ(f.distance(0, 0), 0.0);
  EXPECT_FALSE(std::isfinite(f.distance(0, 1)));  // IoU 1/3 < 0.5
  EXPECT_DOUBLE_EQ(f.distance(0, 2), 0.5);        // IoU exactly 0.5 matches
  EXPECT_FALSE(std::isfinite(f.distance(1, 0)));
}

TEST(DistanceFrame, EuclideanWithinTheThreshold) {
  const MotFrame f = DistanceFrame({{3, {0.0, 0.0}}}, {{4, {3.0, 4.0}}, {5, {1.0, 1.0}}}, 2.0);
  EXPECT_FALSE(std::isfinite(f.distance(0, 0)));  // 5 m
  EXPECT_DOUBLE_EQ(f.distance(0, 1), std::sqrt(2.0));
  const MotFrame edge = DistanceFrame({{3, {0.0, 0.0}}}, {{4, {2.0, 0.0}}}, 2.0);
  EXPECT_DOUBLE_EQ(edge.distance(0, 0), 2.0);
  const MotFrame empty = DistanceFrame({}, {{4, {2.0, 0.0}}}, 2.0);
  EXPECT_EQ(empty.distance.rows(), 0);
  EXPECT_EQ(empty.distance.cols(), 1);
}

}  // namespace
}  // namespace lookout::eval
