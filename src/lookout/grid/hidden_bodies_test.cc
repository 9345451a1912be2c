#include "lookout/grid/hidden_bodies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {
namespace {

constexpr double kBodyCellM = 0.15;
constexpr double kBodyDtS = 0.08;
// 1.875 m/s: 1 cell a cycle along x, so that where the body is carried is a whole cell.
constexpr double kBodySpeedMps = kBodyCellM / kBodyDtS;
constexpr float kBodyHit = 0.7f, kBodyFree = 0.3f;

// A filter state by hand: a 3 x 3 body at x0..x0+2, y 20..22 believed occupied (0.9), moving
// at kBodySpeedMps along x with confidence 0.6, its cells linked (a rigid cluster); everything else
// seen free once (O = 0.2: writable, unlike the never-observed prior).
struct HiddenBodyScene {
  GridLayers layers{ScrollingGridGeometry(kBodyCellM, 48, 48, CellIndex{0, 0})};
  FilterLayerIds ids = AddFilterLayers(layers);
  HiddenBodies stage;
  HiddenBodyOptions options;
  int held_x0 = -1;  // the body the filter holds (HoldBodyAt), a rigid cluster; -1: none

  HiddenBodyScene() {
    const std::span<float> o = layers.Values(ids.occupancy);
    std::fill(o.begin(), o.end(), 0.2f);
  }

  std::size_t At(int x, int y) const { return layers.geometry().StorageIndexOfLocal({x, y}); }
  float Occupancy(int x, int y) const { return layers.Values(ids.occupancy)[At(x, y)]; }
  float Vx(int x, int y) const { return layers.Values(ids.velocity_x_mps)[At(x, y)]; }

