#include "lookout/grid/inverse_sensor_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lookout/core/breakpoint_distance.h"
#include "lookout/core/dead_reckoning.h"
#include "lookout/core/random.h"
#include "lookout/grid/testing/segment_in_cell.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

InverseSensorModelOptions Options() {
  InverseSensorModelOptions o;
  o.p_hit = 0.7;
  o.p_free = 0.3;
  o.p_free_no_return = 0.4;
  o.no_return_free_range_m = 8.0;
  return o;
}

LidarScan Scan(double angle_min_rad, double increment_rad, std::vector<float> ranges,
               double max_range_m = 150.0) {
  LidarScan scan;
  scan.stamp = 42;
  scan.angle_min_rad = angle_min_rad;
  scan.angle_increment_rad = increment_rad;
  scan.max_range_m = max_range_m;
  scan.ranges_m = std::move(ranges);
  return scan;
}

// Evidence strength, the order of the overlap rule: unknown < weak free < free < hit.
int Rank(float p, const InverseSensorModelOptions& o) {
  if (p == static_cast<float>(o.p_hit)) return 3;
  if (p == static_cast<float>(o.p_free)) return 2;
  if (p == static_cast<float>(o.p_free_no_return)) return 1;
  EXPECT_EQ(p, kUnknownProbability);
  return 0;
}

struct Beam {
  Vector2d start_m;
  Vector2d end_m;
  bool hit = false;
};

// The beam segments as the model defines them, written out independently.
std::vector<Beam> Beams(const LidarScan& scan, const Pose2& pose,
                        const InverseSensorModelOptions& o, double cell_size_m) {
  std::vector<Beam> beams;
  const std::size_t n = scan.ranges_m.size();
  auto range = [&](std::size_t i) { return static_cast<double>(scan.ranges_m[i]); };
  auto returned = [&](std::size_t i) { return range(i) > 0.0 && range(i) < scan.max_range_m; };
  for (std::size_t i = 0; i < n; ++i) {
    const double r = range(i);
    if (std::isnan(r) || r <= 0.0) continue;
    const bool hit = r < scan.max_range_m;
    double length = hit ? r : std::min(o.no_return_free_range_m, scan.max_range_m);
    // A dropout between two neighbours that returned from within surface_gap_m of each other
    // (laterally and in range): free space ends a cell short of the nearer neighbour's impact.
    if (!hit && i > 0 && i + 1 < n && returned(i - 1) && returned(i + 1)) {
      const double near = std::min(range(i - 1), range(i + 1));
      const double far = std::max(range(i - 1), range(i + 1));
      if (far * 2.0 * std::abs(scan.angle_increment_rad) < o.surface_gap_m &&
          far - near < o.surface_gap_m) {
        length = std::min(length, near - cell_size_m);
      }
    }
    if (length <= 0.0) continue;
    const double angle = pose.yaw + scan.BeamAngle(i);
    beams.push_back({pose.translation,
                     pose.translation + length * Vector2d(std::cos(angle), std::sin(angle)), hit});
  }
  return beams;
}

