#include "lookout/eval/grid_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>

#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/simulator.h"

namespace lookout::eval {
namespace {

using Eigen::Vector2d;
using Eigen::Vector2f;

GridGeometry Geometry(int width, int height, double cell_size_m) {
  GridGeometry g;
  g.origin_m = Vector2d::Zero();
  g.cell_size_m = cell_size_m;
  g.width = width;
  g.height = height;
  return g;
}

GridBelief Belief(const GridGeometry& g, float occupancy) {
  const auto n = static_cast<std::size_t>(g.CellCount());
  GridBelief b;
  b.geometry = g;
  b.occupancy.assign(n, occupancy);
  b.velocity_x_mps.assign(n, 0.0f);
  b.velocity_y_mps.assign(n, 0.0f);
  b.velocity_confidence.assign(n, 0.0f);
  return b;
}

sim::TruthRaster FreeTruth(const GridGeometry& g) {
  const auto n = static_cast<std::size_t>(g.CellCount());
  sim::TruthRaster t;
  t.geometry = g;
  t.occupied.assign(n, 0);
  t.velocity.assign(n, Vector2f::Zero());
  t.owner.assign(n, sim::kFreeCell);
  return t;
}

void SetTruth(sim::TruthRaster& t, std::size_t i, int owner, Vector2f v) {
  t.occupied[i] = 1;
  t.owner[i] = owner;
  t.velocity[i] = v;
}

void SetBelief(GridBelief& b, std::size_t i, float occupancy, float vx, float vy,
               float confidence) {
  b.occupancy[i] = occupancy;
  b.velocity_x_mps[i] = vx;
  b.velocity_y_mps[i] = vy;
  b.velocity_confidence[i] = confidence;
}

TEST(GridMetricOptionsTest, DefaultsValidAndBadFieldNamed) {
  EXPECT_NO_THROW(GridMetricOptions{}.Validate());
  GridMetricOptions o;
  o.retention_mass_fraction = 0.0;
  try {
    o.Validate();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("retention_mass_fraction"), std::string::npos);
  }
}

TEST(GridMetricsTest, PerfectBeliefScoresZero) {
  const GridGeometry g = Geometry(6, 5, 0.5);
  sim::TruthRaster truth = FreeTruth(g);
  GridBelief belief = Belief(g, 0.0f);
  for (std::size_t i : {7u, 8u, 13u}) SetTruth(truth, i, 0, Vector2f(3.0f, -1.0f));
  for (std::size_t i : {20u, 21u}) SetTruth(truth, i, sim::kStaticOwner, Vector2f::Zero());
  for (std::size_t i = 0; i < truth.occupied.size(); ++i) {
    if (truth.occupied[i]) {
      SetBelief(belief, i, 1.0f, truth.velocity[i].x(), truth.velocity[i].y(), 1.0f);
    }
  }
  const SquaredErrorSum v = VelocitySquaredErrors(belief, truth);
  EXPECT_EQ(v.count, 3);
  EXPECT_EQ(v.sum_squared, 0.0);
  const FalseDynamicCount f = CountFalseDynamic(belief, truth);
  EXPECT_EQ(f.static_cells, 2);
  EXPECT_EQ(f.false_dynamic_cells, 0);
  const std::vector<std::uint8_t> all(truth.occupied.size(), 1);
  const SquaredErrorSum brier = OccupancySquaredErrors(belief, truth, all);
  EXPECT_EQ(brier.count, 30);
  EXPECT_EQ(brier.sum_squared, 0.0);
}

TEST(GridMetricsTest, VelocityRmseKnownOffsetsAndExclusions) {
  const GridGeometry g = Geometry(4, 4, 1.0);
  sim::TruthRaster truth = FreeTruth(g);
  GridBelief belief = Belief(g, 0.0f);
  const Vector2f v(2.0f, 1.0f);
  // Counted cells with errors (1, 0), (0, 2), (3, 4) and (0, 0): squared 1 + 4 + 25 + 0 = 30.
  SetTruth(truth, 0, 0, v);
  SetBelief(belief, 0, 0.9f, 3.0f, 1.0f, 1.0f);
  SetTruth(truth, 1, 0, v);
  SetBelief(belief, 1, 0.6f, 2.0f, 3.0f, 0.0f);  // confidence does not matter
  SetTruth(truth, 2, 1, v);
  SetBelief(belief, 2, 1.0f, 5.0f, 5.0f, 1.0f);
  SetTruth(truth, 3, 1, v);
  SetBelief(belief, 3, 0.7f, 2.0f, 1.0f, 1.0f);
  // Excluded: not believed occupied (O = 0.5 is not > 0.5), a slow actor, the static world,
  // a believed-occupied free cell.
  SetTruth(truth, 4, 0, v);
  SetBelief(belief, 4, 0.5f, 100.0f, 0.0f, 1.0f);
  SetTruth(truth, 5, 2, Vector2f(0.3f, 0.3f));  // 0.42 m/s
  SetBelief(belief, 5, 1.0f, 100.0f, 0.0f, 1.0f);
  SetTruth(truth, 6, sim::kStaticOwner, Vector2f::Zero());
  SetBelief(belief, 6, 1.0f, 100.0f, 0.0f, 1.0f);
  SetBelief(belief, 7, 1.0f, 100.0f, 0.0f, 1.0f);

  const SquaredErrorSum s = VelocitySquaredErrors(belief, truth);
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.sum_squared, 30.0);

