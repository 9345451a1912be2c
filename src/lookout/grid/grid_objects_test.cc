#include "lookout/grid/grid_objects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "lookout/core/input_error.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

constexpr double kCellW = 0.15;
constexpr double kTickS = 0.08;

// A 30 m x 30 m window centred on the odometry frame's origin.
ExtendedGrid MakeGrid() {
  return ExtendedGrid(ScrollingGridGeometry(kCellW, 200, 200, {-100, -100}));
}

// An axis-aligned box in the odometry frame [lo, hi) (edges on cell boundaries in the tests, so
// its cells are exactly the box), and the state the filter would hold for a tracked rigid body.
struct SeededBox {
  Vector2d lo, hi;
  Vector2d velocity_mps = Vector2d::Zero();
  float occupancy = 0.9f;
  float confidence = 0.9f;
  float link = 0.3f;
  GridClass grid_class = GridClass::kVehicle;
  Vector2d Center() const { return 0.5 * (lo + hi); }
};

template <typename Fn>
void ForCellsIn(const ExtendedGrid& grid, const Vector2d& lo, const Vector2d& hi, const Fn& fn) {
  const ScrollingGridGeometry& g = grid.geometry();
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Vector2d c = g.CellCenterM(g.GlobalFromLocal({x, y}));
      if ((c.array() >= lo.array()).all() && (c.array() < hi.array()).all()) {
        fn(g.StorageIndexOfLocal({x, y}), c);
      }
    }
  }
}

void Seed(ExtendedGrid& grid, const SeededBox& box) {
  GridLayers& layers = grid.mutable_layers();
  const FilterLayerIds& ids = grid.ids();
  ForCellsIn(grid, box.lo, box.hi, [&](std::size_t i, const Vector2d&) {
    layers.Values(ids.occupancy)[i] = box.occupancy;
    layers.Values(ids.velocity_x_mps)[i] = static_cast<float>(box.velocity_mps.x());
    layers.Values(ids.velocity_y_mps)[i] = static_cast<float>(box.velocity_mps.y());
    layers.Values(ids.velocity_confidence)[i] = box.confidence;
    for (const LayerId d : ids.rigidity) layers.Values(d)[i] = box.link;
    for (int c = 0; c < kGridClassCount; ++c) {
      layers.Values(ids.class_pmf[static_cast<std::size_t>(c)])[i] =
          c == static_cast<int>(box.grid_class) ? 0.8f : 0.05f;
    }
  });
}

const LidarObject* Nearest(const LidarObjectFrame& frame, const Vector2d& p) {
  const LidarObject* best = nullptr;
  for (const LidarObject& o : frame.objects) {
    if (!best || (o.centroid_m - p).norm() < (best->centroid_m - p).norm()) best = &o;
  }
  return best;
}

ObjectFrameContext Context(const Pose2& ego, const Pose2& mount) {
  ObjectFrameContext c;
  c.stamp = 1'000'000'000;
  c.ego_pose = ego;
  c.lidar_mount = mount;
  c.dt_s = kTickS;
  return c;
}