// The surface segments: the impacts of consecutive returns at most surface_gap_m apart, and
// either within Borges-Aldon's distance at the nearer range (written out here) or in line with
// the previous or the next impact (the angle between the two steps at most
// surface_max_turn_rad).
std::vector<Beam> Surfaces(const LidarScan& scan, const Pose2& pose,
                           const InverseSensorModelOptions& o) {
  std::vector<Beam> surfaces;
  const std::size_t n = scan.ranges_m.size();
  auto range = [&](std::size_t i) { return static_cast<double>(scan.ranges_m[i]); };
  auto impact = [&](std::size_t i) -> std::optional<Vector2d> {
    const double r = range(i);
    if (!(r > 0.0 && r < scan.max_range_m)) return std::nullopt;
    const double angle = pose.yaw + scan.BeamAngle(i);
    return pose.translation + r * Vector2d(std::cos(angle), std::sin(angle));
  };
  auto turn_rad = [](const Vector2d& u, const Vector2d& v) {
    return std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0));
  };
  auto in_line = [&](const std::optional<Vector2d>& p, const std::optional<Vector2d>& q,
                     const Vector2d& step) {
    return p && q && (*q - *p).norm() > 0.0 && (*q - *p).norm() <= o.surface_gap_m &&
           turn_rad(*q - *p, step) <= o.surface_max_turn_rad;
  };
  const double dphi = std::abs(scan.angle_increment_rad);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const auto a = impact(i), b = impact(i + 1);
    if (!a || !b || (*b - *a).norm() > o.surface_gap_m) continue;
    const double nearer = std::min(range(i), range(i + 1));
    const double breakpoint = nearer * std::sin(dphi) / std::sin(o.surface_incidence_rad - dphi) +
                              o.surface_range_noise_m;
    const bool surface = (*b - *a).norm() <= breakpoint ||
                         (i > 0 && in_line(impact(i - 1), a, *b - *a)) ||
                         (i + 2 < n && in_line(b, impact(i + 2), *b - *a));
    if (surface) surfaces.push_back({*a, *b, true});
  }
  return surfaces;
}

// The slow literal reference: march along each beam in 1 mm steps, classify the cell under
// each sample as crossed, then mark the impact cell; combine beams by the strength rule.
std::vector<int> ReferenceRanks(const LidarScan& scan, const Pose2& pose,
                                const ScrollingGridGeometry& g,
                                const InverseSensorModelOptions& o) {
  constexpr double kStepM = 1e-3;
  std::vector<int> rank(g.CellCount(), 0);
  for (const Beam& b : Beams(scan, pose, o, g.cell_size_m())) {
    const double length = (b.end_m - b.start_m).norm();
    const Vector2d dir = (b.end_m - b.start_m) / length;
    const int free_rank = b.hit ? 2 : 1;
    for (long k = 0;; ++k) {
      const double t = static_cast<double>(k) * kStepM;
      if (t >= length) break;
      const auto i = g.StorageIndexAt(b.start_m + t * dir);
      if (i && rank[*i] < free_rank) rank[*i] = free_rank;
    }
    if (b.hit) {
      if (const auto i = g.StorageIndexAt(b.end_m)) rank[*i] = 3;
    }
  }
  for (const Beam& surface : Surfaces(scan, pose, o)) {
    const double length = (surface.end_m - surface.start_m).norm();
    for (long k = 0;; ++k) {
      const double t = std::min(length, static_cast<double>(k) * kStepM);
      const Vector2d p =
          length > 0.0 ? Vector2d(surface.start_m + t / length * (surface.end_m - surface.start_m))
                       : surface.start_m;
      if (const auto i = g.StorageIndexAt(p)) rank[*i] = 3;
      if (t >= length) break;
    }
  }
  return rank;
}

using testing::LengthInCell;

void ExpectTouchedIsTheSupport(const MeasurementGrid& m) {
  std::set<std::size_t> support;
  for (std::size_t i = 0; i < m.p_occupied.size(); ++i) {
    if (m.p_occupied[i] != kUnknownProbability) support.insert(i);
  }
  const std::set<std::size_t> touched(m.touched.begin(), m.touched.end());
  EXPECT_EQ(touched.size(), m.touched.size()) << "duplicates in touched";
  EXPECT_EQ(touched, support);
}