  VelocityRmseAccumulator acc;
  EXPECT_FALSE(acc.Value().has_value());
  acc.AddFrame(belief, truth);
  EXPECT_DOUBLE_EQ(*acc.Value(), std::sqrt(30.0 / 4.0));
  // A second frame with only actor 1 counted: adds 25 + 0 over 2 cells -> 55 / 6.
  acc.AddFrame(belief, truth, [](int owner) { return owner == 1; });
  EXPECT_EQ(acc.cells(), 6);
  EXPECT_DOUBLE_EQ(*acc.Value(), std::sqrt(55.0 / 6.0));
}

TEST(GridMetricsTest, VisibilityClockGatesCountingAfterFirstSecond) {
  sim::TruthFrame f0;
  f0.stamp = 0;
  f0.actors.resize(2);
  f0.actors[0].index = 0;
  f0.actors[0].visible_fraction_lidar = 0.0;
  f0.actors[1].index = 1;
  f0.actors[1].visible_fraction_lidar = 0.3;
  for (sim::ActorTruth& a : f0.actors)
    a.footprint = sim::Shape::Circle(Vector2d(1.0, 1.0), 0.3, a.index);
  sim::TruthFrame f1 = f0;
  f1.stamp = FromSeconds(0.5);
  f1.actors[0].visible_fraction_lidar = 1.0;
  const GridGeometry window = Geometry(4, 4, 1.0);  // both actors inside
  ActorVisibilityClock clock;
  clock.Observe(f0, window);
  clock.Observe(f1, window);
  EXPECT_EQ(clock.FirstVisible(0), FromSeconds(0.5));
  EXPECT_EQ(clock.FirstVisible(1), TimeNs{0});
  EXPECT_FALSE(clock.FirstVisible(7).has_value());
  const OwnerFilter at_1_4 = clock.AfterFirstVisible(1.0, FromSeconds(1.4));
  EXPECT_FALSE(at_1_4(0));
  EXPECT_TRUE(at_1_4(1));
  EXPECT_TRUE(clock.VisibleForAtLeast(0, 1.0, FromSeconds(1.5)));
  EXPECT_FALSE(clock.VisibleForAtLeast(7, 0.0, FromSeconds(100.0)));
}

// The grid measures nothing of an actor outside its window: the clock starts when a seen actor
// is inside it.
TEST(GridMetricsTest, VisibilityClockStartsInsideTheWindow) {
  const GridGeometry window = Geometry(4, 4, 1.0);  // [0, 4) x [0, 4) m
  sim::TruthFrame f;
  f.actors.resize(1);
  f.actors[0].index = 3;
  f.actors[0].visible_fraction_lidar = 1.0;
  ActorVisibilityClock clock;
  for (int k = 0; k < 5; ++k) {  // seen from 8 m out, coming in at 2 m a second
    f.stamp = FromSeconds(0.5 * k);
    f.actors[0].footprint = sim::Shape::Circle(Vector2d(8.0 - 1.0 * k, 1.0), 0.3, 3);
    clock.Observe(f, window);
  }
  // Centres 8, 7, 6, 5, 4 m: none inside yet (the window ends before 4 m).
  EXPECT_FALSE(clock.FirstVisible(3).has_value());
  f.stamp = FromSeconds(2.5);
  f.actors[0].footprint = sim::Shape::Circle(Vector2d(3.0, 1.0), 0.3, 3);
  clock.Observe(f, window);
  EXPECT_EQ(clock.FirstVisible(3), FromSeconds(2.5));
  EXPECT_FALSE(clock.VisibleForAtLeast(3, 1.0, FromSeconds(3.0)));
  EXPECT_TRUE(clock.VisibleForAtLeast(3, 1.0, FromSeconds(3.5)));
}