  // The body's cells with x0 as its left column.
  std::vector<std::size_t> BodyCells(int x0) const {
    std::vector<std::size_t> cells;
    for (int y = 20; y <= 22; ++y) {
      for (int x = x0; x <= x0 + 2; ++x) cells.push_back(At(x, y));
    }
    return cells;
  }
  // What the filter would hold of the body with its left column at x0 (and nothing elsewhere).
  void HoldBodyAt(int x0) {
    held_x0 = x0;
    std::span<float> o = layers.Values(ids.occupancy);
    for (std::size_t s = 0; s < o.size(); ++s) {
      o[s] = std::min(o[s], 0.2f);
      layers.Values(ids.velocity_x_mps)[s] = 0.0f;
    }
    for (const std::size_t s : BodyCells(x0)) {
      o[s] = 0.9f;
      layers.Values(ids.velocity_x_mps)[s] = static_cast<float>(kBodySpeedMps);
      layers.Values(ids.velocity_y_mps)[s] = 0.0f;
      layers.Values(ids.velocity_confidence)[s] = 0.6f;
      for (const LayerId d : ids.rigidity) layers.Values(d)[s] = 0.3f;
    }
  }
  // The filter having lost the body: its cells back to what a spread left (under the stage's
  // min_occupancy, no cluster).
  void LoseBody() {
    held_x0 = -1;
    std::span<float> o = layers.Values(ids.occupancy);
    for (std::size_t s = 0; s < o.size(); ++s) o[s] = std::min(o[s], 0.55f);
  }
  // A scan that sees everything free but `hits`, and nothing in `hidden`.
  MeasurementGrid Scan(const std::vector<std::size_t>& hits,
                       const std::vector<std::size_t>& hidden) const {
    MeasurementGrid z;
    z.geometry = layers.geometry();
    z.p_occupied.assign(layers.geometry().CellCount(), kBodyFree);
    for (const std::size_t s : hits) z.p_occupied[s] = kBodyHit;
    for (const std::size_t s : hidden) z.p_occupied[s] = kUnknownProbability;
    return z;
  }
  // The stage after the clusters' one, which found the body the filter holds (if any) and
  // measured `measured`.
  void Update(const MeasurementGrid& z, const std::vector<MeasuredBody>& measured) {
    ClusterStageOutput found;
    if (held_x0 >= 0) found.clusters.push_back(BodyCells(held_x0));
    found.measured = measured;
    stage.Update(layers, ids, z, kBodyDtS, found, ClusterMotionOptions{}.staying_min_hit_scans,
                 options);
  }
  // Three cycles seen and measured moving (left column x0 - 3 .. x0 - 1), then the cycle it goes
  // into a shadow that covers x >= shadow_x0 (its left column x0): remembered there.
  void SeeThenHide(int x0, int shadow_x0) {
    for (int k = 3; k >= 1; --k) {
      HoldBodyAt(x0 - k);
      Update(Scan(BodyCells(x0 - k), {}), {MeasuredBody{BodyCells(x0 - k), kBodySpeedMps, 0.0}});
    }
    HoldBodyAt(x0);
    Update(Scan({}, Shadow(shadow_x0)), {});
  }
  std::vector<std::size_t> Shadow(int x_from) const {
    std::vector<std::size_t> cells;
    for (int y = 0; y < 48; ++y) {
      for (int x = x_from; x < 48; ++x) cells.push_back(At(x, y));
    }
    return cells;
  }
};

TEST(HiddenBodiesTest, ABodyGoingIntoAShadowIsCarriedWholeAtItsVelocity) {
  HiddenBodyScene scene;
  scene.SeeThenHide(10, 10);
  ASSERT_EQ(scene.stage.bodies().size(), 1u);
  EXPECT_NEAR(scene.stage.bodies()[0].velocity_x_mps, kBodySpeedMps, 1e-6);
  // Twelve cycles in the shadow, the filter having lost it: the body is one cell further each
  // cycle, with its occupancy and velocity, and nowhere else.
  for (int k = 1; k <= 12; ++k) {
    scene.LoseBody();
    scene.Update(scene.Scan({}, scene.Shadow(10)), {});
    ASSERT_EQ(scene.stage.bodies().size(), 1u) << "cycle " << k;
    for (int y = 20; y <= 22; ++y) {
      for (int x = 10 + k; x <= 12 + k; ++x) {
        EXPECT_FLOAT_EQ(scene.Occupancy(x, y), 0.9f)
            << "cycle " << k << " (" << x << ", " << y << ")";
        EXPECT_FLOAT_EQ(scene.Vx(x, y), static_cast<float>(kBodySpeedMps));
      }
      EXPECT_LE(scene.Occupancy(9 + k, y), 0.55f) << "behind it, cycle " << k;
      EXPECT_LE(scene.Occupancy(13 + k, y), 0.55f) << "ahead of it, cycle " << k;
    }
  }
}

TEST(HiddenBodiesTest, TheMaskShowsTheCarriedBodyInWindowOrder) {
  HiddenBodyScene scene;
  const ScrollingGridGeometry& g = scene.layers.geometry();
  EXPECT_EQ(HiddenBodyMask(scene.stage, g), std::vector<std::uint8_t>(g.CellCount(), 0));
  scene.SeeThenHide(10, 10);
  scene.LoseBody();
  scene.Update(scene.Scan({}, scene.Shadow(10)), {});  // carried to columns 11-13, rows 20-22
  const std::vector<std::uint8_t> mask = HiddenBodyMask(scene.stage, g);
  ASSERT_EQ(mask.size(), g.CellCount());
  int set = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const bool body = x >= 11 && x <= 13 && y >= 20 && y <= 22;
      const std::uint8_t m = mask[static_cast<std::size_t>(y * g.width() + x)];
      EXPECT_EQ(m, body ? 1 : 0) << "(" << x << ", " << y << ")";
      set += m;
    }
  }
  EXPECT_EQ(set, 9);
}

