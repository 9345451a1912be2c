#include "lookout/app/pipeline.h"

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

TEST(PipelineOptions, AChoiceThatNeedsAPartThatIsOffIsRefused) {
  PipelineOptions o;
  o.lidar_chain = false;
  o.ego_pose = EgoPoseMode::kLidarLocalisation;
  try {
    o.Validate();
    FAIL() << "accepted lidar localisation without the lidar chain";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ego_pose");
  }
  o.ego_pose = EgoPoseMode::kDeadReckoning;
  o.lidar_objects = LidarObjectSource::kSegmentation;
  EXPECT_THROW(Pipeline{o}, InputError);
  o = {};
  o.lidar_objects = LidarObjectSource::kGrid;
  o.grid = false;
  EXPECT_THROW(o.Validate(), InputError);  // fusion of the grid's objects without a grid
  o.fusion = false;
  EXPECT_NO_THROW(o.Validate());
}

TEST(Pipeline, TheGridTakesItsPoseFromTheChosenSource) {
  PipelineOptions o;
  o.ego_pose = EgoPoseMode::kLidarLocalisation;
  const Pipeline lidar(o);
  ASSERT_NE(lidar.grid(), nullptr);
  ASSERT_NE(lidar.lidar_chain(), nullptr);
  EXPECT_EQ(&lidar.grid()->pose_source(), &lidar.lidar_chain()->localisation());
  o.ego_pose = EgoPoseMode::kDeadReckoning;
  const Pipeline odometry(o);
  EXPECT_NE(&odometry.grid()->pose_source(), &odometry.lidar_chain()->localisation());
}

TEST(Pipeline, SegmentationObjectsComeFromTheLidarChain) {
  PipelineOptions o;
  o.lidar_objects = LidarObjectSource::kSegmentation;
  Pipeline p(o);
  EXPECT_EQ(p.lidar_objects(), nullptr);  // before the first cycle
  EgoOdometry odometry;
  p.OnOdometry(odometry);
  LidarScan scan;
  scan.angle_min_rad = -0.5;
  scan.angle_increment_rad = 0.01;
  scan.max_range_m = 50.0;
  scan.ranges_m.assign(101, 10.0f);
  p.OnLidar(scan);
  ASSERT_NE(p.lidar_objects(), nullptr);
  EXPECT_EQ(p.lidar_objects(), &*p.lidar_chain()->last_objects());
  EXPECT_EQ(p.lidar_objects()->stamp, scan.stamp);
  EXPECT_NE(p.fusion(), nullptr);
}

}  // namespace
}  // namespace lookout::app