// ---------------------------------------------------------------------------------------------
// Property test against the literal reference on random scans. The fast traversal visits every
// cell a beam crosses; the 1 mm march can miss a cell that a beam only clips by less than a
// step (or touches at a corner). So: wherever they differ, the fast result must hold the
// stronger evidence and some beam must clip that cell by less than 2 mm.
TEST(InverseSensorModelTest, AgreesWithTheMarchingReferenceOnRandomScans) {
  const InverseSensorModelOptions o = Options();
  int grazing_total = 0;
  std::size_t evidence_total = 0;
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    Rng rng(DeriveSeed(20260611, "ism", seed));
    const CellIndex origin{static_cast<int>(rng.UniformIndex(2001)) - 1000,
                           static_cast<int>(rng.UniformIndex(2001)) - 1000};
    const ScrollingGridGeometry g(0.15, 80, 64, origin);
    const Vector2d lower = g.WindowLowerLeftM();
    // The sensor inside the window, or (every fifth seed) up to half a window outside it.
    const double margin = seed % 5 == 0 ? 0.5 : 0.0;
    const Pose2 pose{lower.x() + rng.Uniform(-margin, 1.0 + margin) * 12.0,
                     lower.y() + rng.Uniform(-margin, 1.0 + margin) * 9.6, rng.Uniform(-kPi, kPi)};
    std::vector<float> ranges;
    for (int i = 0; i < 120; ++i) {
      const double u = rng.Uniform();
      ranges.push_back(u < 0.05   ? kNan
                       : u < 0.12 ? kInf
                       : u < 0.17 ? static_cast<float>(rng.Uniform(15.0, 30.0))  // beyond max
                                  : static_cast<float>(rng.Uniform(0.02, 14.0)));
    }
    const double first_angle_rad = rng.Uniform(-kPi, kPi);
    const LidarScan scan = Scan(first_angle_rad, DegToRad(rng.Uniform(0.2, 3.0)),
                                std::move(ranges), /*max_range_m=*/15.0);
    const MeasurementGrid fast = ComputeInverseSensorModel(scan, pose, g, o);
    const std::vector<int> reference = ReferenceRanks(scan, pose, g, o);
    std::vector<Beam> beams = Beams(scan, pose, o, g.cell_size_m());
    for (const Beam& surface : Surfaces(scan, pose, o)) beams.push_back(surface);
    for (std::size_t i = 0; i < g.CellCount(); ++i) {
      const int f = Rank(fast.p_occupied[i], o);
      if (f == reference[i]) continue;
      ASSERT_GT(f, reference[i]) << "the fast model lost evidence; seed " << seed << " cell " << i;
      bool grazed = false;
      for (const Beam& b : beams) {
        const auto length = LengthInCell(g, g.GlobalFromStorage(i), b.start_m, b.end_m);
        grazed = grazed || (length.has_value() && *length < 2e-3);
      }
      ASSERT_TRUE(grazed) << "seed " << seed << " cell " << i << ": fast " << f << ", reference "
                          << reference[i];
      ++grazing_total;
    }
    ExpectTouchedIsTheSupport(fast);
    evidence_total += fast.touched.size();
  }
  // Grazes are rare: a sub-millimetre clip of a cell that no other beam crosses. With these
  // seeds, 34 of the 39,881 cells with evidence (0.09 %).
  EXPECT_LT(static_cast<double>(grazing_total), 0.005 * static_cast<double>(evidence_total));
}

// ---------------------------------------------------------------------------------------------
// Analytic worlds.

// A wall along x = 10 m in front of a sensor at the origin heading +x, beams over +-30 deg.
TEST(InverseSensorModelTest, WallAtKnownDistance) {
  const InverseSensorModelOptions o = Options();
  const ScrollingGridGeometry g(GridOptions{});  // 60 m x 60 m around the origin
  const double half_fov = DegToRad(30.0);
  const double increment = DegToRad(0.25);
  std::vector<float> ranges;
  for (int i = 0; i <= 240; ++i) {
    ranges.push_back(static_cast<float>(10.0 / std::cos(-half_fov + i * increment)));
  }
  const LidarScan scan = Scan(-half_fov, increment, ranges);
  const Pose2 pose(0.0, 0.0, 0.0);
  const MeasurementGrid m = ComputeInverseSensorModel(scan, pose, g, o);
  EXPECT_EQ(m.stats.hit_beams, 241);
  EXPECT_EQ(m.stamp, 42);

  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double a = scan.BeamAngle(i);
    const auto r = static_cast<double>(scan.ranges_m[i]);
    EXPECT_EQ(m.p_occupied[*g.StorageIndexAt(r * Vector2d(std::cos(a), std::sin(a)))], 0.7f);
  }
  const double cell_radius = 0.15 / std::sqrt(2.0);
  int free_cells = 0;
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    const double bearing = std::atan2(c.y(), c.x());
    // Angular half-width of the cell seen from the sensor: inside or outside the fan for sure.
    const double spread = std::asin(std::min(1.0, cell_radius / c.norm()));
    const float p = m.p_occupied[i];
    if (std::abs(bearing) > half_fov + spread) {
      ASSERT_EQ(p, 0.5f) << "outside the field of view: " << c.transpose();
    } else if (std::abs(bearing) < half_fov - spread && c.x() < 10.0 - 0.15) {
      ASSERT_EQ(p, 0.3f) << "before the wall: " << c.transpose();
      ++free_cells;
    } else if (c.x() > 10.0 + 0.15) {
      ASSERT_EQ(p, 0.5f) << "behind the wall: " << c.transpose();
    }
  }
  EXPECT_GT(free_cells, 2000);  // the wedge's area over the cell area: about 2560
  ExpectTouchedIsTheSupport(m);
}

