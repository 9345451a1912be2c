#include "lookout/fusion/lidar_point_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "lookout/core/pose2.h"
#include "lookout/stereo/oriented_box.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

constexpr unsigned kSeed = 20261202;

// Each end uniform over a beam spacing past its return and, independently, over its cell:
// the middle's variance by Monte Carlo against the closed form.
TEST(LidarPointModelTest, EndResolutionMatchesMonteCarlo) {
  std::mt19937_64 rng(kSeed);
  const double spacing = 0.12, cell = 0.15;
  std::uniform_real_distribution<double> beam(0.0, spacing), in_cell(-0.5 * cell, 0.5 * cell);
  const int n = 200'000;
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < n; ++k) {
    // The start end moves outward to -x, the far end to +x.
    const double start = -beam(rng) + in_cell(rng);
    const double end = beam(rng) + in_cell(rng);
    const double middle = 0.5 * (start + end);
    sum += middle;
    sum2 += middle * middle;
  }
  const double mean = sum / n;
  const double variance = sum2 / n - mean * mean;
  EXPECT_NEAR(variance, EndResolutionVariance(spacing, cell), 0.02 * variance) << "seed " << kSeed;
  EXPECT_DOUBLE_EQ(EndResolutionVariance(0.0, 0.0), 0.0);
}

// A window of `visible` placed uniformly on a side: the offset of its middle from the side's.
TEST(LidarPointModelTest, HiddenExtentMatchesMonteCarlo) {
  std::mt19937_64 rng(kSeed);
  const double side = 4.5, visible = 1.3;
  std::uniform_real_distribution<double> start(0.0, side - visible);
  const int n = 200'000;
  double sum2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double offset = start(rng) + 0.5 * visible - 0.5 * side;
    sum2 += offset * offset;
  }
  EXPECT_NEAR(sum2 / n, HiddenExtentVariance(visible, side), 0.02 * sum2 / n) << "seed " << kSeed;
  EXPECT_DOUBLE_EQ(HiddenExtentVariance(4.5, 4.5), 0.0);
  EXPECT_DOUBLE_EQ(HiddenExtentVariance(5.0, 4.5), 0.0);  // more seen than the side: nothing hid
}

// A car seen over less than its width from a uniformly random direction: which side faces the
// viewer is stereo::FrontSegmentFacing's (the truth's and the camera's rule), the window on it
// uniform. The mixture's chance of the length side is checked through the variance.
TEST(LidarPointModelTest, BoxHiddenExtentFollowsTheFacingSideRule) {
  std::mt19937_64 rng(kSeed);
  const double length = 4.5, width = 1.8, visible = 1.0;
  const stereo::OrientedBox box{Vector2d::Zero(), 0.0, length, width};
  std::uniform_real_distribution<double> direction(-kPi, kPi), unit(0.0, 1.0);
  const int n = 200'000;
  double sum2 = 0.0;
  int length_sides = 0;
  for (int k = 0; k < n; ++k) {
    const double a = direction(rng);
    const auto front = stereo::FrontSegmentFacing(box, 30.0 * Vector2d(std::cos(a), std::sin(a)));
    ASSERT_TRUE(front.has_value());
    const double side = (front->end_m - front->start_m).norm();
    if (side > 0.5 * (length + width)) ++length_sides;
    const double offset = unit(rng) * (side - visible) + 0.5 * visible - 0.5 * side;
    sum2 += offset * offset;
  }
  const double p_length = 1.0 - (2.0 / kPi) * std::atan(width / length);
  EXPECT_NEAR(static_cast<double>(length_sides) / n, p_length, 0.005) << "seed " << kSeed;
  const double expected = BoxHiddenExtentVariance(visible, length, width);
  EXPECT_NEAR(sum2 / n, expected, 0.02 * expected) << "seed " << kSeed;
  // Seen over more than its width, it can only be the length side.
  EXPECT_DOUBLE_EQ(BoxHiddenExtentVariance(2.5, length, width), HiddenExtentVariance(2.5, length));
}

// A pedestrian, a circle of radius r, 12 m from the lidar, seen by beams 0.05 deg apart (far
// enough and fine enough for the model's "seen from afar"): the grid's point is the middle of
// its returns across the ray at their mean depth (what a straight-line fit of the arc gives),
// the segmentation's that moved (1 - pi/4) r towards the lidar (half the returns' extent
// across the ray for r); the true point is the middle of the facing side of the 2r square
// along a uniformly random heading (eval::TrueFrontPoints). Their second moments in ray axes
// against the model's, for each depth.
TEST(LidarPointModelTest, RoundBodyMatchesBeamsOnACircle) {
  const double r = 0.3;
  const Vector2d lidar(2.2, 0.0);
  const Vector2d centre = lidar + 12.0 * Vector2d(std::cos(0.4), std::sin(0.4));
  const Vector2d to_centre = centre - lidar;
  const double distance = to_centre.norm();
  const Vector2d along = to_centre / distance;
  const Vector2d across(-along.y(), along.x());
  // The returns: beams through the circle, each at its near intersection.
  const double dphi = 0.05 * kPi / 180.0;
  const double half_angle = std::asin(r / distance);
  Vector2d sum = Vector2d::Zero();
  int hits = 0;
  double first_across = 0.0, last_across = 0.0;
  for (double b = -half_angle; b <= half_angle; b += dphi) {
    const Vector2d ray = std::cos(b) * along + std::sin(b) * across;
    const double t_mid = ray.dot(to_centre);
    const double h2 = r * r - (distance * distance - t_mid * t_mid);
    if (h2 < 0.0) continue;
    const Vector2d hit = lidar + (t_mid - std::sqrt(h2)) * ray;
    if (hits == 0) first_across = (hit - centre).dot(across);
    last_across = (hit - centre).dot(across);
    sum += hit;
    ++hits;
  }
  ASSERT_GT(hits, 50);  // 57 beams over the 0.6 m body
  const Vector2d mean = sum / hits;
  const Vector2d grid_point =
      centre + (mean - centre).dot(along) * along + 0.5 * (first_across + last_across) * across;
  const double seen_radius = 0.5 * std::abs(last_across - first_across);
  const Vector2d segmentation_point = grid_point - (1.0 - kPi / 4.0) * seen_radius * along;

  for (const auto& [lidar_point, depth] :
       {std::pair{grid_point, kGridRoundBodyDepth},
        std::pair{segmentation_point, kSegmentationRoundBodyDepth}}) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> heading(-kPi, kPi);
    const int n = 200'000;
    double s_along = 0.0, s_across = 0.0;
    for (int k = 0; k < n; ++k) {
      const stereo::OrientedBox square{centre, heading(rng), 2.0 * r, 2.0 * r};
      const auto front = stereo::FrontSegmentFacing(square, lidar);
      ASSERT_TRUE(front.has_value());
      const Vector2d e = lidar_point - front->midpoint_m;
      s_along += e.dot(along) * e.dot(along);
      s_across += e.dot(across) * e.dot(across);
    }
    const Matrix2d model = RoundBodyCovariance(r, to_centre, depth);
    const double model_along = along.dot(model * along);
    const double model_across = across.dot(model * across);
    EXPECT_NEAR(s_along / n, model_along, 0.05 * model_along)
        << "depth " << depth << ", seed " << kSeed;
    EXPECT_NEAR(s_across / n, model_across, 0.02 * model_across)
        << "depth " << depth << ", seed " << kSeed;
    EXPECT_NEAR(along.dot(model * across), 0.0, 1e-12);
    // The figures the docs give: across, 0.13 m for r = 0.3 m.
    EXPECT_NEAR(std::sqrt(model_across), 0.128, 0.001);
  }
}

