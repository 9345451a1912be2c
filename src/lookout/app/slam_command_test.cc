#include "lookout/app/slam_command.h"

#include <gtest/gtest.h>

namespace lookout::app {
namespace {

TEST(SlamCommand, MapImageIsNorthUpWhiteFreeBlackOccupiedGreyUnknown) {
  lidar::MapRaster map;
  map.geometry.width = 3;
  map.geometry.height = 2;
  // Bottom row (y = 0): free, unknown, occupied; top row all unknown.
  map.log_odds = {-5.0f, 0.0f, 5.0f, 0.0f, 0.0f, 0.0f};
  const io::Image8 image = MapImage(map);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  // The picture's last row is the map's bottom row.
  EXPECT_EQ(image.pixels[image.Offset(0, 1)], 253);  // 255 (1 - 1 / (1 + e^5))
  EXPECT_EQ(image.pixels[image.Offset(1, 1)], 128);
  EXPECT_EQ(image.pixels[image.Offset(2, 1)], 2);
  EXPECT_EQ(image.pixels[image.Offset(2, 0)], 128);
}

TEST(SlamCommand, RecordsCarryNoReferencePose) {
  io::CarmenLog log;
  // Built in place: copying a record that holds an optional scan trips gcc 12's
  // maybe-uninitialized false positive under the sanitizer build's -O2.
  log.records.resize(2);
  io::CarmenRecord& odometry = log.records[0];
  odometry.t_s = 1.0;
  odometry.odometry = Pose2(1.0, 2.0, 0.5);
  io::CarmenRecord& scan = log.records[1];
  scan.t_s = 2.0;
  scan.odometry = Pose2(3.0, 2.0, 0.5);
  scan.scan.emplace();
  scan.reference_pose = Pose2(100.0, 100.0, 1.0);
  const std::vector<lidar::SlamRecord> records = SlamRecordsOf(log);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].t_s, 1.0);
  EXPECT_FALSE(records[0].scan.has_value());
  EXPECT_EQ(records[1].odometry.x(), 3.0);  // the raw odometry, not the reference
  EXPECT_TRUE(records[1].scan.has_value());
}

TEST(SlamCommand, RelationErrorPairsTheScansByOrderOverTenMetres) {
  // 21 scans 1 m apart along x on the reference, 1.1 m apart in the estimate. Each scan is
  // related to the one 10 m further: 11 relations, each 1 m too long.
  io::CarmenLog log;
  lidar::SlamResult result;
  log.records.resize(21);
  for (int i = 0; i < 21; ++i) {
    io::CarmenRecord& r = log.records[static_cast<std::size_t>(i)];
    r.t_s = 0.0;  // no time base, as five Radish logs: pairing is by order
    r.scan.emplace();
    r.reference_pose = Pose2(static_cast<double>(i), 0.0, 0.0);
    EgoState state;
    state.stamp = FromSeconds(r.t_s);
    state.pose = Pose2(1.1 * i, 0.0, 0.0);
    result.scan_states.push_back(state);
  }
  const eval::RelationError error = ReferenceRelationError(log, result);
  EXPECT_EQ(error.used, 11u);
  EXPECT_NEAR(error.translation_mean_m, 1.0, 1e-9);
  EXPECT_NEAR(error.translation_std_m, 0.0, 1e-9);
  EXPECT_NEAR(error.rotation_mean_rad, 0.0, 1e-12);
  // Over 5 m, the first scan 5 m further: 16 relations 0.5 m too long.
  const eval::RelationError five = ReferenceRelationError(log, result, 5.0);
  EXPECT_EQ(five.used, 16u);
  EXPECT_NEAR(five.translation_mean_m, 0.5, 1e-9);
}

}  // namespace
}  // namespace lookout::app