TEST(GridMetricsTest, StaticFastConfidentCellCountsAsFalseDynamic) {
  const GridGeometry g = Geometry(3, 2, 1.0);
  sim::TruthRaster truth = FreeTruth(g);
  GridBelief belief = Belief(g, 0.0f);
  for (std::size_t i = 0; i < 5; ++i) SetTruth(truth, i, sim::kStaticOwner, Vector2f::Zero());
  SetBelief(belief, 0, 0.9f, 0.0f, 0.6f, 0.9f);   // fast, confident: false dynamic
  SetBelief(belief, 1, 0.9f, 0.6f, 0.0f, 0.1f);   // fast, not confident
  SetBelief(belief, 2, 0.9f, -0.4f, 0.0f, 1.0f);  // confident, slow
  SetBelief(belief, 3, 0.3f, 5.0f, 0.0f, 1.0f);   // not believed occupied: not scored
  SetBelief(belief, 4, 0.9f, 0.0f, -0.5f, 0.5f);  // exactly 0.5 m/s: not above
  SetTruth(truth, 5, 0, Vector2f(0.0f, 0.0f));    // a still actor is not static world
  SetBelief(belief, 5, 0.9f, 5.0f, 0.0f, 1.0f);
  const FalseDynamicCount c = CountFalseDynamic(belief, truth);
  EXPECT_EQ(c.static_cells, 4);
  EXPECT_EQ(c.false_dynamic_cells, 1);
  FalseDynamicAccumulator acc;
  EXPECT_FALSE(acc.Value().has_value());
  acc.AddFrame(belief, truth);
  acc.AddFrame(belief, truth);
  EXPECT_DOUBLE_EQ(*acc.Value(), 0.25);
}

TEST(GridMetricsTest, BrierOverMaskedCells) {
  const GridGeometry g = Geometry(2, 2, 1.0);
  sim::TruthRaster truth = FreeTruth(g);
  GridBelief belief = Belief(g, 0.5f);
  SetTruth(truth, 1, sim::kStaticOwner, Vector2f::Zero());
  belief.occupancy[1] = 0.8f;
  belief.occupancy[2] = 1.0f;  // free, error 1, but masked out
  const std::vector<std::uint8_t> mask = {1, 1, 0, 0};
  const SquaredErrorSum s = OccupancySquaredErrors(belief, truth, mask);
  EXPECT_EQ(s.count, 2);
  EXPECT_NEAR(s.sum_squared, 0.25 + 0.04, 1e-7);
  OccupancyBrierAccumulator acc;
  acc.AddFrame(belief, truth, mask);
  EXPECT_NEAR(*acc.Value(), 0.145, 1e-7);
  EXPECT_THROW(OccupancySquaredErrors(belief, truth, std::vector<std::uint8_t>(3, 1)),
               std::invalid_argument);
}

TEST(GridMetricsTest, WithinRangeMaskIsADiskOfCellCentres) {
  const GridGeometry g = Geometry(5, 5, 1.0);
  const std::vector<std::uint8_t> mask = WithinRangeMask(g, Vector2d(2.5, 2.5), 1.0);
  int count = 0;
  for (const std::uint8_t m : mask) count += m;
  EXPECT_EQ(count, 5);  // the centre and its four neighbours at exactly 1 m
  EXPECT_EQ(mask[static_cast<std::size_t>(g.LinearIndex({2, 3}))], 1);
  EXPECT_EQ(mask[static_cast<std::size_t>(g.LinearIndex({3, 3}))], 0);
}

TEST(GridMetricsTest, MismatchedGeometryThrows) {
  const GridGeometry g = Geometry(3, 3, 1.0);
  GridBelief belief = Belief(g, 0.5f);
  sim::TruthRaster truth = FreeTruth(Geometry(3, 3, 0.5));
  EXPECT_THROW(VelocitySquaredErrors(belief, truth), std::invalid_argument);
  belief.velocity_confidence.pop_back();
  EXPECT_THROW(CountFalseDynamic(belief, FreeTruth(g)), std::invalid_argument);
}