LidarObject SegmentObject(const Vector2d& point, const Vector2d& half_side) {
  LidarObject o;
  o.point_m = point;
  o.front_start_m = point - half_side;
  o.front_end_m = point + half_side;
  o.point_covariance = Vector2d(0.0004, 0.0009).asDiagonal();
  return o;
}

// Which terms reach which object: the round body any pedestrian's, the ends and the hidden
// extent a grid object's only (the segmentation bounds its ends from the scan), nothing an
// unknown segmentation object's, and no term that is switched off.
TEST(LidarPointModelTest, TermsByClassAndSource) {
  LidarPointModelOptions options;
  options.grid_extent = true;
  const Vector2d lidar(2.2, 0.0);
  const Vector2d point(22.2, 0.0);  // 20 m straight ahead: along the ray is x
  const LidarObject segment = SegmentObject(point, Vector2d(0.0, 0.25));
  EXPECT_EQ(LidarPointCovariance(segment, ObjectClass::kUnknown, lidar, options),
            segment.point_covariance);
  EXPECT_EQ(LidarPointCovariance(segment, ObjectClass::kCar, lidar, options),
            segment.point_covariance);
  const Matrix2d pedestrian =
      LidarPointCovariance(segment, ObjectClass::kPedestrian, lidar, options);
  EXPECT_LT((pedestrian - segment.point_covariance -
             RoundBodyCovariance(options.footprints.pedestrian_radius_m, point - lidar,
                                 kSegmentationRoundBodyDepth))
                .norm(),
            1e-15);
  LidarPointModelOptions off;
  off.round_body = false;
  EXPECT_EQ(LidarPointCovariance(segment, ObjectClass::kPedestrian, lidar, off),
            segment.point_covariance);

  // A grid car seen over 1 m across the ray at 20 m: along the side (y) the ends (beam spacing
  // 8.7 cm, cell 0.15 m) and the hidden part of a width or length side; across it, nothing.
  LidarObject grid = SegmentObject(point, Vector2d(0.0, 0.5));
  grid.cell_count = 12;
  const Matrix2d car = LidarPointCovariance(grid, ObjectClass::kCar, lidar, options);
  const double spacing = 20.0 * options.beam_spacing_rad;
  const double expected_y = EndResolutionVariance(spacing, options.grid_cell_size_m) +
                            BoxHiddenExtentVariance(1.0, 4.5, 1.8);
  EXPECT_NEAR(car(1, 1) - grid.point_covariance(1, 1), expected_y, 1e-12);
  EXPECT_NEAR(car(0, 0), grid.point_covariance(0, 0), 1e-15);
  EXPECT_NEAR(car(0, 1), 0.0, 1e-15);
  // The same grid object of unknown class: the ends only.
  const Matrix2d unknown = LidarPointCovariance(grid, ObjectClass::kUnknown, lidar, options);
  EXPECT_NEAR(unknown(1, 1) - grid.point_covariance(1, 1),
              EndResolutionVariance(spacing, options.grid_cell_size_m), 1e-12);
  // The defaults: the round body on, the grid's extent off.
  const LidarPointModelOptions defaults;
  EXPECT_EQ(LidarPointCovariance(grid, ObjectClass::kCar, lidar, defaults), grid.point_covariance);
  EXPECT_LT((LidarPointCovariance(grid, ObjectClass::kPedestrian, lidar, defaults) -
             grid.point_covariance -
             RoundBodyCovariance(defaults.footprints.pedestrian_radius_m, point - lidar,
                                 kGridRoundBodyDepth))
                .norm(),
            1e-15);
}

// The shape decides what is round: a walker the camera calls a car (its box the circle's 2r
// square) keeps the round body with its own radius; a car-sized box is no circle whatever the
// class; a pedestrian known by its class alone has the footprint's radius.
TEST(LidarPointModelTest, ARoundBodyIsKnownByItsBoxWhateverItsClass) {
  const LidarPointModelOptions options;
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kPedestrian, 0.0, 0.0}, options),
            options.footprints.pedestrian_radius_m);
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kPedestrian, 0.44, 0.44}, options), 0.22);
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kPedestrian, 0.6, 0.4}, options), 0.3);
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kCar, 0.6, 0.6}, options), 0.3);
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kPole, 0.2, 0.2}, options), 0.1);
  EXPECT_EQ(RoundBodyRadius({ObjectClass::kUnknown, 0.7, 0.7}, options), 0.35);
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kCar, 0.0, 0.0}, options));
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kCar, 0.6, 0.4}, options));  // not a square
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kCar, 4.5, 1.8}, options));
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kPedestrian, 4.5, 1.8}, options));
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kCyclist, 1.8, 0.6}, options));
  EXPECT_FALSE(RoundBodyRadius({ObjectClass::kTruck, 1.0, 1.0}, options));  // over 0.8 m

  const Vector2d lidar(2.2, 0.0);
  const Vector2d point(12.2, 3.0);
  const LidarObject segment = SegmentObject(point, Vector2d(0.0, 0.25));
  const Matrix2d misnamed =
      LidarPointCovariance(segment, PairedBody{ObjectClass::kCar, 0.6, 0.6}, lidar, options);
  EXPECT_LT((misnamed - segment.point_covariance -
             RoundBodyCovariance(0.3, point - lidar, kSegmentationRoundBodyDepth))
                .norm(),
            1e-15);
  EXPECT_EQ(LidarPointCovariance(segment, PairedBody{ObjectClass::kCar, 4.5, 1.8}, lidar, options),
            segment.point_covariance);
  LidarPointModelOptions off;
  off.round_body = false;
  EXPECT_EQ(LidarPointCovariance(segment, PairedBody{ObjectClass::kCar, 0.6, 0.6}, lidar, off),
            segment.point_covariance);
}