TEST(GridObjectsTest, TwoMovingBoxesGiveTwoObjectsInTheVehicleFrame) {
  ExtendedGrid grid = MakeGrid();
  // A car along x at 5 m/s (30 x 12 cells) and a van along -y at 3 m/s (12 x 30 cells).
  const SeededBox car{{4.05, -0.9}, {8.55, 0.9}, {5.0, 0.0}};
  const SeededBox van{{-6.0, 3.0}, {-4.2, 7.5}, {0.0, -3.0}};
  Seed(grid, car);
  Seed(grid, van);
  const Pose2 ego(2.0, 1.0, 0.3);
  const Pose2 mount(1.2, 0.0, 0.0);
  const LidarObjectFrame frame = ExtractGridObjects(grid, Context(ego, mount), {});
  EXPECT_EQ(frame.stamp, 1'000'000'000);
  EXPECT_EQ(frame.ego_pose.yaw, ego.yaw);
  ASSERT_EQ(frame.objects.size(), 2u);
  EXPECT_NE(frame.objects[0].id, frame.objects[1].id);

  const Pose2 vehicle_from_odom = ego.Inverse();
  const Eigen::Matrix2d r = vehicle_from_odom.Rotation();
  for (const SeededBox& box : {car, van}) {
    const Vector2d centre = vehicle_from_odom * box.Center();
    const LidarObject* o = Nearest(frame, centre);
    ASSERT_NE(o, nullptr);
    EXPECT_TRUE(o->dynamic);
    EXPECT_EQ(o->cell_count, 360u);
    EXPECT_NEAR((o->centroid_m - centre).norm(), 0.0, 1e-6);
    // Range and bearing of the centroid in the lidar frame.
    const Vector2d in_lidar = mount.Inverse() * centre;
    EXPECT_NEAR(o->range_m, in_lidar.norm(), 1e-6);
    EXPECT_NEAR(o->bearing_rad, std::atan2(in_lidar.y(), in_lidar.x()), 1e-9);
    // The extent of the cells' squares: the box, its length along the motion.
    EXPECT_NEAR(o->length_m, 4.5, 1e-6);
    EXPECT_NEAR(o->width_m, 1.8, 1e-6);
    const double heading_odom = std::atan2(box.velocity_mps.y(), box.velocity_mps.x());
    EXPECT_NEAR(WrapAngle(o->yaw_rad - (heading_odom - ego.yaw)), 0.0, 1e-6);
    EXPECT_NEAR((o->velocity_mps - r * box.velocity_mps).norm(), 0.0, 1e-5);
    // Equal velocities: no spread, only the cell quantisation (cell / dt)^2 / 12.
    const double q = (kCellW / kTickS) * (kCellW / kTickS) / 12.0;
    EXPECT_NEAR(o->velocity_covariance(0, 0), q, 1e-6);
    EXPECT_NEAR(o->velocity_covariance(1, 1), q, 1e-6);
    EXPECT_NEAR(o->velocity_covariance(0, 1), 0.0, 1e-6);
    // The point: the quantisation of a cell plus the box's spread over its 360 cells; the
    // spread along the 4.5 m side is 4.5^2 / 12 (a uniform box) up to the lattice.
    EXPECT_GT(o->point_covariance.trace(), 2.0 * kCellW * kCellW / 12.0);
    EXPECT_NEAR(o->point_covariance.trace(),
                2.0 * kCellW * kCellW / 12.0 + (4.5 * 4.5 + 1.8 * 1.8) / 12.0 / 360.0, 2e-4);
    EXPECT_NEAR(o->class_pmf[static_cast<std::size_t>(ObjectClass::kCar)], 0.8, 1e-6);
    double total = 0.0;
    for (const double p : o->class_pmf) total += p;
    EXPECT_NEAR(total, 1.0, 1e-9);
  }
}

TEST(GridObjectsTest, StaticWallAndUnsureMotionGiveNone) {
  ExtendedGrid grid = MakeGrid();
  Seed(grid, SeededBox{{-12.0, 9.0}, {12.0, 9.6}, {0.0, 0.0}, 0.95f, 0.9f, 0.3f,
                       GridClass::kStatic});                            // a wall
  Seed(grid, SeededBox{{-12.0, -9.6}, {12.0, -9.0}, {0.3, 0.2}});      // creeping below 0.5 m/s
  Seed(grid, SeededBox{{0.0, 0.0}, {4.5, 1.8}, {8.0, 0.0}, 0.9f, 0.2f}); // velocity not trusted
  Seed(grid, SeededBox{{-3.0, -3.0}, {-2.7, -2.85}, {4.0, 0.0}});      // two cells only
  Seed(grid, SeededBox{{5.0, 5.0}, {9.5, 6.8}, {4.0, 0.0}, 0.55f});    // barely above the prior
  const LidarObjectFrame frame = ExtractGridObjects(grid, Context(Pose2(), Pose2()), {});
  EXPECT_TRUE(frame.objects.empty()) << frame.objects.size() << " objects";
}

TEST(GridObjectsTest, ClusterWhoseLinksAreCutSplits) {
  ExtendedGrid grid = MakeGrid();
  const SeededBox bus{{0.0, 0.0}, {6.0, 2.4}, {4.0, 0.0}};  // 40 x 16 cells
  Seed(grid, bus);
  const LidarObjectFrame whole = ExtractGridObjects(grid, Context(Pose2(), Pose2()), {});
  ASSERT_EQ(whole.objects.size(), 1u);
  EXPECT_EQ(whole.objects[0].cell_count, 640u);

  // Cut every link across x = 2.4 m (between cell columns 15 and 16), in both directions:
  // D(x, x + offset) of the cells left of the cut towards +x, right of it towards -x.
  GridLayers& layers = grid.mutable_layers();
  const FilterLayerIds& ids = grid.ids();
  ForCellsIn(grid, bus.lo, bus.hi, [&](std::size_t i, const Vector2d& c) {
    const bool left = c.x() < 2.4 && c.x() > 2.4 - kCellW;
    const bool right = c.x() > 2.4 && c.x() < 2.4 + kCellW;
    for (std::size_t d = 0; d < kNeighbourCount; ++d) {
      if ((left && kNeighbourOffsets[d].ix > 0) || (right && kNeighbourOffsets[d].ix < 0)) {
        layers.Values(ids.rigidity[d])[i] = 0.01f;  // below min_link
      }
    }
  });
  const LidarObjectFrame split = ExtractGridObjects(grid, Context(Pose2(), Pose2()), {});
  ASSERT_EQ(split.objects.size(), 2u);
  const LidarObject* front = Nearest(split, {4.2, 1.2});
  const LidarObject* rear = Nearest(split, {1.2, 1.2});
  ASSERT_NE(front, rear);
  EXPECT_EQ(rear->cell_count, 16u * 16u);
  EXPECT_EQ(front->cell_count, 24u * 16u);
  EXPECT_NEAR(rear->centroid_m.x(), 1.2, 1e-6);
  EXPECT_NEAR(front->centroid_m.x(), 4.2, 1e-6);

  // A link cut on one side only still joins (the larger of the two links counts).
  Seed(grid, bus);
  ForCellsIn(grid, bus.lo, bus.hi, [&](std::size_t i, const Vector2d& c) {
    if (c.x() < 2.4 && c.x() > 2.4 - kCellW) {
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        if (kNeighbourOffsets[d].ix > 0) layers.Values(ids.rigidity[d])[i] = 0.0f;
      }
    }
  });
  EXPECT_EQ(ExtractGridObjects(grid, Context(Pose2(), Pose2()), {}).objects.size(), 1u);
}