TEST(HiddenBodiesTest, ABodyNeverMeasuredMovingIsNotRemembered) {
  // The static world's false-dynamic clusters: dynamic in the filter, never measured whole.
  HiddenBodyScene scene;
  for (int k = 3; k >= 1; --k) {
    scene.HoldBodyAt(10 - k);
    scene.Update(scene.Scan(scene.BodyCells(10 - k), {}), {});
  }
  scene.HoldBodyAt(10);
  scene.Update(scene.Scan({}, scene.Shadow(10)), {});
  EXPECT_TRUE(scene.stage.bodies().empty());
  // Measured once only: not enough either (confirm_min_measurements 3).
  HiddenBodyScene once;
  once.HoldBodyAt(9);
  once.Update(once.Scan(once.BodyCells(9), {}),
              {MeasuredBody{once.BodyCells(9), kBodySpeedMps, 0.0}});
  once.HoldBodyAt(10);
  once.Update(once.Scan({}, once.Shadow(10)), {});
  EXPECT_TRUE(once.stage.bodies().empty());
}

// Step 5: a mover the filter loses between two cycles (its cluster gone before half of it is
// unobserved: out of the field of view at once) is remembered from its measurements, at their
// mean velocity; measured twice only, or seen free where it would be, it is not.
TEST(HiddenBodiesTest, AMoverLostBetweenTwoCyclesIsRememberedFromItsMeasurements) {
  // Three measurements 0.3 m/s apart around kBodySpeedMps, each carried at its own velocity:
  // within a cell of each other a cycle or two later.
  const std::vector<double> measured_mps = {kBodySpeedMps - 0.3, kBodySpeedMps + 0.3,
                                            kBodySpeedMps};
  const auto see = [&](HiddenBodyScene& scene, std::size_t measurements) {
    for (std::size_t k = 0; k < measurements; ++k) {
      const int x0 = 7 + static_cast<int>(k);
      scene.HoldBodyAt(x0);
      scene.Update(scene.Scan(scene.BodyCells(x0), {}),
                   {MeasuredBody{scene.BodyCells(x0), measured_mps[k], 0.0}});
    }
    scene.LoseBody();  // no cluster left
  };
  HiddenBodyScene lost;
  see(lost, 3);
  lost.Update(lost.Scan({}, lost.Shadow(0)), {});  // nothing in view
  ASSERT_EQ(lost.stage.bodies().size(), 1u);
  EXPECT_NEAR(lost.stage.bodies()[0].velocity_x_mps, kBodySpeedMps, 1e-9);
  EXPECT_NEAR(lost.stage.bodies()[0].velocity_y_mps, 0.0, 1e-9);
  // Carried and written: measured last with its left column at 9, one cycle to 10, the next to 11.
  lost.LoseBody();
  lost.Update(lost.Scan({}, lost.Shadow(0)), {});
  for (int y = 20; y <= 22; ++y) {
    for (int x = 11; x <= 13; ++x) {
      EXPECT_FLOAT_EQ(lost.Occupancy(x, y), 0.9f) << "(" << x << ", " << y << ")";
      EXPECT_FLOAT_EQ(lost.Vx(x, y), static_cast<float>(kBodySpeedMps));
    }
    EXPECT_LE(lost.Occupancy(14, y), 0.55f);
  }

  HiddenBodyScene twice;
  see(twice, 2);
  twice.Update(twice.Scan({}, twice.Shadow(0)), {});
  EXPECT_TRUE(twice.stage.bodies().empty());

  HiddenBodyScene seen_free;  // it stopped, or turned away: the scan sees its place free
  see(seen_free, 3);
  seen_free.Update(seen_free.Scan({}, {}), {});
  EXPECT_TRUE(seen_free.stage.bodies().empty());
}