// The camera's side: a segment 0.9 m long on the 1.8 m end the camera measures facing the
// lidar has the other 0.9 m hidden at either end (0.9^2 / 12 along the segment); a segment
// across the camera's side (another side seen), a whole side, a round body or the switch off
// add nothing.
TEST(LidarPointModelTest, ASideTheCameraMeasuresLongerIsPartlyHidden) {
  LidarPointModelOptions options;
  options.side_heading = false;  // its own test, below
  const Vector2d lidar(2.2, 0.0);
  const Vector2d point(22.2, 0.0);  // ahead: the end runs along y
  const LidarObject segment = SegmentObject(point, Vector2d(0.0, 0.45));
  const PairedBody car{ObjectClass::kCar, 4.5, 1.8, Vector2d(0.0, 1.8)};
  const Matrix2d c = LidarPointCovariance(segment, car, lidar, options);
  EXPECT_NEAR(c(1, 1) - segment.point_covariance(1, 1), 0.9 * 0.9 / 12.0, 1e-12);
  EXPECT_NEAR(c(0, 0), segment.point_covariance(0, 0), 1e-15);
  EXPECT_NEAR(c(0, 1), 0.0, 1e-15);
  // The camera's side in the other direction along the same line: the same.
  EXPECT_EQ(LidarPointCovariance(segment, {ObjectClass::kCar, 4.5, 1.8, Vector2d(0.0, -1.8)}, lidar,
                                 options),
            c);
  EXPECT_EQ(LidarPointCovariance(segment, {ObjectClass::kCar, 4.5, 1.8, Vector2d(4.5, 0.0)}, lidar,
                                 options),
            segment.point_covariance);
  const LidarObject whole = SegmentObject(point, Vector2d(0.0, 0.9));
  EXPECT_EQ(LidarPointCovariance(whole, car, lidar, options), whole.point_covariance);
  const Matrix2d round = LidarPointCovariance(
      segment, {ObjectClass::kCar, 0.6, 0.6, Vector2d(0.0, 1.8)}, lidar, options);
  EXPECT_LT((round - segment.point_covariance -
             RoundBodyCovariance(0.3, point - lidar, kSegmentationRoundBodyDepth))
                .norm(),
            1e-15);
  LidarPointModelOptions off;
  off.camera_side = false;
  EXPECT_EQ(LidarPointCovariance(segment, car, lidar, off), segment.point_covariance);
}

// A cyclist (1.8 x 0.6 m, heading +x, x in [6, 7.8], y in [-1.85, -1.25]) seen from the
// origin: the ray from its centre leaves through its rear end (x = 6), whose middle (6, -1.55)
// is the truth's point; the lidar's segment is the whole near long side.
TEST(LidarPointModelTest, TheCornerViewTakesTheFacingSidesMiddle) {
  LidarPointModelOptions exact;
  exact.camera_size_sigma_m = 0.0;
  const Vector2d lidar(0.0, 0.0);
  LidarObject side = SegmentObject(Vector2d(6.9, -1.25), Vector2d(0.9, 0.0));
  side.point_covariance = Vector2d(0.0001, 0.00001).asDiagonal();
  const PairedBody cyclist{ObjectClass::kCyclist, 1.8, 0.6, Vector2d(0.0, 0.6)};
  const LidarSidePoint p = FacingSidePoint(side, cyclist, lidar, exact);
  EXPECT_LT((p.point_m - Vector2d(6.0, -1.55)).norm(), 1e-12);
  EXPECT_LT((p.front_start_m - Vector2d(6.0, -1.25)).norm(), 1e-12);
  EXPECT_LT((p.front_end_m - Vector2d(6.0, -1.85)).norm(), 1e-12);
  // Along the segment the corner (twice the middle's 0.0001) and the 0.3 m half side turned by
  // the segment's heading error (12 x 0.00001 / 1.8^2); across, the segment's offset and the
  // half side's (sigma / 2)^2.
  const double along = 2.0 * 0.0001 + 0.3 * 0.3 * 12.0 * 0.00001 / (1.8 * 1.8);
  EXPECT_NEAR(p.covariance(0, 0), along, 1e-15);
  EXPECT_NEAR(p.covariance(1, 1), 0.00001, 1e-15);
  EXPECT_NEAR(p.covariance(0, 1), 0.0, 1e-15);
  const LidarPointModelOptions options;
  EXPECT_NEAR(FacingSidePoint(side, cyclist, lidar, options).covariance(1, 1),
              0.00001 + 0.05 * 0.05, 1e-12);

  // The camera's box picked the long side (its heading is the camera's, tenths of a radian
  // out): the segment's box decides, the same end.
  const PairedBody turned{ObjectClass::kCyclist, 1.8, 0.6, Vector2d(1.8, 0.0)};
  EXPECT_LT((FacingSidePoint(side, turned, lidar, exact).point_m - p.point_m).norm(), 1e-12);

  // Seen along the box's diagonal the rule's test is 0: either side as likely, the point half
  // way, the spread between the middles in its covariance.
  const Vector2d centre(6.9, -1.55);
  const Vector2d diagonal = centre + 10.0 * Vector2d(-0.9, 0.3);
  const LidarSidePoint m = FacingSidePoint(side, cyclist, diagonal, exact);
  const Vector2d d = Vector2d(6.9, -1.25) - Vector2d(6.0, -1.55);
  EXPECT_LT((m.point_m - (Vector2d(6.0, -1.55) + 0.5 * d)).norm(), 1e-9);
  EXPECT_GT(d.normalized().dot(m.covariance * d.normalized()), 0.25 * d.squaredNorm());

  // Seen from (4, 3) the long side faces the lidar: the segment's own middle.
  const Vector2d above(4.0, 3.0);
  const LidarSidePoint own = FacingSidePoint(side, turned, above, exact);
  EXPECT_LT((own.point_m - side.point_m).norm(), 1e-12);
  EXPECT_LT((own.covariance - LidarPointCovariance(side, turned, above, exact)).norm(), 1e-12);
  EXPECT_EQ(own.front_start_m, side.front_start_m);

  // Where it does not apply, the segment's own point and covariance.
  const auto unchanged = [&](const LidarObject& o, const PairedBody& b, const Vector2d& from,
                             const LidarPointModelOptions& with) {
    const LidarSidePoint r = FacingSidePoint(o, b, from, with);
    return r.point_m == o.point_m && r.covariance == LidarPointCovariance(o, b, from, with) &&
           r.front_start_m == o.front_start_m && r.front_end_m == o.front_end_m;
  };
  LidarPointModelOptions off;
  off.corner_view = false;
  EXPECT_TRUE(unchanged(side, cyclist, lidar, off));
  EXPECT_TRUE(unchanged(side, {ObjectClass::kCyclist, 0.6, 0.6, Vector2d(0.0, 0.6)}, lidar,
                        options));  // round
  EXPECT_TRUE(unchanged(side, {ObjectClass::kCyclist, 1.8, 0.6, Vector2d::Zero()}, lidar,
                        options));  // no box
  EXPECT_TRUE(unchanged(SegmentObject(Vector2d(6.9, -1.25), Vector2d(0.1, 0.0)), cyclist, lidar,
                        options));  // too short
  EXPECT_TRUE(unchanged(SegmentObject(Vector2d(6.9, -1.25), Vector2d(0.6, 0.6)), cyclist, lidar,
                        options));                                     // oblique to both sides
  EXPECT_TRUE(unchanged(side, cyclist, Vector2d(6.5, 3.0), options));  // no end visible
}