// A wall parallel to the sensor's heading, `wall_m` to its right, seen from the sensor at the
// origin between `from_deg` and `to_deg` off the axis (from > to > 0), one beam every 0.25
// degrees.
LidarScan WallScan(double wall_m, double from_deg, double to_deg) {
  const double increment = DegToRad(0.25);
  const double first = -DegToRad(from_deg);
  const int beams = static_cast<int>(std::lround((from_deg - to_deg) / 0.25));
  std::vector<float> ranges;
  for (int i = 0; i <= beams; ++i) {
    ranges.push_back(static_cast<float>(wall_m / std::sin(-(first + i * increment))));
  }
  return Scan(first, increment, ranges);
}

// The wall's cells between its first and last impact, sampled every 1 cm: how many samples
// fall in hit cells, of how many.
std::pair<int, int> HitsAlongWall(const MeasurementGrid& m, const ScrollingGridGeometry& g,
                                  double wall_m, double from_deg, double to_deg) {
  int hits = 0, samples = 0;
  for (double x = wall_m / std::tan(DegToRad(from_deg)); x <= wall_m / std::tan(DegToRad(to_deg));
       x += 0.01) {
    ++samples;
    hits += m.p_occupied[*g.StorageIndexAt(Vector2d(x, -wall_m))] == 0.7f ? 1 : 0;
  }
  return {hits, samples};
}

// The wall 4.275 m to the right (mid-cell), seen from 10 to 80 degrees off the axis: beyond a
// few metres its impacts are farther apart than a cell, and as the sensor moves they slide
// along it. Joined as one surface, every cell the wall passes through between the first and the
// last impact is a hit; without the segments, some are not.
TEST(InverseSensorModelTest, ConsecutiveReturnsFromOneSurfaceAreJoined) {
  const ScrollingGridGeometry g(GridOptions{});
  constexpr double kWallM = 4.275;
  const LidarScan scan = WallScan(kWallM, 80.0, 10.0);
  auto hits_along_wall = [&](double surface_gap_m) {
    InverseSensorModelOptions o = Options();
    o.surface_gap_m = surface_gap_m;
    const MeasurementGrid m = ComputeInverseSensorModel(scan, Pose2(0.0, 0.0, 0.0), g, o);
    ExpectTouchedIsTheSupport(m);
    return HitsAlongWall(m, g, kWallM, 80.0, 10.0);  // x = 0.75 .. 24.2 m
  };
  const auto [joined, samples] = hits_along_wall(1.0);
  EXPECT_EQ(joined, samples);
  const auto [beams_only, samples_too] = hits_along_wall(0.0);
  EXPECT_LT(beams_only, samples_too * 9 / 10);
}

