#include "lookout/eval/relation_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::eval {
namespace {

// Poses reached by repeating `step` from the identity, one a second.
Trajectory2 Repeat(const Pose2& step, int poses) {
  Trajectory2 trajectory;
  Pose2 pose;
  for (int i = 0; i < poses; ++i) {
    trajectory.push_back({1.0 * i, pose});
    pose = pose * step;
  }
  return trajectory;
}

TEST(RelationErrorTest, ExactEstimateInAnotherFrameHasNoError) {
  const Trajectory2 reference = Repeat(Pose2(1.0, 0.0, 0.1), 50);
  Trajectory2 estimate = reference;
  for (StampedPose2& p : estimate) p.pose = Pose2(5.0, -3.0, 1.0) * p.pose;
  const RelationError error = ComputeRelationError(estimate, GenerateRelations(reference));
  EXPECT_EQ(error.used, 49u);
  EXPECT_NEAR(error.translation_mean_m, 0.0, 1e-9);
  EXPECT_NEAR(error.rotation_mean_rad, 0.0, 1e-12);
}

TEST(RelationErrorTest, PerStepBiasIsTheErrorOfEveryRelation) {
  // The reference drives 1 m a step straight ahead; the estimate's odometry reads 1.1 m and an
  // extra 0.01 rad a step. Each one-step relation is off by exactly (0.1 m, 0.01 rad), however
  // far the estimate has drifted in absolute terms.
  const Trajectory2 reference = Repeat(Pose2(1.0, 0.0, 0.0), 100);
  const Trajectory2 estimate = Repeat(Pose2(1.1, 0.0, 0.01), 100);
  const RelationError error = ComputeRelationError(estimate, GenerateRelations(reference));
  EXPECT_EQ(error.used, 99u);
  EXPECT_NEAR(error.translation_mean_m, 0.1, 1e-9);
  EXPECT_NEAR(error.translation_std_m, 0.0, 1e-9);
  EXPECT_NEAR(error.translation_squared_mean_m2, 0.01, 1e-9);
  EXPECT_NEAR(error.rotation_mean_rad, 0.01, 1e-12);
  EXPECT_NEAR(error.rotation_squared_mean_rad2, 1e-4, 1e-12);

  // Over k steps of pure translation bias the error grows to 0.1 k.
  const Trajectory2 straight = Repeat(Pose2(1.1, 0.0, 0.0), 100);
  RelationGeneratorOptions five;
  five.step_poses = 5;
  const RelationError error5 = ComputeRelationError(straight, GenerateRelations(reference, five));
  EXPECT_EQ(error5.used, 95u);
  EXPECT_NEAR(error5.translation_mean_m, 0.5, 1e-9);
}

TEST(RelationErrorTest, HalfTheStepsBiasedGivesMeanAndSpreadOfHalf) {
  // Steps alternate between exact and 0.2 m long: relation errors are 0 and 0.2 in turn,
  // mean 0.1 and (population) standard deviation 0.1.
  Trajectory2 estimate;
  double x = 0.0;
  for (int i = 0; i < 101; ++i) {
    estimate.push_back({1.0 * i, Pose2(x, 0.0, 0.0)});
    x += i % 2 == 0 ? 1.0 : 1.2;
  }
  const Trajectory2 reference = Repeat(Pose2(1.0, 0.0, 0.0), 101);
  const RelationError error = ComputeRelationError(estimate, GenerateRelations(reference));
  EXPECT_EQ(error.used, 100u);
  EXPECT_NEAR(error.translation_mean_m, 0.1, 1e-9);
  EXPECT_NEAR(error.translation_std_m, 0.1, 1e-9);
  EXPECT_NEAR(error.translation_squared_mean_m2, 0.02, 1e-9);
  EXPECT_NEAR(error.translation_squared_std_m2, 0.02, 1e-9);
}

TEST(RelationErrorTest, RelationsOutsideTheEstimateAreCountedNotUsed) {
  const Trajectory2 reference = Repeat(Pose2(1.0, 0.0, 0.0), 20);
  Trajectory2 estimate(reference.begin() + 5, reference.end());
  const RelationError error = ComputeRelationError(estimate, GenerateRelations(reference));
  EXPECT_EQ(error.used, 14u);
  EXPECT_EQ(error.unmatched, 5u);
}

TEST(RelationErrorTest, GeneratorPairsByStepOrByTravel) {
  const Trajectory2 reference = Repeat(Pose2(1.0, 0.0, kPi / 2), 8);  // a 1 m square, twice
  const std::vector<Relation2> one = GenerateRelations(reference);
  ASSERT_EQ(one.size(), 7u);
  EXPECT_EQ(one[3].t1_s, 3.0);
  EXPECT_EQ(one[3].t2_s, 4.0);
  EXPECT_NEAR(one[3].motion.x(), 1.0, 1e-12);
  EXPECT_NEAR(one[3].motion.y(), 0.0, 1e-12);
  EXPECT_NEAR(one[3].motion.yaw, kPi / 2, 1e-12);

  RelationGeneratorOptions travel;
  travel.min_travel_m = 2.5;  // three 1 m sides, although pose i + 4 is back at the start
  const std::vector<Relation2> far = GenerateRelations(reference, travel);
  ASSERT_EQ(far.size(), 5u);
  for (const Relation2& r : far) EXPECT_EQ(r.t2_s - r.t1_s, 3.0);

  RelationGeneratorOptions bad;
  bad.step_poses = 0;
  EXPECT_THROW(GenerateRelations(reference, bad), InputError);
}

}  // namespace
}  // namespace lookout::eval