// A 0.3 m piece of an oncoming car's 1.8 m front (x = 30), its ends hidden: its own heading
// is the noise's (sigma 2.6 rad from its 0.05 m^2 offset variance), and on it alone the side
// choice is a coin toss that drags the point metres down the car's long side. The camera's
// heading (0.1 rad) keeps the front.
TEST(LidarPointModelTest, TheCamerasHeadingSteadiesAShortSegmentsBox) {
  const LidarPointModelOptions options;
  const Vector2d lidar(0.0, 0.0);
  LidarObject piece = SegmentObject(Vector2d(30.0, 3.5), Vector2d(0.0, 0.15));
  piece.point_covariance = Vector2d(0.05, 0.2).asDiagonal();
  PairedBody car{ObjectClass::kCar, 4.5, 1.8, Vector2d(0.0, 1.8), 0.01};
  EXPECT_LT((FacingSidePoint(piece, car, lidar, options).point_m - piece.point_m).norm(), 0.05);
  car.yaw_variance = 0.0;  // unknown: the segment's heading alone
  EXPECT_GT((FacingSidePoint(piece, car, lidar, options).point_m - piece.point_m).norm(), 0.5);
}

// A segment oblique to both of the box's sides is a chord across a corner: it covers its
// projection of the facing side, the rest hidden along that side. One too short for its
// direction to be the side's spreads along the camera's side too.
TEST(LidarPointModelTest, AChordAcrossACornerAndAShortPieceSpreadAlongTheCamerasSide) {
  LidarPointModelOptions options;
  options.side_heading = false;  // its own test, below
  const Vector2d lidar(0.0, 0.0);
  const PairedBody cyclist{ObjectClass::kCyclist, 1.8, 0.6, Vector2d(0.0, 1.8)};
  const Vector2d y(0.0, 1.0);
  const LidarObject chord = SegmentObject(Vector2d(20.0, 0.0), Vector2d(0.15, 0.15));
  const double projected = std::sqrt(2.0) * 0.3 * std::cos(0.25 * kPi);
  const Matrix2d c = LidarPointCovariance(chord, cyclist, lidar, options);
  EXPECT_LT((c - chord.point_covariance - HiddenExtentVariance(projected, 1.8) * y * y.transpose())
                .norm(),
            1e-12);
  const LidarObject piece = SegmentObject(Vector2d(20.0, 0.0), Vector2d(0.05, 0.0));
  const Matrix2d p = LidarPointCovariance(piece, cyclist, lidar, options);
  EXPECT_LT((p - piece.point_covariance - 0.0004 * y * y.transpose()).norm(), 1e-12);
  LidarPointModelOptions off;
  off.camera_side = false;
  EXPECT_EQ(LidarPointCovariance(chord, cyclist, lidar, off), chord.point_covariance);
  EXPECT_EQ(LidarPointCovariance(piece, cyclist, lidar, off), piece.point_covariance);
}

// A segment the scan took for an arc and moved 6 cm towards the lidar (right-turn-cyclist's
// cyclist, its 0.6 m end seen head on between a return on each side: NEES 52 and 42) goes
// back where its returns put it when the camera's box is no circle; a round box keeps it.
TEST(LidarPointModelTest, AnArcTheCameraSaysIsNoCircleGoesBack) {
  const LidarPointModelOptions options;
  const Vector2d lidar(0.0, 0.0);
  LidarObject end = SegmentObject(Vector2d(11.19, -1.55), Vector2d(0.0, 0.3));
  end.point_covariance = 1e-6 * Matrix2d::Identity();  // the end's side choice sure
  end.round_body_shift_m = Vector2d(-0.064, 0.0);
  const PairedBody cyclist{ObjectClass::kCyclist, 1.8, 0.6, Vector2d(0.0, 0.6)};
  const LidarSidePoint back = FacingSidePoint(end, cyclist, lidar, options);
  EXPECT_LT((back.point_m - Vector2d(11.254, -1.55)).norm(), 1e-9);
  EXPECT_LT((back.front_start_m - Vector2d(11.254, -1.85)).norm(), 1e-9);
  const PairedBody walker{ObjectClass::kPedestrian, 0.6, 0.6, Vector2d(0.0, 0.6)};
  EXPECT_EQ(FacingSidePoint(end, walker, lidar, options).point_m, end.point_m);
}

// A small L the scan also read as an arc (LidarObject::arc_reading): a round body's camera box
// takes the arc, every field the reading holds; a cyclist's box, no box of a class that is not
// a pedestrian, or the round body switched off keep the L; an object with no reading is itself.
TEST(LidarPointModelTest, ASmallLIsReadAsAnArcWhereTheCameraSeesACircle) {
  LidarPointModelOptions options;
  LidarObject l = SegmentObject(Vector2d(11.19, -1.55), Vector2d(0.0, 0.2));
  l.id = 7;
  l.point_count = 12;
  LidarObject::FrontReading arc;
  arc.point_m = Vector2d(11.12, -1.40);
  arc.point_covariance = Vector2d(0.0001, 0.0002).asDiagonal();
  arc.front_start_m = Vector2d(11.10, -1.68);
  arc.front_end_m = Vector2d(11.14, -1.12);
  arc.round_body_shift_m = Vector2d(-0.06, 0.0);
  arc.hidden_start_m = 0.04;
  arc.hidden_end_m = 0.9;
  l.arc_reading = arc;
  l.has_arc_reading = true;
  const auto same_front = [](const LidarObject& o, const LidarObject::FrontReading& r) {
    return o.point_m == r.point_m && o.point_covariance == r.point_covariance &&
           o.front_start_m == r.front_start_m && o.front_end_m == r.front_end_m &&
           o.round_body_shift_m == r.round_body_shift_m && o.hidden_start_m == r.hidden_start_m &&
           o.hidden_end_m == r.hidden_end_m;
  };
  const LidarObject::FrontReading as_l{l.point_m,     l.point_covariance,   l.front_start_m,
                                       l.front_end_m, l.round_body_shift_m, l.hidden_start_m,
                                       l.hidden_end_m};
  const PairedBody walker{ObjectClass::kPedestrian, 0.6, 0.6, Vector2d(0.0, 0.6)};
  const LidarObject read = ReadAsBody(l, walker, options);
  EXPECT_TRUE(same_front(read, arc));
  EXPECT_EQ(read.id, 7u);
  EXPECT_EQ(read.point_count, 12u);
  EXPECT_TRUE(same_front(ReadAsBody(l, PairedBody{ObjectClass::kPedestrian}, options), arc));
  EXPECT_TRUE(
      same_front(ReadAsBody(l, PairedBody{ObjectClass::kCyclist, 1.8, 0.6}, options), as_l));
  EXPECT_TRUE(same_front(ReadAsBody(l, PairedBody{ObjectClass::kCyclist}, options), as_l));
  options.round_body = false;
  EXPECT_TRUE(same_front(ReadAsBody(l, walker, options), as_l));
  options.round_body = true;
  l.has_arc_reading = false;
  EXPECT_TRUE(same_front(ReadAsBody(l, walker, options), as_l));
}

