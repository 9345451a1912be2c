#include "lookout/eval/trajectory_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "lookout/core/input_error.h"

namespace lookout::eval {
namespace {

namespace fs = std::filesystem;

TEST(TrajectoryIoTest, WrittenTrajectoryReadsBackBitForBit) {
  const unsigned seed = 4004;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> any(-1e4, 1e4);
  Trajectory2 trajectory;
  for (int i = 0; i < 500; ++i) {
    trajectory.push_back(
        {1134863807.658934 + 0.1 * i, Pose2(any(rng), any(rng), WrapAngle(any(rng)))});
  }
  const std::string text = FormatTrajectory(trajectory);
  const Trajectory2 back = ParseTrajectory(text, "t.txt");
  ASSERT_EQ(back.size(), trajectory.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].t_s, trajectory[i].t_s) << "seed " << seed << " pose " << i;
    EXPECT_EQ(back[i].pose.x(), trajectory[i].pose.x()) << "seed " << seed << " pose " << i;
    EXPECT_EQ(back[i].pose.y(), trajectory[i].pose.y()) << "seed " << seed << " pose " << i;
    EXPECT_EQ(back[i].pose.yaw, trajectory[i].pose.yaw) << "seed " << seed << " pose " << i;
  }
  EXPECT_EQ(FormatTrajectory(back), text);  // same poses, same bytes
}

TEST(TrajectoryIoTest, FormatIsOnePoseALine) {
  EXPECT_EQ(FormatTrajectory({{1.5, Pose2(2.0, -0.25, 0.5)}, {2.0, Pose2(3.0, 0.0, -1.0)}}),
            "1.5 2 -0.25 0.5\n2 3 0 -1\n");
}

TEST(TrajectoryIoTest, CommentsAndBlankLinesAreSkipped) {
  const Trajectory2 t = ParseTrajectory("# t x y theta\n\n 1 2 3 0.5\r\n\t2 3 4 0.25", "t.txt");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].t_s, 2.0);
  EXPECT_EQ(t[1].pose.yaw, 0.25);
}

struct Bad {
  std::string line;
  std::string field;
};

TEST(TrajectoryIoTest, BadLinesNameFileLineAndField) {
  for (const Bad& bad : std::vector<Bad>{{"1 2 3", "theta"},
                                         {"1 2 y 4", "y"},
                                         {"nan 2 3 4", "t"},
                                         {"1 2 3 inf", "theta"},
                                         {"1 2 3 4 5", ""},
                                         {"1,2,3,4", "t"}}) {
    try {
      ParseTrajectory("0 0 0 0\n" + bad.line + "\n", "t.txt");
      ADD_FAILURE() << "accepted: " << bad.line;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "t.txt");
      EXPECT_EQ(e.line(), 2) << bad.line;
      EXPECT_EQ(e.field(), bad.field) << bad.line;
    }
  }
}

TEST(TrajectoryIoTest, RelationsRoundTripAndRefuseShortLines) {
  const std::vector<Relation2> relations = {{1.0, 2.5, Pose2(0.5, -0.125, 0.25)},
                                            {3.0, 4.0, Pose2(1.0, 2.0, -3.0)}};
  const std::vector<Relation2> back = ParseRelations(FormatRelations(relations), "r.relations");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].t2_s, 2.5);
  EXPECT_EQ(back[0].motion.y(), -0.125);
  EXPECT_EQ(back[1].motion.yaw, -3.0);
  // The published files carry z, roll and pitch, ignored in the plane.
  const std::vector<Relation2> published =
      ParseRelations("10.5 11.5 0.3 0.01 0.000000 0.000000 0.000000 0.02\n", "r.relations");
  ASSERT_EQ(published.size(), 1u);
  EXPECT_EQ(published[0].motion.yaw, 0.02);
  try {
    ParseRelations("1 2 3 4 5 6 7\n", "r.relations");
    ADD_FAILURE() << "accepted a line of 7 fields";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.field(), "yaw");
  }
}

TEST(TrajectoryIoTest, FilesAreWrittenAndRead) {
  const fs::path dir =
      fs::temp_directory_path() / ("lookout_trajectory_io_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const Trajectory2 trajectory = {{0.0, Pose2(1, 2, 0.5)}, {0.1, Pose2(1.5, 2, 0.5)}};
  WriteTrajectory(dir / "t.txt", trajectory);
  EXPECT_EQ(ReadTrajectory(dir / "t.txt").size(), 2u);
  WriteRelations(dir / "r.relations", {{0.0, 0.1, Pose2(0.5, 0, 0)}});
  EXPECT_EQ(ReadRelations(dir / "r.relations").at(0).motion.x(), 0.5);
  EXPECT_THROW(ReadTrajectory(dir / "missing.txt"), InputError);
  EXPECT_THROW(WriteTrajectory(dir / "no-such-dir" / "t.txt", trajectory), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lookout::eval