TEST(HiddenBodiesTest, AMoverLostInViewIsRememberedWhenItsShadowComesLater) {
  // Measured three times (left column 7, 8, 9), then no longer a cluster though the scan still
  // hits it (a far walker a nearer one starts to cover), seven cycles (0.56 s, more than
  // confirm_s) in view; then a shadow over it. lost_memory_s: how long the newest measurement
  // is looked for.
  const auto lose_in_view_then_hide = [](HiddenBodyScene& scene) {
    for (int x0 = 7; x0 <= 9; ++x0) {
      scene.HoldBodyAt(x0);
      scene.Update(scene.Scan(scene.BodyCells(x0), {}),
                   {MeasuredBody{scene.BodyCells(x0), kBodySpeedMps, 0.0}});
    }
    for (int x0 = 10; x0 <= 16; ++x0) {
      scene.LoseBody();
      scene.Update(scene.Scan(scene.BodyCells(x0), {}), {});
      EXPECT_TRUE(scene.stage.bodies().empty()) << "in view at " << x0;
    }
    scene.Update(scene.Scan({}, scene.Shadow(0)), {});  // left column 17, hidden
  };
  HiddenBodyScene remembered;
  ASSERT_GT(7 * kBodyDtS, remembered.options.confirm_s);
  ASSERT_LE(8 * kBodyDtS, remembered.options.lost_memory_s);
  lose_in_view_then_hide(remembered);
  ASSERT_EQ(remembered.stage.bodies().size(), 1u);
  EXPECT_NEAR(remembered.stage.bodies()[0].velocity_x_mps, kBodySpeedMps, 1e-9);
  remembered.Update(remembered.Scan({}, remembered.Shadow(0)), {});  // carried to 18
  for (int y = 20; y <= 22; ++y) {
    for (int x = 18; x <= 20; ++x) {
      EXPECT_FLOAT_EQ(remembered.Occupancy(x, y), 0.9f) << "(" << x << ", " << y << ")";
    }
    EXPECT_LE(remembered.Occupancy(17, y), 0.55f);
    EXPECT_LE(remembered.Occupancy(21, y), 0.55f);
  }

  HiddenBodyScene forgotten;  // looked for no longer than the confirmation's window
  forgotten.options.lost_memory_s = forgotten.options.confirm_s;
  lose_in_view_then_hide(forgotten);
  EXPECT_TRUE(forgotten.stage.bodies().empty());
}

TEST(HiddenBodiesTest, WhereTheScanSeesItFreeItIsNotThere) {
  // The shadow's front edge at x = 14: carried one cell a cycle, the body's leading column
  // reaches it on the second cycle and is seen free there; one cell back it is not: shifted back.
  HiddenBodyScene scene;
  scene.SeeThenHide(10, 10);
  std::vector<std::size_t> shadow;
  for (int y = 0; y < 48; ++y) {
    for (int x = 10; x < 14; ++x) shadow.push_back(scene.At(x, y));
  }
  scene.LoseBody();
  scene.Update(scene.Scan({}, shadow), {});  // left column 11: columns 11-13, all hidden
  scene.LoseBody();
  scene.Update(scene.Scan({}, shadow), {});  // carried to 12: column 14 seen free; back to 11
  ASSERT_EQ(scene.stage.bodies().size(), 1u);
  EXPECT_FLOAT_EQ(scene.Occupancy(11, 21), 0.9f);
  EXPECT_FLOAT_EQ(scene.Occupancy(13, 21), 0.9f);
  EXPECT_LE(scene.Occupancy(14, 21), 0.55f);
  // Seen free all over (the shadow gone, no return): forgotten, nothing written.
  scene.LoseBody();
  scene.Update(scene.Scan({}, {}), {});
  EXPECT_TRUE(scene.stage.bodies().empty());
  EXPECT_LE(scene.Occupancy(12, 21), 0.55f);
}