TEST(GridMetricsTest, EvidenceMassCountsOnlyAboveUnknownNearTheActor) {
  const GridGeometry g = Geometry(20, 20, 0.5);  // 10 m
  sim::TruthRaster truth = FreeTruth(g);
  GridBelief belief = Belief(g, 0.5f);
  const sim::Shape ped = sim::Shape::Circle(Vector2d(5.0, 5.0), 0.3, 3);
  auto at = [&](double x, double y) {
    return static_cast<std::size_t>(g.LinearIndex(*g.CellAt(Vector2d(x, y))));
  };
  belief.occupancy[at(4.8, 4.8)] = 1.0f;   // inside: 1
  belief.occupancy[at(5.2, 5.2)] = 0.75f;  // inside: 0.5
  belief.occupancy[at(6.2, 5.2)] = 1.0f;   // centre (6.25, 5.25): 0.97 m from the circle: 1
  belief.occupancy[at(7.2, 5.2)] = 1.0f;   // 1.95 m from the circle: out
  belief.occupancy[at(4.2, 5.2)] = 0.2f;   // free: 0
  belief.occupancy[at(5.2, 4.2)] = 1.0f;   // truly another body's: out
  SetTruth(truth, at(5.2, 4.2), sim::kStaticOwner, Vector2f::Zero());
  EXPECT_DOUBLE_EQ(ActorEvidenceMass(belief, truth, ped, 3, 1.0), 2.5);
  // Far outside the grid: nothing, and no overflow.
  EXPECT_EQ(
      ActorEvidenceMass(belief, truth, sim::Shape::Circle(Vector2d(1e12, -1e12), 1.0, 3), 3, 1.0),
      0.0);
  // A box: distance to its edges.
  const sim::Shape box = sim::Shape::Box(Pose2(2.0, 8.0, 0.0), 2.0, 1.0, 4);
  belief.occupancy[at(2.2, 9.2)] = 1.0f;  // centre (2.25, 9.25): 0.75 m above the top edge
  belief.occupancy[at(4.2, 9.2)] = 1.0f;  // 1.25 m right of, 0.75 m above a corner: 1.46 m
  EXPECT_DOUBLE_EQ(ActorEvidenceMass(belief, truth, box, 4, 1.0), 1.0);
}

TEST(GridMetricsTest, TruthInAnotherFrameMovesShapesAndVelocities) {
  sim::TruthFrame f;
  sim::ActorTruth a;
  a.index = 0;
  a.state.pose = Pose2(3.0, 0.0, 0.0);
  a.state.speed_mps = 2.0;
  a.footprint = sim::Shape::Circle(Vector2d(3.0, 0.0), 0.5, 0);
  f.actors.push_back(a);
  const Pose2 target_from_world(1.0, 2.0, std::numbers::pi / 2.0);
  const sim::TruthFrame t = TruthFrameIn(f, target_from_world);
  EXPECT_NEAR(t.actors[0].state.pose.x(), 1.0, 1e-12);
  EXPECT_NEAR(t.actors[0].state.pose.y(), 5.0, 1e-12);
  EXPECT_NEAR(t.actors[0].footprint.center.x(), 1.0, 1e-12);
  EXPECT_NEAR(t.actors[0].footprint.center.y(), 5.0, 1e-12);
  EXPECT_NEAR(t.actors[0].state.Velocity().x(), 0.0, 1e-12);
  EXPECT_NEAR(t.actors[0].state.Velocity().y(), 2.0, 1e-12);
  const std::vector<sim::Shape> wall = ShapesIn(
      {sim::Shape::Box(Pose2(0.0, 0.0, 0.0), 2.0, 1.0, sim::kStaticOwner)}, target_from_world);
  // The box's rear right corner (-1, -0.5) maps to (1.5, 1).
  EXPECT_NEAR(wall[0].vertices[0].x(), 1.5, 1e-12);
  EXPECT_NEAR(wall[0].vertices[0].y(), 1.0, 1e-12);
  // Rasterised in the new frame, the actor's cells move north at 2 m/s.
  const GridGeometry g = Geometry(20, 20, 0.5);
  const sim::TruthRaster r = sim::RasteriseTruth(t, wall, g);
  const auto i = static_cast<std::size_t>(g.LinearIndex(*g.CellAt(Vector2d(1.1, 5.1))));
  EXPECT_EQ(r.owner[i], 0);
  EXPECT_NEAR(r.velocity[i].x(), 0.0f, 1e-6f);
  EXPECT_NEAR(r.velocity[i].y(), 2.0f, 1e-6f);
}