// A walker (r = 0.3 m, 12 m away) whatever its heading: with the camera's heading, the lidar's
// point is the middle of the side of the walker's square that faces the lidar (the truth's
// point), its front that side, a radius in front of the centre; without it, the arc's nearest
// point, up to r sin(pi/4) = 0.21 m across from it.
TEST(LidarPointModelTest, AWalkersSquareTurnsWithTheCamerasHeading) {
  const double r = 0.3;
  const Vector2d lidar(2.2, 0.0);
  const Vector2d centre = lidar + 12.0 * Vector2d(std::cos(0.4), std::sin(0.4));
  const Vector2d along = (centre - lidar).normalized();
  const Vector2d across(-along.y(), along.x());
  LidarObject arc = SegmentObject(centre - r * along, r * across);  // the whole chord seen
  LidarPointModelOptions options;
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> heading(-kPi, kPi);
  double worst_without = 0.0;
  int checked = 0;
  for (int k = 0; k < 500; ++k) {
    const double yaw = heading(rng);
    const stereo::OrientedBox square{centre, yaw, 2.0 * r, 2.0 * r};
    const auto truth = stereo::FrontSegmentFacing(square, lidar);
    ASSERT_TRUE(truth.has_value());
    const PairedBody walker{ObjectClass::kPedestrian, 2.0 * r, 2.0 * r,
                            truth->end_m - truth->start_m, 1e-8};
    options.round_body_heading = true;
    const LidarSidePoint turned = FacingSidePoint(arc, walker, lidar, options);
    // Near a corner view (the square's diagonal on the ray) either of two sides may face the
    // lidar within the centre's few centimetres: the point is their mixture
    // (stereo::ExpectedFrontPoint), tested there.
    const double t = std::remainder(yaw - 0.4, 0.5 * kPi);
    if (std::abs(std::abs(t) - 0.25 * kPi) > 0.2) {
      EXPECT_LT((turned.point_m - truth->midpoint_m).norm(), 1e-3) << "heading " << yaw;
      ++checked;
    }
    const Vector2d side = turned.front_end_m - turned.front_start_m;
    Vector2d normal(-side.y(), side.x());
    normal = normal.normalized() * (normal.dot(centre - lidar) < 0.0 ? -1.0 : 1.0);
    EXPECT_LT((0.5 * (turned.front_start_m + turned.front_end_m) + r * normal - centre).norm(),
              1e-9);
    options.round_body_heading = false;
    worst_without = std::max(
        worst_without,
        (FacingSidePoint(arc, walker, lidar, options).point_m - truth->midpoint_m).dot(across));
  }
  EXPECT_GT(worst_without, 0.19) << "seed " << kSeed;
  EXPECT_GT(checked, 350);
}

// A walker's 0.6 m square at `centre`, turned 0.2 rad, as the camera pairs it (its heading to
// 0.05 rad): the side facing `lidar`.
constexpr double kTurnedWalkerRadius = 0.3;
PairedBody TurnedWalker(const Vector2d& centre, const Vector2d& lidar) {
  const double d = 2.0 * kTurnedWalkerRadius;
  const auto facing = stereo::FrontSegmentFacing(stereo::OrientedBox{centre, 0.2, d, d}, lidar);
  return PairedBody{ObjectClass::kPedestrian, d, d, facing->end_m - facing->start_m, 0.05 * 0.05};
}

// The turned square's covariance: with the camera's heading to 0.05 rad and the whole chord
// seen, centimetres across the ray where the heading unknown gives 0.13 m; a chord of half the
// diameter, both ends seen free, lies anywhere between the silhouettes: the unseen half's
// (0.3 m)^2 / 12 across, give or take the range noise's terms (the mean of the whole arc's 12
// returns and of the piece's 6), and along the ray the depth
// that goes with it (a piece off the ray's middle lies deeper), more than the whole arc's by
// about a centimetre's standard deviation; one longer than the diameter, the surplus's.
TEST(LidarPointModelTest, ATurnedSquaresSpreadIsTheHeadingsAndTheUnseenChords) {
  const double r = kTurnedWalkerRadius;
  const Vector2d lidar(0.0, 0.0);
  const Vector2d centre(12.0, 0.0);
  const LidarPointModelOptions options;
  const PairedBody walker = TurnedWalker(centre, lidar);
  LidarObject whole = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, r));
  whole.point_count = 12;
  const Matrix2d p = FacingSidePoint(whole, walker, lidar, options).covariance;
  EXPECT_LT(std::sqrt(p(1, 1)), 0.03);
  EXPECT_GT(std::sqrt(RoundBodyCovariance(r, centre - lidar, kSegmentationRoundBodyDepth)(1, 1)),
            0.12);
  LidarObject half = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, 0.5 * r));
  half.point_count = 6;
  const Matrix2d q = FacingSidePoint(half, walker, lidar, options).covariance;
  const double noise = options.range_sigma_m * options.range_sigma_m;
  EXPECT_NEAR(q(1, 1) - p(1, 1), r * r / 12.0, noise);
  EXPECT_GT(q(0, 0), p(0, 0));
  EXPECT_LT(q(0, 0) - p(0, 0), 0.015 * 0.015);
  // A chord of 0.9 m holds another body besides the 0.6 m one: (0.3 m)^2 / 12 along it.
  LidarObject two = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, 0.45));
  two.point_count = whole.point_count;
  const Matrix2d t = FacingSidePoint(two, walker, lidar, options).covariance;
  EXPECT_NEAR(t(1, 1) - p(1, 1), 0.3 * 0.3 / 12.0, 1e-9);
}

// The radius's error as the side's middle feels it, a whole arc of 12 returns: the centre lies
// behind the returns by what ArcPieceCentre's secant says per metre of radius, and the side's
// middle a radius in front of the centre along its normal. Square on, the side moves along
// the ray by the slope less one and not across it; turned 40 degrees, the side's middle lies
// r cos 40 in front of the centre and r sin 40 to the side, and moves by (slope - cos 40,
// sin 40) per metre: across the ray too (it was taken along the ray alone before 2026-12-06).
TEST(LidarPointModelTest, TheRadiusErrorMovesTheSideAlongItsNormal) {
  const double r = 0.3;
  const Vector2d lidar(0.0, 0.0);
  const Vector2d centre(12.0, 0.0);
  const LidarPointModelOptions options;
  const double radius_sigma = 0.5 * options.camera_size_sigma_m;
  const double size_variance = radius_sigma * radius_sigma;
  LidarObject whole = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, r));
  whole.point_count = 12;
  const double slope = ArcPieceCentre(r, 2.0 * r, 12, -r, -r, radius_sigma).depth_radius_slope;
  const auto side_variances = [&](double yaw) {
    const stereo::OrientedBox square{centre, yaw, 2.0 * r, 2.0 * r};
    const auto truth = stereo::FrontSegmentFacing(square, lidar);
    const PairedBody walker{ObjectClass::kPedestrian, 2.0 * r, 2.0 * r,
                            truth->end_m - truth->start_m, 1e-8};
    const Matrix2d c = FacingSidePoint(whole, walker, lidar, options).covariance;
    return Vector2d(c(0, 0), c(1, 1));
  };
  const Vector2d square_on = side_variances(0.0);
  const double turn = 40.0 * kPi / 180.0;
  const Vector2d turned = side_variances(turn);
  const double along_on = slope - 1.0;
  const double along = slope - std::cos(turn);
  const double across = std::sin(turn);
  EXPECT_NEAR(turned.x() - square_on.x(), size_variance * (along * along - along_on * along_on),
              1e-6);
  EXPECT_NEAR(turned.y() - square_on.y(), size_variance * across * across, 1e-6);
  EXPECT_GT(turned.y() - square_on.y(), 0.03 * 0.03);
}