TEST(HiddenBodiesTest, ForgottenWhenMeasuredAgainOrHiddenTooLong) {
  HiddenBodyScene measured;
  measured.SeeThenHide(10, 10);
  ASSERT_EQ(measured.stage.bodies().size(), 1u);
  // Out of the shadow and measured by the clusters' stage where it was carried: in view enough,
  // the memory steps aside.
  measured.HoldBodyAt(11);
  measured.Update(measured.Scan(measured.BodyCells(11), measured.Shadow(14)),
                  {MeasuredBody{measured.BodyCells(11), kBodySpeedMps, 0.0}});
  EXPECT_TRUE(measured.stage.bodies().empty());

  HiddenBodyScene old;
  old.options.max_hidden_s = 0.5;  // six cycles
  // Step 5 looks for a lost mover this long after its newest measurement: longer than the body
  // is carried here, it would remember it again from the measurements made before it hid.
  old.options.lost_memory_s = old.options.max_hidden_s;
  old.SeeThenHide(10, 0);
  ASSERT_EQ(old.stage.bodies().size(), 1u);
  for (int k = 1; k <= 6; ++k) old.Update(old.Scan({}, old.Shadow(0)), {});
  EXPECT_EQ(old.stage.bodies().size(), 1u);
  old.Update(old.Scan({}, old.Shadow(0)), {});
  EXPECT_TRUE(old.stage.bodies().empty());
}

TEST(HiddenBodiesTest, WritesNeitherObservedCellsNorWallsNorTheNeverSeen) {
  HiddenBodyScene scene;
  scene.SeeThenHide(10, 10);
  ASSERT_EQ(scene.stage.bodies().size(), 1u);
  scene.LoseBody();
  // Next cycle the body is at columns 11-13. Row 20: hit by the scan (another thing there);
  // (12, 21): a wall's place, hit a second in a row before the shadow; (13, 22): never observed.
  std::vector<std::size_t> hidden = scene.Shadow(10);
  std::vector<std::size_t> hits;
  for (int x = 11; x <= 13; ++x) hits.push_back(scene.At(x, 20));
  std::erase_if(
      hidden, [&](std::size_t s) { return std::find(hits.begin(), hits.end(), s) != hits.end(); });
  scene.layers.Values(scene.ids.hit_scans)[scene.At(12, 21)] = 12.0f;
  scene.layers.Values(scene.ids.occupancy)[scene.At(13, 22)] = kUnknownProbability;
  scene.Update(scene.Scan(hits, hidden), {});
  ASSERT_EQ(scene.stage.bodies().size(), 1u);
  for (int x = 11; x <= 13; ++x) EXPECT_LE(scene.Occupancy(x, 20), 0.55f) << x;
  EXPECT_LE(scene.Occupancy(12, 21), 0.55f);
  EXPECT_FLOAT_EQ(scene.Occupancy(13, 22), kUnknownProbability);
  EXPECT_FLOAT_EQ(scene.Occupancy(11, 21), 0.9f);  // the rest is written
  EXPECT_FLOAT_EQ(scene.Occupancy(13, 21), 0.9f);
}

TEST(HiddenBodiesTest, OffForgetsEverything) {
  HiddenBodyScene scene;
  scene.SeeThenHide(10, 10);
  ASSERT_EQ(scene.stage.bodies().size(), 1u);
  scene.options.enabled = false;
  scene.LoseBody();
  scene.Update(scene.Scan({}, scene.Shadow(10)), {});
  EXPECT_TRUE(scene.stage.bodies().empty());
  EXPECT_LE(scene.Occupancy(12, 21), 0.55f);
}

TEST(HiddenBodyOptionsTest, ValidateNamesTheField) {
  HiddenBodyOptions o;
  EXPECT_NO_THROW(o.Validate());
  o.drop_free_share = 1.5;
  try {
    o.Validate("test");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid.filter.hidden_bodies.drop_free_share"),
              std::string::npos)
        << e.what();
  }
  o = {};
  o.confirm_min_measurements = 0;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.shift_cells = 5;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.lost_memory_s = -0.1;
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::grid