TEST(GridObjectsTest, FrontSegmentFacesTheLidar) {
  // Lidar at the vehicle origin; boxes ahead of it and to its left.
  struct Case {
    SeededBox box;
    Vector2d start, end;  // the cells at the lowest and the highest bearing
  };
  const double h = kCellW / 2.0;
  const std::vector<Case> cases = {
      {SeededBox{{10.05, -0.9}, {14.55, 0.9}, {-5.0, 0.0}}, {10.05 + h, -0.9 + h},
       {10.05 + h, 0.9 - h}},
      {SeededBox{{-2.25, 10.05}, {2.25, 11.85}, {5.0, 0.0}}, {2.25 - h, 10.05 + h},
       {-2.25 + h, 10.05 + h}},
  };
  for (const Case& c : cases) {
    ExtendedGrid grid = MakeGrid();
    Seed(grid, c.box);
    const LidarObjectFrame frame = ExtractGridObjects(grid, Context(Pose2(), Pose2()), {});
    ASSERT_EQ(frame.objects.size(), 1u);
    const LidarObject& o = frame.objects[0];
    EXPECT_NEAR((o.front_start_m - c.start).norm(), 0.0, 1e-6);
    EXPECT_NEAR((o.front_end_m - c.end).norm(), 0.0, 1e-6);
    EXPECT_NEAR((o.point_m - 0.5 * (c.start + c.end)).norm(), 0.0, 1e-9);
    EXPECT_LT(o.point_m.norm(), o.centroid_m.norm());  // the front is nearer than the centre
  }
}