// The retention scenario: a pedestrian at a fixed spot, frames every 0.1 s.
class RetentionTest : public ::testing::Test {
 protected:
  static constexpr int kActor = 0;
  const GridGeometry g = Geometry(40, 40, 0.25);  // 10 m
  const sim::Shape ped = sim::Shape::Circle(Vector2d(5.0, 5.0), 0.4, kActor);

  sim::TruthFrame Frame(int k, double visible_fraction) const {
    sim::TruthFrame f;
    f.stamp = TimeNs{k} * 100'000'000;
    sim::ActorTruth a;
    a.index = kActor;
    a.footprint = ped;
    a.state.pose = Pose2(5.0, 5.0, 0.0);
    a.visible_fraction_lidar = visible_fraction;
    f.actors.push_back(a);
    return f;
  }
  // Believed occupancy `o` on the actor's true cells, `background` elsewhere.
  GridBelief BeliefWith(const sim::TruthRaster& truth, float o, float background) const {
    GridBelief b = Belief(g, background);
    for (std::size_t i = 0; i < truth.occupied.size(); ++i) {
      if (truth.owner[i] == kActor) b.occupancy[i] = o;
    }
    return b;
  }
  void Add(OccludedRetentionAccumulator& acc, int k, double visible_fraction, float o) const {
    const sim::TruthFrame f = Frame(k, visible_fraction);
    const sim::TruthRaster truth = sim::RasteriseTruth(f, {}, g);
    acc.AddFrame(f, BeliefWith(truth, o, 0.5f), truth);
  }
};

TEST_F(RetentionTest, VisibleThenHiddenKeptFor2p4SecondsThenLost) {
  OccludedRetentionAccumulator acc;
  for (int k = 0; k <= 10; ++k) Add(acc, k, 0.8, 0.9f);  // visible 0 - 1.0 s
  EXPECT_FALSE(acc.Value().has_value());
  for (int k = 11; k <= 34; ++k) Add(acc, k, 0.0, 0.8f);  // hidden from 1.1 s, kept
  for (int k = 35; k <= 40; ++k) Add(acc, k, 0.0, 0.5f);  // lost at 3.5 s
  ASSERT_TRUE(acc.Value().has_value());
  EXPECT_NEAR(*acc.Value(), 2.4, 1e-12);
  EXPECT_NEAR(acc.PerActorSeconds().at(kActor), 2.4, 1e-12);
}

TEST_F(RetentionTest, MassBelowHalfTheVisibleMassIsLost) {
  OccludedRetentionAccumulator acc;
  for (int k = 0; k <= 10; ++k) Add(acc, k, 1.0, 1.0f);
  Add(acc, 11, 0.0, 0.8f);   // evidence 0.6 of the visible 1.0 per cell: kept
  Add(acc, 12, 0.0, 0.74f);  // 0.48: below half, lost
  Add(acc, 13, 0.0, 1.0f);   // a later coincidence is not retention
  Add(acc, 14, 0.0, 1.0f);
  EXPECT_NEAR(*acc.Value(), 0.1, 1e-12);
}

TEST_F(RetentionTest, ReappearanceAndEndOfDataCloseTheEpisode) {
  OccludedRetentionAccumulator acc;
  for (int k = 0; k <= 5; ++k) Add(acc, k, 0.5, 0.9f);
  for (int k = 6; k <= 15; ++k) Add(acc, k, 0.0, 0.9f);  // hidden 0.6 s - 1.5 s, kept
  Add(acc, 16, 0.5, 0.9f);                               // visible again at 1.6 s
  EXPECT_NEAR(*acc.Value(), 1.0, 1e-12);
  for (int k = 17; k <= 49; ++k) Add(acc, k, 0.0, 0.9f);  // hidden 1.7 s to the end (4.9 s)
  EXPECT_NEAR(*acc.Value(), 3.2, 1e-12);
}

TEST_F(RetentionTest, NeverSeenIsNotScoredAndOccluderMassIsNotCredited) {
  OccludedRetentionAccumulator never_seen;
  for (int k = 0; k <= 5; ++k) Add(never_seen, k, 0.0, 0.9f);
  EXPECT_FALSE(never_seen.Value().has_value());

  // A wall right next to the pedestrian, believed occupied: once the pedestrian's own cells
  // are lost, the wall's mass within 1 m does not keep it.
  const sim::Shape wall = sim::Shape::Box(Pose2(5.0, 5.9, 0.0), 4.0, 0.5, sim::kStaticOwner);
  OccludedRetentionAccumulator acc;
  for (int k = 0; k <= 20; ++k) {
    const bool hidden = k > 10;
    const sim::TruthFrame f = Frame(k, hidden ? 0.0 : 1.0);
    const sim::TruthRaster truth = sim::RasteriseTruth(f, {wall}, g);
    GridBelief b = BeliefWith(truth, k <= 13 ? 0.9f : 0.5f, 0.5f);
    for (std::size_t i = 0; i < truth.owner.size(); ++i) {
      if (truth.owner[i] == sim::kStaticOwner) b.occupancy[i] = 0.95f;
    }
    acc.AddFrame(f, b, truth);
  }
  EXPECT_NEAR(*acc.Value(), 0.3, 1e-12);  // hidden at 1.1 s, lost at 1.4 s
}