// The wall 1 m to the right seen 4 to 6.5 degrees off the axis, more obliquely than the
// breakpoint distance's 10 degrees: its impacts are 0.35-0.9 m apart, beyond that distance,
// but each in line with the next, so it is still one surface.
TEST(InverseSensorModelTest, AWallInLineBeyondTheBreakpointDistanceIsJoined) {
  const ScrollingGridGeometry g(GridOptions{});
  constexpr double kWallM = 1.025;
  const LidarScan scan = WallScan(kWallM, 6.5, 4.0);
  const InverseSensorModelOptions o = Options();
  // Every step lies beyond the breakpoint distance at its nearer impact.
  for (std::size_t i = 0; i + 1 < scan.ranges_m.size(); ++i) {
    const double a = scan.BeamAngle(i), b = scan.BeamAngle(i + 1);
    const auto ra = static_cast<double>(scan.ranges_m[i]);
    const auto rb = static_cast<double>(scan.ranges_m[i + 1]);
    const Vector2d p = ra * Vector2d(std::cos(a), std::sin(a));
    const Vector2d q = rb * Vector2d(std::cos(b), std::sin(b));
    ASSERT_GT((q - p).norm(), BreakpointDistance(std::min(ra, rb), scan.angle_increment_rad,
                                                 o.surface_incidence_rad, o.surface_range_noise_m));
  }
  const MeasurementGrid m = ComputeInverseSensorModel(scan, Pose2(0.0, 0.0, 0.0), g, o);
  ExpectTouchedIsTheSupport(m);
  const auto [hits, samples] = HitsAlongWall(m, g, kWallM, 6.5, 4.0);
  EXPECT_EQ(hits, samples);
}

// A give-way sign 0.7 m in front of a walker at 18 m (occluded-pedestrian's first seconds):
// the last beam on the sign and the first on the walker land 0.7 m apart along the beams,
// within surface_gap_m but beyond the breakpoint distance, and neither face goes on in line
// with the jump. The cells between are not hits: the beam that reached the walker crossed
// them, free.
TEST(InverseSensorModelTest, ADepthJumpBetweenTwoObjectsIsNoSurface) {
  const ScrollingGridGeometry g(GridOptions{});
  const double increment = DegToRad(0.25);
  std::vector<float> ranges(21, kInf);  // -2.5 .. +2.5 degrees
  for (int i = 8; i <= 10; ++i) ranges[static_cast<std::size_t>(i)] = 18.0f;   // the sign
  for (int i = 11; i <= 16; ++i) ranges[static_cast<std::size_t>(i)] = 18.7f;  // the walker
  const LidarScan scan = Scan(DegToRad(-2.5), increment, ranges);
  const InverseSensorModelOptions o = Options();
  const MeasurementGrid m = ComputeInverseSensorModel(scan, Pose2(0.0, 0.0, 0.0), g, o);
  ExpectTouchedIsTheSupport(m);
  // Along beam 11, from 0.2 m past the sign's depth to 0.2 m short of the walker's face (the
  // cells of neither).
  const double angle = DegToRad(-2.5) + 11.0 * increment;
  const Vector2d dir(std::cos(angle), std::sin(angle));
  int hits = 0;
  for (double r = 18.2; r <= 18.5; r += 0.01) {
    hits += m.p_occupied[*g.StorageIndexAt(r * dir)] == 0.7f ? 1 : 0;
  }
  EXPECT_EQ(hits, 0);
  // Each body's own returns, 8 cm apart, are still one surface: the walker's face is hit
  // between its first and last beams.
  const double a11 = angle, a16 = DegToRad(-2.5) + 16.0 * increment;
  for (double t = 0.0; t <= 1.0; t += 0.05) {
    const Vector2d p = ((1.0 - t) * Vector2d(std::cos(a11), std::sin(a11)) +
                        t * Vector2d(std::cos(a16), std::sin(a16))) *
                       18.7;
    EXPECT_EQ(m.p_occupied[*g.StorageIndexAt(p)], 0.7f) << "t = " << t;
  }
}