TEST(GridObjectsTest, ScrollingTheWindowChangesNothing) {
  // Storage order wraps when the window moves; clusters are searched in window order, so the
  // objects (ids included) do not depend on where the cells are stored.
  ExtendedGrid grid = MakeGrid();
  Seed(grid, SeededBox{{4.05, -0.9}, {8.55, 0.9}, {5.0, 0.0}});
  Seed(grid, SeededBox{{-6.0, 3.0}, {-4.2, 7.5}, {0.0, -3.0}});
  Seed(grid, SeededBox{{-1.05, -6.0}, {-0.45, -5.4}, {0.0, 1.2}, 0.9f, 0.9f, 0.3f,
                       GridClass::kPedestrian});
  const ObjectFrameContext context = Context(Pose2(0.5, 0.2, -0.4), Pose2(1.0, 0.0, 0.0));
  const LidarObjectFrame before = ExtractGridObjects(grid, context, {});
  grid.Recenter(Vector2d(2.1, 1.3));  // 14 and 9 cells: every box stays in the window
  const LidarObjectFrame after = ExtractGridObjects(grid, context, {});
  ASSERT_EQ(before.objects.size(), 3u);
  ASSERT_EQ(after.objects.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const LidarObject& a = before.objects[k];
    const LidarObject& b = after.objects[k];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.cell_count, b.cell_count);
    EXPECT_NEAR((a.centroid_m - b.centroid_m).norm(), 0.0, 1e-9);
    EXPECT_NEAR((a.point_m - b.point_m).norm(), 0.0, 1e-9);
    EXPECT_NEAR((a.velocity_mps - b.velocity_mps).norm(), 0.0, 1e-9);
  }
  const LidarObject* walker = Nearest(after, context.ego_pose.Inverse() * Vector2d(-0.75, -5.7));
  ASSERT_NE(walker, nullptr);
  EXPECT_EQ(walker->cell_count, 16u);
  EXPECT_NEAR(walker->class_pmf[static_cast<std::size_t>(ObjectClass::kPedestrian)], 0.8, 1e-6);
}

// A synthetic measurement: p_hit in the box's cells, p_free elsewhere (as extended_grid_test).
MeasurementGrid MeasureBox(const ScrollingGridGeometry& g, const Vector2d& lo, const Vector2d& hi) {
  MeasurementGrid z;
  z.geometry = g;
  z.p_occupied.assign(g.CellCount(), 0.3f);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Vector2d c = g.CellCenterM(g.GlobalFromLocal({x, y}));
      if ((c.array() >= lo.array()).all() && (c.array() < hi.array()).all()) {
        z.p_occupied[g.StorageIndexOfLocal({x, y})] = 0.7f;
      }
    }
  }
  for (std::size_t i = 0; i < z.p_occupied.size(); ++i) z.touched.push_back(i);
  return z;
}

TEST(GridObjectsTest, BoxTrackedByTheFilterBecomesOneObject) {
  // The filter itself, not a seeded state: a 0.9 m x 0.6 m box at 3.75 m/s (the filter test's
  // MovingBoxVelocityConvergesFromRest), 25 cycles.
  ExtendedGrid grid(ScrollingGridGeometry(kCellW, 128, 24, {0, 0}));
  const Vector2d v(3.75, 0.0), size(0.9, 0.6), start(0.9, 1.5);
  Vector2d lo = start;
  for (int k = 0; k < 25; ++k) {
    lo = start + v * (k * kTickS);
    grid.Update(MeasureBox(grid.geometry(), lo, lo + size), kTickS);
  }
  const LidarObjectFrame frame = ExtractGridObjects(grid, Context(Pose2(), Pose2()), {});
  int dynamic = 0;
  for (const LidarObject& o : frame.objects) {
    std::printf("object %u: %u cells at (%.2f, %.2f), v (%.2f, %.2f)\n", o.id, o.cell_count,
                o.centroid_m.x(), o.centroid_m.y(), o.velocity_mps.x(), o.velocity_mps.y());
    dynamic += o.dynamic ? 1 : 0;
  }
  ASSERT_EQ(dynamic, 1);
  const LidarObject* o = Nearest(frame, lo + size / 2.0);
  EXPECT_LT((o->centroid_m - (lo + size / 2.0)).norm(), 0.3);
  EXPECT_LT((o->velocity_mps - v).norm(), 0.5);
}

