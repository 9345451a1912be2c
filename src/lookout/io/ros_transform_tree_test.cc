#include "lookout/io/ros_transform_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace lookout::io {
namespace {

RosTransform Edge(const char* parent, const char* child, TimeNs t, double x, double y,
                  double yaw) {
  RosTransform r;
  r.stamp = t;
  r.parent_frame = parent;
  r.child_frame = child;
  r.translation_m = Eigen::Vector3d(x, y, 0.2);
  r.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return r;
}

void ExpectPose(const Pose2& got, const Pose2& want) {
  EXPECT_NEAR(got.x(), want.x(), 1e-12);
  EXPECT_NEAR(got.y(), want.y(), 1e-12);
  EXPECT_NEAR(WrapAngle(got.yaw - want.yaw), 0.0, 1e-12);
}

// The frames of the leg-tracker wheelchair: odom -> base_link (moving), base_link -> two
// lasers (fixed), left_laser -> a sonar; names with and without the leading '/'.
class TreeTest : public ::testing::Test {
 protected:
  const Pose2 left_{0.85, 0.235, 0.737};
  const Pose2 right_{0.868, -0.215, -0.675};
  const Pose2 sonar_{0.07, 0.055, 0.785};
  const std::vector<RosTransform> transforms_ = {
      Edge("/odom", "/base_link", 0, 0.0, 0.0, 0.0),
      Edge("base_link", "left_laser", 5, left_.x(), left_.y(), left_.yaw),
      Edge("/odom", "/base_link", 1000, 10.0, 2.0, 1.0),
      Edge("base_link", "right_laser", 5, right_.x(), right_.y(), right_.yaw),
      Edge("left_laser", "left_sonar", 5, sonar_.x(), sonar_.y(), sonar_.yaw)};
  const RosTransformTree tree_{transforms_};
};

TEST_F(TreeTest, ComposesEdgesUpAndDownTheTree) {
  ExpectPose(tree_.Find("base_link", "left_laser", 0)->pose, left_);
  ExpectPose(tree_.Find("/base_link", "/left_sonar", 0)->pose, left_ * sonar_);
  ExpectPose(tree_.Find("left_laser", "base_link", 0)->pose, left_.Inverse());
  // Across branches: through their common ancestor.
  ExpectPose(tree_.Find("right_laser", "left_sonar", 0)->pose, right_.Inverse() * left_ * sonar_);
  ExpectPose(tree_.Find("left_laser", "left_laser", 0)->pose, Pose2());
}

TEST_F(TreeTest, InterpolatesAMovingEdgeAndHoldsTheEndsOutsideItsSamples) {
  ExpectPose(tree_.Find("odom", "base_link", 250)->pose, Pose2(2.5, 0.5, 0.25));
  ExpectPose(tree_.Find("odom", "base_link", -50)->pose, Pose2(0.0, 0.0, 0.0));
  ExpectPose(tree_.Find("odom", "base_link", 5000)->pose, Pose2(10.0, 2.0, 1.0));
  // A fixed edge stamped at 5 answers before its stamp too.
  ExpectPose(tree_.Find("odom", "left_laser", 500)->pose, Pose2(5.0, 1.0, 0.5) * left_);
}

TEST_F(TreeTest, UnknownOrUnconnectedFramesHaveNoAnswer) {
  EXPECT_FALSE(tree_.Find("base_link", "camera", 0));
  EXPECT_FALSE(tree_.Find("camera", "camera", 0));
  const std::vector<RosTransform> two_trees = {Edge("a", "b", 0, 1, 0, 0),
                                               Edge("c", "d", 0, 1, 0, 0)};
  EXPECT_FALSE(RosTransformTree(two_trees).Find("b", "d", 0));
}

TEST(RosTransformTreeTest, KeepsTheFirstParentOfAFrameAndSurvivesLoops) {
  const std::vector<RosTransform> transforms = {Edge("a", "b", 0, 1, 0, 0),
                                                Edge("c", "b", 0, 5, 0, 0),
                                                Edge("b", "a", 0, 1, 0, 0)};
  const RosTransformTree tree(transforms);
  EXPECT_EQ(tree.conflicting(), 1u);
  EXPECT_FALSE(tree.Find("c", "b", 0)) << "the second parent was kept";
  // a -> b -> a is a loop (contradictory edges): lookups end, whatever they answer.
  EXPECT_TRUE(tree.Find("a", "b", 0));
  EXPECT_FALSE(tree.Find("a", "unknown", 0));
}

TEST(RosTransformTreeTest, ReportsTheTiltOfTheEdgesUsed) {
  RosTransform tilted = Edge("base_link", "laser", 0, 0.5, 0.0, 0.0);
  tilted.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  const std::vector<RosTransform> transforms = {tilted, Edge("odom", "base_link", 0, 0, 0, 0)};
  const RosTransformTree tree(transforms);
  EXPECT_NEAR(tree.Find("base_link", "laser", 0)->max_tilt_rad, 0.1, 1e-9);
  EXPECT_NEAR(tree.Find("odom", "base_link", 0)->max_tilt_rad, 0.0, 1e-9);
}

}  // namespace
}  // namespace lookout::io