// Two poles 2 m apart at the same range are two objects, not one surface: the cells between
// them stay as the beams passing between them left them (free).
TEST(InverseSensorModelTest, ReturnsFartherApartThanTheGapAreNotJoined) {
  const ScrollingGridGeometry g(GridOptions{});
  const double increment = DegToRad(0.25);
  std::vector<float> ranges(81, kInf);  // -10 .. +10 degrees
  for (int i = 0; i < 4; ++i) {
    ranges[static_cast<std::size_t>(i + 10)] = 10.0f;   // about -7.5 degrees: y = -1.3 m
    ranges[static_cast<std::size_t>(i + 67)] = 10.0f;   // about +6.75 degrees: y = +1.2 m
  }
  const LidarScan scan = Scan(DegToRad(-10.0), increment, ranges);
  const MeasurementGrid m = ComputeInverseSensorModel(scan, Pose2(0.0, 0.0, 0.0), g, Options());
  EXPECT_EQ(m.stats.surface_segments, 6);  // three within each pole
  for (double y = -0.5; y <= 0.5; y += 0.05) {
    EXPECT_NE(m.p_occupied[*g.StorageIndexAt(Vector2d(9.95, y))], 0.7f) << "y = " << y;
  }
}

// The same wall in the grid frame, scanned from a rotated, translated sensor: the model must
// place everything in the grid frame.
TEST(InverseSensorModelTest, SensorPoseIsRespected) {
  const InverseSensorModelOptions o = Options();
  const ScrollingGridGeometry g(GridOptions{}, Vector2d(3.0, -2.0));
  // The wall: the line through (10, 4) with direction (-1, 2) / sqrt(5), in the grid frame.
  const Vector2d wall_point(10.0, 4.0);
  const Vector2d wall_dir = Vector2d(-1.0, 2.0).normalized();
  const Vector2d wall_normal(-wall_dir.y(), wall_dir.x());
  const Pose2 pose(3.3, -2.1, 0.7);
  const double increment = DegToRad(0.25);
  const double angle_min = DegToRad(-40.0);
  std::vector<float> ranges;
  for (int i = 0; i <= 320; ++i) {
    const double a = pose.yaw + angle_min + i * increment;
    const Vector2d d(std::cos(a), std::sin(a));
    // Ray-line intersection: pose + r d on the wall line.
    const double denominator = d.dot(wall_normal);
    const double r = (wall_point - pose.translation).dot(wall_normal) / denominator;
    ranges.push_back(r > 0.0 && r < 40.0 ? static_cast<float>(r) : kInf);
  }
  const LidarScan scan = Scan(angle_min, increment, ranges);
  InverseSensorModelOptions no_weak = o;
  no_weak.no_return_free_range_m = 0.0;
  const MeasurementGrid m = ComputeInverseSensorModel(scan, pose, g, no_weak);
  ASSERT_GT(m.stats.hit_beams, 200);

  const double sensor_side = (pose.translation - wall_point).dot(wall_normal) > 0.0 ? 1.0 : -1.0;
  const double diagonal = 0.15 * std::sqrt(2.0);
  int hits = 0;
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    const double signed_distance = (c - wall_point).dot(wall_normal);
    const float p = m.p_occupied[i];
    if (p == 0.7f) {
      ++hits;
      ASSERT_LT(std::abs(signed_distance), diagonal) << "a hit off the wall: " << c.transpose();
    } else if (p == 0.3f) {
      ASSERT_GT(signed_distance * sensor_side, -diagonal) << "free behind the wall";
    }
    if (signed_distance * sensor_side < -diagonal) {
      ASSERT_EQ(p, 0.5f) << "behind the wall: " << c.transpose();
    }
  }
  EXPECT_GT(hits, 50);  // about 100 distinct wall cells from some 280 returns
  // The beam along the sensor's own x axis (index 160) hits where the pose says.
  const double a = pose.yaw;
  const Vector2d impact =
      pose.translation + static_cast<double>(ranges[160]) * Vector2d(std::cos(a), std::sin(a));
  EXPECT_EQ(m.p_occupied[*g.StorageIndexAt(impact)], 0.7f);
  EXPECT_EQ(m.p_occupied[*g.StorageIndexAt(pose.translation)], 0.3f);
}