TEST(GridObjectsTest, ClassesMapOntoObjectClasses) {
  const auto p = ToObjectClassPmf({0.1, 0.2, 0.3, 0.3, 0.1});
  EXPECT_NEAR(p[static_cast<std::size_t>(ObjectClass::kUnknown)], 0.2, 1e-12);
  EXPECT_NEAR(p[static_cast<std::size_t>(ObjectClass::kPedestrian)], 0.2, 1e-12);
  EXPECT_NEAR(p[static_cast<std::size_t>(ObjectClass::kCyclist)], 0.3, 1e-12);
  EXPECT_NEAR(p[static_cast<std::size_t>(ObjectClass::kCar)], 0.3, 1e-12);
  EXPECT_EQ(p[static_cast<std::size_t>(ObjectClass::kTruck)], 0.0);
  EXPECT_EQ(p[static_cast<std::size_t>(ObjectClass::kPole)], 0.0);
  const auto none = ToObjectClassPmf({0.0, 0.0, 0.0, 0.0, 0.0});
  EXPECT_EQ(none[static_cast<std::size_t>(ObjectClass::kUnknown)], 1.0);
}

// DynamicCellMask skips blocks of cells by a float test before its exact one: on random layers,
// most values on or next to the thresholds (NaN among them), the mask is its definition.
TEST(GridObjectsTest, DynamicCellMaskIsItsDefinitionAtTheThresholds) {
  const std::uint64_t seed = 4409;
  std::mt19937_64 rng(seed);
  ExtendedGrid grid = MakeGrid();
  GridLayers& layers = grid.mutable_layers();
  const FilterLayerIds& ids = grid.ids();
  const GridObjectOptions options;
  const auto near = [&](double threshold) {
    const auto f = static_cast<float>(threshold);
    switch (rng() % 6) {
      case 0:
        return f;
      case 1:
        return std::nextafter(f, 0.0f);
      case 2:
        return std::nextafter(f, 2.0f);
      case 3:
        return std::numeric_limits<float>::quiet_NaN();
      default:
        return static_cast<float>(std::uniform_real_distribution<double>(0.0, 1.0)(rng));
    }
  };
  const std::size_t cells = grid.geometry().CellCount();
  for (std::size_t i = 0; i < cells; ++i) {
    // Occupied cells sparse, as on the road: a block of cells holds one or none, so that a
    // block whose only cell sits on the threshold is decided by the block test too.
    const bool empty = i % 41 != 0;
    layers.Values(ids.occupancy)[i] = empty ? 0.02f : near(options.min_occupancy);
    layers.Values(ids.velocity_confidence)[i] =
        empty ? 0.9f : near(options.min_velocity_confidence);
    layers.Values(ids.velocity_x_mps)[i] = empty ? 3.0f : near(options.min_speed_mps);
    layers.Values(ids.velocity_y_mps)[i] = rng() % 2 == 0 ? 0.0f : near(0.1);
  }
  const std::vector<std::uint8_t> mask = DynamicCellMask(layers, ids, options);
  std::size_t dynamic = 0;
  for (std::size_t i = 0; i < cells; ++i) {
    const auto o = static_cast<double>(layers.Values(ids.occupancy)[i]);
    const auto c = static_cast<double>(layers.Values(ids.velocity_confidence)[i]);
    const auto vx = static_cast<double>(layers.Values(ids.velocity_x_mps)[i]);
    const auto vy = static_cast<double>(layers.Values(ids.velocity_y_mps)[i]);
    const bool expected = o > options.min_occupancy && c >= options.min_velocity_confidence &&
                          vx * vx + vy * vy > options.min_speed_mps * options.min_speed_mps;
    ASSERT_EQ(mask[i] != 0, expected) << "cell " << i << ", seed " << seed;
    dynamic += expected ? 1 : 0;
  }
  EXPECT_GT(dynamic, cells / 1000);  // the test sees dynamic cells, not only empty ones
}

TEST(GridObjectsTest, ValidateNamesTheField) {
  GridObjectOptions options;
  EXPECT_NO_THROW(options.Validate());
  options.min_link = 1.5;
  try {
    options.Validate("test");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "grid.objects.min_link");
  }
  options = {};
  options.min_cells = 0;
  EXPECT_THROW(options.Validate(), InputError);
  options = {};
  options.min_speed_mps = std::nan("");
  EXPECT_THROW(options.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::grid