// A front that is one leg of a split L holds that leg's returns, not the object's: 12 returns
// on a walker 12 m away whose front spans half the diameter (six beam spacings of 5.2 cm) gives
// the side point of the six on it, exactly; counted whole, its depth would be twice as sure.
TEST(LidarPointModelTest, AFrontHoldsTheReturnsOnItsChord) {
  const double r = kTurnedWalkerRadius;
  const Vector2d lidar(0.0, 0.0);
  const Vector2d centre(12.0, 0.0);
  const LidarPointModelOptions options;
  const PairedBody walker = TurnedWalker(centre, lidar);
  LidarObject leg = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, 0.5 * r));
  leg.point_count = 12;
  LidarObject alone = leg;
  alone.point_count = 7;  // 0.3 m / 5.2 cm + 1
  const LidarSidePoint from_leg = FacingSidePoint(leg, walker, lidar, options);
  const LidarSidePoint from_alone = FacingSidePoint(alone, walker, lidar, options);
  EXPECT_LT((from_leg.covariance - from_alone.covariance).norm(), 1e-15);
  EXPECT_LT((from_leg.point_m - from_alone.point_m).norm(), 1e-15);
  LidarObject fewer = leg;
  fewer.point_count = 5;  // fewer than the chord would hold: the object's own count stands
  EXPECT_GT(FacingSidePoint(fewer, walker, lidar, options).covariance(0, 0),
            from_leg.covariance(0, 0));
}

// The same leg with one end in a nearer body's shadow that could hide the rest and the other
// seen free: a piece of its own seven returns is the silhouette's edge on the free side, but as
// the leg of a split L of twelve its free end may be the L's corner: anywhere on the near
// half-circle, half the diameter's (0.3 m)^2 / 12 wider across the ray.
TEST(LidarPointModelTest, ASplitLegIsAnywhereOnTheCircle) {
  const double r = kTurnedWalkerRadius;
  const Vector2d lidar(0.0, 0.0);
  const Vector2d centre(12.0, 0.0);
  const LidarPointModelOptions options;
  const PairedBody walker = TurnedWalker(centre, lidar);
  LidarObject piece = SegmentObject(centre - Vector2d(r, 0.0), Vector2d(0.0, 0.5 * r));
  piece.point_count = 7;
  piece.hidden_start_m = 1.0;
  piece.hidden_end_m = 12.0 * options.beam_spacing_rad;
  LidarObject leg = piece;
  leg.point_count = 12;
  const Matrix2d edge = FacingSidePoint(piece, walker, lidar, options).covariance;
  const Matrix2d anywhere = FacingSidePoint(leg, walker, lidar, options).covariance;
  EXPECT_GT(anywhere(1, 1) - edge(1, 1), 0.5 * r * r / 12.0);
}

// A segment deeper along the ray than a radius is no arc of one circle: a lamp post 0.5 m in
// front of a walker, one segment to the scan. The walker's side is at either end of that depth:
// (0.5 m / 2)^2 along the ray. A segment 0.2 m deep, within a radius, gets nothing of it: a few
// centimetres along, where the piece may lie on the circle.
TEST(LidarPointModelTest, ASegmentDeeperThanARadiusHoldsAnotherBody) {
  const double r = 0.3;
  const Vector2d lidar(0.0, 0.0);
  const LidarPointModelOptions options;
  const PairedBody walker{ObjectClass::kPedestrian, 2.0 * r, 2.0 * r, Vector2d(0.0, 2.0 * r),
                          0.05 * 0.05};
  const auto along_variance = [&](double depth) {
    LidarObject o = SegmentObject(Vector2d(20.0, 0.0), Vector2d(0.5 * depth, 0.1));
    o.hidden_start_m = o.hidden_end_m = 5.0;  // a piece anywhere on the near half-circle
    return FacingSidePoint(o, walker, lidar, options).covariance(0, 0);
  };
  EXPECT_LT(along_variance(0.2), 0.05 * 0.05);
  EXPECT_GT(along_variance(0.5), 0.25 * 0.25);
  EXPECT_LT(along_variance(0.5), 0.25 * 0.25 + 0.05 * 0.05);
}

// The corner lies anywhere in what the scan could not see past the segment's end: 0.42 m of
// the cyclist's 1.8 m side seen from its rear corner on, the scan unable to say how far the
// side runs on past that end (a shadow), the corner's variance along is the second moment of
// the 1.38 m the camera's side leaves, 1.38^2 / 3 (right-turn-cyclist's pair at 2.7 m: its
// corner 0.75 m past the end, fused NEES 93). Where the scan sees the end free, a beam spacing.
TEST(LidarPointModelTest, ACornerPastAHiddenEndIsThatUncertain) {
  const LidarPointModelOptions options;
  const Vector2d lidar(0.0, 0.0);
  LidarObject piece = SegmentObject(Vector2d(6.21, -1.25), Vector2d(0.21, 0.0));
  piece.point_covariance = Vector2d(0.0001, 0.00001).asDiagonal();
  piece.hidden_start_m = 2.0;  // the end nearer the lidar: (6, -1.25)
  piece.hidden_end_m = 0.05;
  const PairedBody cyclist{ObjectClass::kCyclist, 1.8, 0.6, Vector2d(0.0, 0.6)};
  const LidarSidePoint hidden = FacingSidePoint(piece, cyclist, lidar, options);
  // Near the end-on view the segment's own middle weighs a little (the box's side choice under
  // that corner's spread, q about 0.01).
  EXPECT_GT(hidden.covariance(0, 0), 0.97 * 1.38 * 1.38 / 3.0);
  EXPECT_LT(hidden.covariance(0, 0), 1.38 * 1.38 / 3.0 + 0.01);
  EXPECT_LT((hidden.point_m - Vector2d(6.0, -1.55)).norm(), 0.05);
  piece.hidden_start_m = 0.01;
  const LidarSidePoint seen_free = FacingSidePoint(piece, cyclist, lidar, options);
  EXPECT_LT(seen_free.covariance(0, 0), 0.001);
  EXPECT_LT((seen_free.point_m - Vector2d(6.0, -1.55)).norm(), 1e-3);
}