TEST(InverseSensorModelTest, SpecialRangesFollowRep117) {
  const InverseSensorModelOptions o = Options();  // no-return: 0.4 up to 8 m
  const ScrollingGridGeometry g(GridOptions{});
  // Beams along +x, +y, -x, -y, and two more: NaN, +inf, beyond max, 5 m, -1, 0.
  const LidarScan scan =
      Scan(0.0, kPi / 2.0, {kNan, kInf, 200.0f, 5.0f, -1.0f, 0.0f}, /*max_range_m=*/150.0);
  const MeasurementGrid m = ComputeInverseSensorModel(scan, Pose2(0.07, 0.07, 0.0), g, o);
  EXPECT_EQ(m.stats.beams, 6);
  EXPECT_EQ(m.stats.nan_beams, 1);
  EXPECT_EQ(m.stats.no_return_beams, 1);
  EXPECT_EQ(m.stats.beyond_max_beams, 1);
  EXPECT_EQ(m.stats.hit_beams, 1);
  EXPECT_EQ(m.stats.non_positive_beams, 2);
  auto at = [&](double x, double y) { return m.p_occupied[*g.StorageIndexAt({x, y})]; };
  EXPECT_EQ(at(3.0, 0.07), 0.5f);   // NaN along +x: nothing
  EXPECT_EQ(at(0.07, 7.0), 0.4f);   // +inf along +y: weak free up to 8 m
  EXPECT_EQ(at(0.07, 9.0), 0.5f);   // and not beyond
  EXPECT_EQ(at(-7.0, 0.07), 0.4f);  // beyond max along -x: the same as no return
  EXPECT_EQ(at(-9.0, 0.07), 0.5f);
  EXPECT_EQ(at(0.07, -4.0), 0.3f);   // a 5 m return along -y
  EXPECT_EQ(at(0.07, -4.93), 0.7f);  // the impact cell
  EXPECT_EQ(at(0.07, -6.0), 0.5f);
  EXPECT_EQ(at(0.07, 0.07), 0.3f);  // the sensor's cell: crossed by the return, the strongest

  // A scan without a usable max range has no range limit; no-return range 0 ignores +inf.
  InverseSensorModelOptions ignore = o;
  ignore.no_return_free_range_m = 0.0;
  const MeasurementGrid unlimited =
      ComputeInverseSensorModel(Scan(0.0, 0.0, {200.0f, kInf}, 0.0), Pose2(), g, ignore);
  EXPECT_EQ(unlimited.stats.hit_beams, 1);
  EXPECT_EQ(unlimited.stats.no_return_beams, 1);
  EXPECT_EQ(unlimited.p_occupied[*g.StorageIndexAt({29.0, 0.01})], 0.3f);

  const MeasurementGrid lost =
      ComputeInverseSensorModel(Scan(0.0, 0.1, {5.0f, 6.0f}), Pose2(std::nan(""), 0.0, 0.0), g, o);
  EXPECT_TRUE(lost.touched.empty());
  EXPECT_EQ(lost.stats.beams, 2);
}

TEST(InverseSensorModelTest, ADropoutInFrontOfAWallDoesNotSeeThroughIt) {
  InverseSensorModelOptions o = Options();
  o.no_return_free_range_m = 30.0;
  const ScrollingGridGeometry g(GridOptions{});
  const double increment = DegToRad(0.25);
  // A wall at x = 10 straight ahead; beam 20 (along +x) drops out.
  std::vector<float> ranges;
  for (int i = 0; i <= 40; ++i) {
    ranges.push_back(static_cast<float>(10.0 / std::cos((i - 20) * increment)));
  }
  ranges[20] = kInf;
  const MeasurementGrid m = ComputeInverseSensorModel(Scan(-20 * increment, increment, ranges),
                                                      Pose2(0.01, 0.01, 0.0), g, o);
  auto at = [&](double x) { return m.p_occupied[*g.StorageIndexAt({x, 0.01})]; };
  EXPECT_EQ(at(5.0), 0.3f);    // its neighbours' free space covers it
  EXPECT_EQ(at(12.0), 0.5f);   // behind the wall: the dropout says nothing there
  EXPECT_EQ(at(20.0), 0.5f);

  // A no-return beam beside open space (one neighbour without return) keeps its weak free space.
  ranges[21] = kInf;
  const MeasurementGrid open = ComputeInverseSensorModel(Scan(-20 * increment, increment, ranges),
                                                         Pose2(0.01, 0.01, 0.0), g, o);
  EXPECT_EQ(open.p_occupied[*g.StorageIndexAt({20.0, 0.01})], 0.4f);
}

