#include "lookout/tracking/benchmark_scene.h"

#include <gtest/gtest.h>

#include "lookout/tracking/gnn_tracker.h"
#include "lookout/tracking/mht_tracker.h"

namespace lookout::tracking {
namespace {

TEST(BenchmarkScene, HasTheTargetsAndFalseObjectsItSays) {
  const BenchmarkScene a = MakeBenchmarkScene(30, 10, 25, 7);
  ASSERT_EQ(a.scans.size(), 25u);
  EXPECT_DOUBLE_EQ(a.clutter_density_per_m2, 10.0 / 1e4);
  std::size_t detections = 0;
  for (std::size_t k = 0; k < a.scans.size(); ++k) {
    ASSERT_EQ(a.truth[k].size(), 30u);
    EXPECT_GE(a.scans[k].size(), 10u);
    EXPECT_LE(a.scans[k].size(), 40u);
    detections += a.scans[k].size() - 10;
    for (const Eigen::Vector2d& p : a.truth[k]) {
      EXPECT_LT(p.cwiseAbs().maxCoeff(), BenchmarkScene::kSideM / 2.0);
    }
  }
  // About 90 % of the targets are detected.
  EXPECT_NEAR(static_cast<double>(detections) / (25.0 * 30.0), 0.9, 0.05);
  const BenchmarkScene b = MakeBenchmarkScene(30, 10, 25, 7);
  EXPECT_EQ(a.scans.back().back().position_m, b.scans.back().back().position_m) << "seeded";
}

// What the benchmark times is a tracker doing its job: after 2 s every target has a confirmed
// track within 1 m, and few false objects made one.
template <typename T>
void ExpectTracksTheScene(T& tracker, const BenchmarkScene& scene, const char* name) {
  for (std::size_t k = 0; k < scene.scans.size(); ++k) {
    tracker.Step(scene.stamps[k], scene.scans[k]);
  }
  const std::vector<Track> tracks = tracker.ConfirmedTracks();
  int found = 0;
  for (const Eigen::Vector2d& p : scene.truth.back()) {
    for (const Track& t : tracks) {
      if ((t.Position() - p).norm() < 1.0) {
        ++found;
        break;
      }
    }
  }
  EXPECT_EQ(found, 30) << name;
  EXPECT_LE(tracks.size(), 33u) << name << ": false tracks";
}

TEST(BenchmarkScene, BothTrackersTrackIt) {
  const BenchmarkScene scene = MakeBenchmarkScene(30, 10, 21, 20261201);
  MhtOptions o;
  o.clutter_density_per_m2 = scene.clutter_density_per_m2;
  o.new_track_density_per_m2 = 2.0 * scene.clutter_density_per_m2;
  MhtTracker mht(o);
  ExpectTracksTheScene(mht, scene, "MHT");
  GnnTracker gnn;
  ExpectTracksTheScene(gnn, scene, "GNN");
}

}  // namespace
}  // namespace lookout::tracking