// The spread along a segment turned by its heading error: 1.8 m of a car's 4.5 m side along y,
// the hidden 2.7 m spread (2.7^2 / 12) along it, and across it that spread times the heading
// variance, the segment's 12 x 0.0004 / 1.8^2 combined with the camera's 0.01.
TEST(LidarPointModelTest, TheSpreadAlongASideTurnsWithItsHeading) {
  const LidarPointModelOptions options;
  const Vector2d lidar(0.0, 0.0);
  const LidarObject side = SegmentObject(Vector2d(20.0, 0.0), Vector2d(0.0, 0.9));
  const PairedBody car{ObjectClass::kCar, 4.5, 1.8, Vector2d(0.0, 4.5), 0.01};
  const Matrix2d c = LidarPointCovariance(side, car, lidar, options);
  const double along = 0.0009 + 2.7 * 2.7 / 12.0;
  const double segment = 12.0 * 0.0004 / (1.8 * 1.8);
  const double heading = 1.0 / (1.0 / segment + 1.0 / 0.01);
  EXPECT_NEAR(c(1, 1), along, 1e-12);
  EXPECT_NEAR(c(0, 0), 0.0004 + along * heading, 1e-12);
  EXPECT_NEAR(c(0, 1), 0.0, 1e-15);
  // Without the camera's heading, the segment's alone; switched off, nothing across.
  PairedBody no_yaw = car;
  no_yaw.yaw_variance = 0.0;
  EXPECT_NEAR(LidarPointCovariance(side, no_yaw, lidar, options)(0, 0), 0.0004 + along * segment,
              1e-12);
  LidarPointModelOptions off;
  off.side_heading = false;
  EXPECT_NEAR(LidarPointCovariance(side, car, lidar, off)(0, 0), 0.0004, 1e-15);
}

TEST(LidarPointModelTest, MostLikelyClassOfThePmf) {
  LidarObject o;
  o.class_pmf = {0.2, 0.5, 0.1, 0.2, 0.0, 0.0};
  EXPECT_EQ(MostLikelyLidarClass(o), ObjectClass::kPedestrian);
  o.class_pmf = {0.4, 0.1, 0.1, 0.4, 0.0, 0.0};
  EXPECT_EQ(MostLikelyLidarClass(o), ObjectClass::kUnknown);  // ties: the first
}