TEST(InverseSensorModelTest, HitsWinOverFreeWhateverTheBeamOrder) {
  const InverseSensorModelOptions o = Options();
  const ScrollingGridGeometry g(GridOptions{});
  const Pose2 pose(0.01, 0.01, 0.0);
  // Several beams along one line: a short hit, a long hit through it, a no-return beam.
  const std::vector<float> ranges = {5.0f, 10.0f, kInf, 2.0f};
  std::vector<float> reversed(ranges.rbegin(), ranges.rend());
  const MeasurementGrid a = ComputeInverseSensorModel(Scan(0.0, 0.0, ranges), pose, g, o);
  const MeasurementGrid b = ComputeInverseSensorModel(Scan(0.0, 0.0, reversed), pose, g, o);
  EXPECT_EQ(a.p_occupied, b.p_occupied);
  auto at = [&](double x) { return a.p_occupied[*g.StorageIndexAt({x, 0.01})]; };
  EXPECT_EQ(at(2.01), 0.7f);  // hit, although two beams cross it further
  EXPECT_EQ(at(5.01), 0.7f);
  EXPECT_EQ(at(10.01), 0.7f);
  EXPECT_EQ(at(7.0), 0.3f);   // a return's free wins over the no-return's weak free
  EXPECT_EQ(at(10.5), 0.5f);  // behind the last hit: the no-return stops at 8 m
  ExpectTouchedIsTheSupport(a);
}

TEST(InverseSensorModelTest, SensorPoseComesFromTheEgoPoseSource) {
  DeadReckoningOptions o;
  o.initial_pose = Pose2(1.0, 2.0, kPi / 2.0);
  o.max_extrapolation_s = 2.0;
  DeadReckoning odometry(o);
  LidarScan scan = Scan(0.0, 0.0, {5.0f});
  scan.stamp = 1'000'000'000;
  scan.mount = Pose2(2.2, 0.0, 0.0);
  EXPECT_FALSE(SensorPoseAt(odometry, scan).has_value());  // no odometry yet
  odometry.Add(EgoOdometry{0, 3.0, 0.0});                  // 3 m/s north for 1 s
  const std::optional<Pose2> sensor = SensorPoseAt(odometry, scan);
  ASSERT_TRUE(sensor.has_value());
  EXPECT_NEAR(sensor->x(), 1.0, 1e-12);
  EXPECT_NEAR(sensor->y(), 2.0 + 3.0 + 2.2, 1e-12);  // the mount is 2.2 m ahead, facing north
  EXPECT_NEAR(sensor->yaw, kPi / 2.0, 1e-12);
}

TEST(InverseSensorModelTest, ReusingTheOutputGivesTheSameResult) {
  const InverseSensorModelOptions o = Options();
  const std::uint64_t seed = 9001;
  Rng rng(seed);
  ScrollingGridGeometry g(GridOptions{});
  MeasurementGrid reused;
  for (int k = 0; k < 5; ++k) {
    std::vector<float> ranges;
    for (int i = 0; i < 641; ++i) ranges.push_back(static_cast<float>(rng.Uniform(0.5, 40.0)));
    const LidarScan scan = Scan(DegToRad(-80.0), DegToRad(0.25), ranges);
    const Pose2 pose{rng.Uniform(-3.0, 3.0), rng.Uniform(-3.0, 3.0), rng.Uniform(-kPi, kPi)};
    g.Recenter(pose.translation);
    ComputeInverseSensorModel(scan, pose, g, o, reused);
    const MeasurementGrid fresh = ComputeInverseSensorModel(scan, pose, g, o);
    ASSERT_EQ(reused.p_occupied, fresh.p_occupied) << "seed " << seed << " scan " << k;
    ASSERT_EQ(reused.touched, fresh.touched) << "seed " << seed << " scan " << k;
    ASSERT_EQ(reused.geometry.window_origin(), g.window_origin());
  }
}

}  // namespace
}  // namespace lookout::grid