// Plumbing against the real simulator: a still ego west of the junction, a pedestrian walking
// south out of the junction behind the south-west block. A perfect belief (the truth itself)
// scores 0 everywhere and keeps the hidden pedestrian for as long as it is hidden.
TEST(GridMetricsSimulatorTest, PerfectBeliefOnSimulatedFrames) {
  sim::Scenario scenario;
  scenario.name = "hidden-pedestrian";
  scenario.duration_s = 8.0;
  scenario.seed = 3;
  scenario.world.preset = "four_way";
  scenario.ego.path = {{-25, -1.75}, {60, -1.75}};
  scenario.ego.speed = sim::SpeedProfile::Constant(0.0);
  sim::ActorSpec ped;
  ped.id = "ped";
  ped.object_class = ObjectClass::kPedestrian;
  ped.path = {{0.0, -4.0}, {0.0, -40.0}};
  ped.speed = sim::SpeedProfile::Constant(1.5);
  ped.stop_s = scenario.duration_s;
  scenario.actors.push_back(ped);
  const sim::Simulator simulator(scenario);

  GridGeometry g = Geometry(200, 200, 0.25);  // 50 m x 50 m around the junction
  g.origin_m = Vector2d(-30.0, -30.0);
  const std::vector<std::uint8_t> in_range = WithinRangeMask(g, Vector2d(-23.0, -1.75), 40.0);
  VelocityRmseAccumulator rmse;
  FalseDynamicAccumulator false_dynamic;
  OccupancyBrierAccumulator brier;
  OccludedRetentionAccumulator retention;
  bool seen = false;
  bool hidden = false;  // (not std::optional: gcc 12 warns maybe-uninitialized on it)
  TimeNs hidden_since = 0;
  double expected_retention_s = 0.0;
  TimeNs last = 0;
  for (int k = 0; k <= 80; ++k) {
    const sim::TruthFrame frame = simulator.Truth(TimeNs{k} * 100'000'000);
    const sim::TruthRaster truth = sim::RasteriseTruth(frame, simulator.static_world(), g);
    GridBelief belief = Belief(g, 0.0f);
    for (std::size_t i = 0; i < truth.occupied.size(); ++i) {
      if (!truth.occupied[i]) continue;
      SetBelief(belief, i, 1.0f, truth.velocity[i].x(), truth.velocity[i].y(), 1.0f);
    }
    rmse.AddFrame(belief, truth);
    false_dynamic.AddFrame(belief, truth);
    brier.AddFrame(belief, truth, in_range);
    retention.AddFrame(frame, belief, truth);
    // The expected retention, straight from the definition for a belief that never loses mass.
    ASSERT_EQ(frame.actors.size(), 1u);
    last = frame.stamp;
    if (frame.actors[0].visible_fraction_lidar > 0.0) {
      if (hidden) {
        expected_retention_s =
            std::max(expected_retention_s, ToSeconds(frame.stamp - hidden_since));
      }
      hidden = false;
      seen = true;
    } else if (seen && !hidden) {
      hidden = true;
      hidden_since = frame.stamp;
    }
  }
  if (hidden) {
    expected_retention_s = std::max(expected_retention_s, ToSeconds(last - hidden_since));
  }
  ASSERT_GT(rmse.cells(), 0);
  EXPECT_EQ(*rmse.Value(), 0.0);
  ASSERT_GT(false_dynamic.counts().static_cells, 0);
  EXPECT_EQ(*false_dynamic.Value(), 0.0);
  EXPECT_EQ(*brier.Value(), 0.0);
  ASSERT_GT(expected_retention_s, 1.0) << "the scenario should hide the pedestrian";
  ASSERT_TRUE(retention.Value().has_value());
  EXPECT_NEAR(*retention.Value(), expected_retention_s, 1e-9);
}

}  // namespace
}  // namespace lookout::eval