TEST(LidarPointModelTest, ValidateNamesTheField) {
  LidarPointModelOptions options;
  options.footprints.pedestrian_radius_m = 0.0;
  try {
    options.Validate();
    FAIL() << "accepted a zero radius";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pedestrian_radius_m"), std::string::npos);
  }
  LidarPointModelOptions square;
  square.round_square_tolerance_m = -0.1;
  EXPECT_THROW(square.Validate(), std::invalid_argument);
  LidarPointModelOptions angle;
  angle.camera_side_max_angle_rad = 2.0;
  EXPECT_THROW(angle.Validate(), std::invalid_argument);
  LidarPointModelOptions diameter;
  diameter.max_round_diameter_m = std::nan("");
  EXPECT_THROW(diameter.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace lookout::fusion

namespace lookout::fusion {
namespace {

// The mean depth of a circle's near arc over [a, a + c] across the ray, by the midpoint rule
// on 20,000 steps: the literal reference for ArcPieceCentre with densely sampled returns.
double LiteralArcDepth(double r, double a, double c) {
  constexpr int kSteps = 20'000;
  double sum = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const double y = a + c * (k + 0.5) / kSteps;
    sum += std::sqrt(std::max(0.0, r * r - y * y));
  }
  return sum / kSteps;
}

// A whole arc's returns lie (pi / 4) r in front of the centre on average, across it in the
// middle; an edge piece's lie shallower, the centre r - c / 2 across from their middle; a piece
// anywhere on the circle has the spread of where it may be. Against the literal integral
// (10,001 returns: the continuous mean within 1e-4).
TEST(LidarPointModelTest, ArcPieceCentreIsWhereTheCircleIs) {
  const double r = 0.3;
  const double step = 0.05;  // the radius's error, half the camera's 0.1 m of size
  const int dense = 10'001;
  const ArcCentre whole = ArcPieceCentre(r, 2.0 * r, dense, -r, -r, step);
  EXPECT_NEAR(whole.mean_m.x(), 0.25 * kPi * r, 1e-4);
  EXPECT_NEAR(whole.mean_m.y(), 0.0, 1e-12);
  EXPECT_LT(whole.covariance.norm(), 1e-12);

  const double c = 0.1;
  const ArcCentre low_edge = ArcPieceCentre(r, c, dense, -r, -r, step);
  EXPECT_NEAR(low_edge.mean_m.x(), LiteralArcDepth(r, -r, c), 1e-4);
  EXPECT_NEAR(low_edge.mean_m.y(), r - 0.5 * c, 1e-12);  // the centre towards the hidden side
  const ArcCentre high_edge = ArcPieceCentre(r, c, dense, r - c, r - c, step);
  EXPECT_NEAR(high_edge.mean_m.x(), low_edge.mean_m.x(), 1e-12);
  EXPECT_NEAR(high_edge.mean_m.y(), -(r - 0.5 * c), 1e-12);
  EXPECT_LT(low_edge.mean_m.x(), 0.55 * r);  // 0.155 m, where a radius (0.3 m) was taken
  // Two returns, at the silhouette and 0.1 m in: their own mean, not the arc's.
  EXPECT_NEAR(ArcPieceCentre(r, c, 2, -r, -r, step).mean_m.x(),
              0.5 * (0.0 + std::sqrt(r * r - (r - c) * (r - c))), 1e-12);

  // Beyond 32 returns the trapezoid rule stands in for the returns' own mean: within a
  // millimetre of it, a whole arc and an edge piece, 33 to 400 returns.
  for (const int returns : {33, 50, 100, 400}) {
    for (const double chord : {2.0 * r - 0.04, 0.2}) {
      double mean = 0.0;
      for (int k = 0; k < returns; ++k) {
        const double y = -r + 0.01 + chord * k / (returns - 1);
        mean += std::sqrt(std::max(0.0, r * r - y * y)) / returns;
      }
      EXPECT_NEAR(ArcPieceCentre(r, chord, returns, -r + 0.01, -r + 0.01, step).mean_m.x(), mean,
                  1e-3)
          << returns << " returns over " << chord << " m";
    }
  }

  // How far the centre lies behind the returns per metre of radius: the secant over the step
  // against the literal integral's, an edge piece anchored to its silhouette, and a whole arc,
  // whose last return reaches the far silhouette: there the derivative is infinite (the depth
  // at the end goes as sqrt(4 r dr)), the secant over 1e-5 m of radius 30 times what it is
  // over the radius's own error, which a whole arc's centre behind its returns moves by
  // (pi / 4 and a little, the returns near the far silhouette). Infinite for any number of
  // returns, it weighs with their fewness: a walker's dozen, ten times over.
  const double literal_edge =
      (LiteralArcDepth(r + step, -r - step, c) - LiteralArcDepth(r, -r, c)) / step;
  EXPECT_NEAR(low_edge.depth_radius_slope, literal_edge, 1e-2);
  const double literal_whole =
      (LiteralArcDepth(r + step, -r - step, 2.0 * r) - LiteralArcDepth(r, -r, 2.0 * r)) / step;
  EXPECT_NEAR(whole.depth_radius_slope, literal_whole, 1e-2);
  EXPECT_GT(whole.depth_radius_slope, 0.25 * kPi);
  EXPECT_LT(whole.depth_radius_slope, 1.5);
  const int walker = 12;  // returns on a walker's whole arc at 12 m
  EXPECT_GT(ArcPieceCentre(r, 2.0 * r, walker, -r, -r, 1e-5).depth_radius_slope,
            10.0 * ArcPieceCentre(r, 2.0 * r, walker, -r, -r, step).depth_radius_slope);

  // Anywhere on the circle: the moments of the piece's place, uniform, against 400 places.
  const ArcCentre anywhere = ArcPieceCentre(r, c, dense, -r, r - c, step);
  constexpr int kPlaces = 400;
  double mean_depth = 0.0, depth2 = 0.0, across2 = 0.0;
  for (int k = 0; k < kPlaces; ++k) {
    const double a = -r + (2.0 * r - c) * (k + 0.5) / kPlaces;
    const double depth = LiteralArcDepth(r, a, c);
    mean_depth += depth / kPlaces;
    depth2 += depth * depth / kPlaces;
    across2 += (a + 0.5 * c) * (a + 0.5 * c) / kPlaces;
  }
  EXPECT_NEAR(anywhere.mean_m.x(), mean_depth, 2e-3);
  EXPECT_NEAR(anywhere.mean_m.y(), 0.0, 1e-12);
  EXPECT_NEAR(anywhere.covariance(1, 1), across2, 0.01 * across2);
  EXPECT_NEAR(anywhere.covariance(0, 0), depth2 - mean_depth * mean_depth,
              0.05 * (depth2 - mean_depth * mean_depth));
}

// A walker (a 0.3 m circle) 18 m away whose high edge the scan sees: four returns on the arc,
// beams 0.25 deg apart, the first `gap_rad` of bearing short of the silhouette; the low end in
// another walker's shadow (hidden 1 m), the high end hidden `hidden_end_m`. The truth: the
// middle of the side of the walker's square (heading 0.3 rad) facing the lidar.
struct WalkersEdge {
  static constexpr double kRadius = 0.3;
  static constexpr double kBeamSpacingRad = 0.25 * kPi / 180.0;
  Vector2d lidar = Vector2d::Zero();
  Vector2d centre{18.0, 0.6};
  LidarObject piece;
  stereo::FrontSegment truth;
  PairedBody walker;
  Vector2d beam() const { return centre.normalized(); }
  Vector2d across() const { return Vector2d(-beam().y(), beam().x()); }
};

WalkersEdge MakeWalkersEdge(double gap_rad, double hidden_end_m) {
  WalkersEdge w;
  const double r = WalkersEdge::kRadius;
  const double centre_bearing = std::atan2(w.centre.y(), w.centre.x());
  const double half_width = std::asin(r / w.centre.norm());
  std::vector<Vector2d> returns;
  for (double phi = centre_bearing + half_width - gap_rad; returns.size() < 4;
       phi -= WalkersEdge::kBeamSpacingRad) {
    const Vector2d d(std::cos(phi), std::sin(phi));
    const double b = d.dot(w.centre);
    const double h2 = r * r - (w.centre.squaredNorm() - b * b);
    EXPECT_GT(h2, 0.0);
    returns.push_back((b - std::sqrt(std::max(h2, 0.0))) * d);
  }
  for (const Vector2d& p : returns) w.piece.point_m += p / 4.0;
  w.piece.front_start_m = returns.back();  // scan order: low bearing first
  w.piece.front_end_m = returns.front();
  w.piece.point_count = 4;
  w.piece.point_covariance = Vector2d(0.0001, 0.002).asDiagonal();
  w.piece.hidden_start_m = 1.0;
  w.piece.hidden_end_m = hidden_end_m;
  const stereo::OrientedBox square{w.centre, 0.3, 2.0 * r, 2.0 * r};
  const auto truth = stereo::FrontSegmentFacing(square, w.lidar);
  EXPECT_TRUE(truth.has_value());
  if (truth) w.truth = *truth;
  w.walker = PairedBody{ObjectClass::kPedestrian, 2.0 * r, 2.0 * r, w.truth.end_m - w.truth.start_m,
                        0.05 * 0.05};
  return w;
}

// A walker half behind another (a crowd's): the edge seen free, the silhouette half a beam
// spacing past the last return (the model's mean: anywhere within the spacing). The edge model
// puts the side's middle on the truth's within 2 cm; taken for the middle of an arc the scan
// does not place (both ends seen free) it is 0.14 m off across the ray.
TEST(LidarPointModelTest, AWalkersEdgeTakesTheCentreBehindIt) {
  const WalkersEdge w = MakeWalkersEdge(0.5 * WalkersEdge::kBeamSpacingRad, 0.05);  // seen free
  const LidarPointModelOptions options;
  const LidarSidePoint edge = FacingSidePoint(w.piece, w.walker, w.lidar, options);
  EXPECT_LT((edge.point_m - w.truth.midpoint_m).norm(), 0.02);
  const Vector2d e = edge.point_m - w.truth.midpoint_m;
  EXPECT_LT(e.dot(e), 9.0 * (w.across().dot(edge.covariance * w.across()) +
                             w.beam().dot(edge.covariance * w.beam())));

  LidarObject unsaid = w.piece;
  unsaid.hidden_start_m = 0.05;  // both ends free: the scan says nothing of which edge
  const LidarSidePoint middle = FacingSidePoint(unsaid, w.walker, w.lidar, options);
  EXPECT_GT(std::abs((middle.point_m - w.truth.midpoint_m).dot(w.across())), 0.12);
}

// The same edge, its silhouette 0.15 m past the last return, hidden there by a nearer body
// whose shadow covers 0.2 m past that end: the scan does not see the end free, so the
// silhouette may lie anywhere within those 0.2 m, not within a beam spacing (0.08 m at 18 m).
// The centre is placed over that margin and the side's middle holds the truth within three
// sigmas across the ray (0.05 m off against 0.06 m of sigma), where one beam spacing's margin
// put it 3.7 sigmas off (0.11 m against 0.03 m).
TEST(LidarPointModelTest, AnEdgeInANearerBodysShadowMayReachAcrossIt) {
  const WalkersEdge w = MakeWalkersEdge(0.15 / WalkersEdge{}.centre.norm(), 0.2);
  const LidarSidePoint edge = FacingSidePoint(w.piece, w.walker, w.lidar, LidarPointModelOptions{});
  const double error_across = (edge.point_m - w.truth.midpoint_m).dot(w.across());
  const double sigma_across = std::sqrt(w.across().dot(edge.covariance * w.across()));
  EXPECT_GT(std::abs(error_across), 0.03);  // the margin's middle, not the silhouette
  EXPECT_LT(std::abs(error_across), 3.0 * sigma_across);
  // The margin's spread: at least that of a uniform place over the 0.2 m past the spacing.
  const double margin = 0.2 - WalkersEdge::kBeamSpacingRad * w.centre.norm();
  EXPECT_GT(sigma_across, margin / std::sqrt(12.0));
}

}  // namespace
}  // namespace lookout::fusion
