#include "lookout/grid/grid_objects.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <limits>

#include "lookout/core/input_error.h"
#include "lookout/grid/min_area_rectangle.h"

namespace lookout::grid {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

void RequireObjectOption(bool ok, const std::string& source, const std::string& field,
                         const char* problem) {
  if (!ok) throw InputError(source, 0, "grid.objects." + field, problem);
}

double At(std::span<const float> layer, std::size_t cell) {
  return static_cast<double>(layer[cell]);
}

// Occupancy-weighted first and second moments of a per-cell vector quantity.
struct WeightedMoments {
  double weight = 0.0;
  double weight_squared = 0.0;
  Vector2d sum = Vector2d::Zero();
  Matrix2d sum_outer = Matrix2d::Zero();

  void Add(double w, const Vector2d& x) {
    weight += w;
    weight_squared += w * w;
    sum += w * x;
    sum_outer += w * x * x.transpose();
  }
  Vector2d Mean() const { return sum / weight; }
  // The weighted (population) covariance of the values.
  Matrix2d Spread() const {
    const Vector2d m = Mean();
    Matrix2d s = sum_outer / weight - m * m.transpose();
    s = 0.5 * (s + s.transpose());  // exactly symmetric
    return s;
  }
  // Kish's effective number of cells: n for equal weights, less when a few cells dominate.
  double EffectiveCount() const { return weight * weight / weight_squared; }
};

// A vector (velocity) and a covariance from the odometry frame's axes into the vehicle's.
Matrix2d Rotated(const Matrix2d& rotation, const Matrix2d& covariance) {
  return rotation * covariance * rotation.transpose();
}

}  // namespace

void GridObjectOptions::Validate(const std::string& source) const {
  RequireObjectOption(min_occupancy >= 0.5 && min_occupancy < 1.0, source, "min_occupancy",
                      "must be in [0.5, 1)");
  RequireObjectOption(std::isfinite(min_speed_mps) && min_speed_mps >= 0.0, source,
                      "min_speed_mps", "must be finite and >= 0");
  RequireObjectOption(min_velocity_confidence >= 0.0 && min_velocity_confidence <= 1.0, source,
                      "min_velocity_confidence", "must be in [0, 1]");
  RequireObjectOption(min_link >= 0.0 && min_link < 1.0, source, "min_link",
                      "must be in [0, 1)");
  RequireObjectOption(min_cells >= 1, source, "min_cells", "must be >= 1");
}

std::vector<std::uint8_t> DynamicCellMask(const GridLayers& layers, const FilterLayerIds& ids,
                                          const GridObjectOptions& options) {
  const std::span<const float> occupancy = layers.Values(ids.occupancy);
  const std::span<const float> vx = layers.Values(ids.velocity_x_mps);
  const std::span<const float> vy = layers.Values(ids.velocity_y_mps);
  const std::span<const float> confidence = layers.Values(ids.velocity_confidence);
  const double min_speed2 = options.min_speed_mps * options.min_speed_mps;
  // The thresholds in locals: the mask's bytes may alias anything, and the options would be
  // read again for every cell.
  const double min_occupancy = options.min_occupancy;
  const double min_confidence = options.min_velocity_confidence;
  std::vector<std::uint8_t> dynamic(occupancy.size(), 0);
  // Most cells are empty: their occupancy alone rules them out, and the velocity layers are read
  // only where it does not (the pass is bound by memory traffic: one layer, not four). The
  // cells are ruled out first by a float test (ForEachWhere's, which vectorises) that lets
  // through every cell the exact test below may keep: its threshold a float under
  // min_occupancy.
  const float below_min =
      std::nextafter(static_cast<float>(min_occupancy), -std::numeric_limits<float>::infinity());
  const float* const o = occupancy.data();
  ForEachWhere(
      occupancy.size(), [&](std::size_t i) { return o[i] > below_min; },
      // By value: the mask's bytes may alias anything a reference would reach.
      [=, &dynamic](std::size_t i) {
        // Comparisons written so that NaN (which the filter never writes) is never dynamic.
        if (!(At(occupancy, i) > min_occupancy)) return;
        const bool confident = At(confidence, i) >= min_confidence;
        const double speed2 = At(vx, i) * At(vx, i) + At(vy, i) * At(vy, i);
        dynamic[i] = confident && speed2 > min_speed2 ? 1 : 0;
      });
  return dynamic;
}

std::vector<GridCluster> FindRigidClusters(const GridLayers& layers, const FilterLayerIds& ids,
                                           const std::vector<std::uint8_t>& dynamic,
                                           const GridObjectOptions& options) {
  const WindowIndexer indexer(layers.geometry());
  std::array<std::span<const float>, kNeighbourCount> link;
  for (std::size_t d = 0; d < kNeighbourCount; ++d) link[d] = layers.Values(ids.rigidity[d]);

  std::vector<std::uint8_t> visited(dynamic.size(), 0);
  std::vector<GridCluster> clusters;
  std::deque<CellIndex> queue;  // local cells
  const auto width = static_cast<std::size_t>(indexer.width());
  for (int y = 0; y < indexer.height(); ++y) {
    // A row without a dynamic cell (most rows) is passed over in one memchr over its storage
    // run; the seeds of the others are taken in local x order, as before.
    if (std::memchr(dynamic.data() + indexer.RowStorage(y), 1, width) == nullptr) continue;
    for (int x = 0; x < indexer.width(); ++x) {
      const std::size_t seed = indexer.Storage(x, y);
      if (!dynamic[seed] || visited[seed]) continue;
      GridCluster cluster;
      visited[seed] = 1;
      queue.push_back({x, y});
      while (!queue.empty()) {
        const CellIndex c = queue.front();
        queue.pop_front();
        const std::size_t from = indexer.Storage(c.ix, c.iy);
        cluster.cells.push_back(from);
        for (std::size_t d = 0; d < kNeighbourCount; ++d) {
          const int nx = c.ix + kNeighbourOffsets[d].ix;
          const int ny = c.iy + kNeighbourOffsets[d].iy;
          if (!indexer.Inside(nx, ny)) continue;
          const std::size_t to = indexer.Storage(nx, ny);
          if (!dynamic[to] || visited[to]) continue;
          const std::size_t back = OppositeDirection(d);
          const double d_link = std::max(At(link[d], from), At(link[back], to));
          if (!(d_link > options.min_link)) continue;
          visited[to] = 1;
          queue.push_back({nx, ny});
        }
      }
      if (cluster.cells.size() >= static_cast<std::size_t>(options.min_cells)) {
        clusters.push_back(std::move(cluster));
      }
    }
  }
  return clusters;
}

std::array<double, kAllObjectClasses.size()> ToObjectClassPmf(
    const std::array<double, kGridClassCount>& grid_pmf) {
  auto p = [&grid_pmf](GridClass c) {
    return std::max(0.0, grid_pmf[static_cast<std::size_t>(c)]);
  };
  std::array<double, kAllObjectClasses.size()> out{};
  auto at = [&out](ObjectClass c) -> double& { return out[static_cast<std::size_t>(c)]; };
  at(ObjectClass::kUnknown) = p(GridClass::kStatic) + p(GridClass::kUnknown);
  at(ObjectClass::kPedestrian) = p(GridClass::kPedestrian);
  at(ObjectClass::kCyclist) = p(GridClass::kCyclist);
  at(ObjectClass::kCar) = p(GridClass::kVehicle);
  double total = 0.0;
  for (const double v : out) total += v;
  if (!(total > 0.0)) {
    at(ObjectClass::kUnknown) = 1.0;  // no class mass at all: say so
    return out;
  }
  for (double& v : out) v /= total;
  return out;
}

LidarObject DescribeCluster(const ExtendedGrid& grid, const GridCluster& cluster,
                            const ObjectFrameContext& context, const GridObjectOptions& options) {
  const ScrollingGridGeometry& g = grid.geometry();
  const GridLayers& layers = grid.layers();
  const FilterLayerIds& ids = grid.ids();
  const std::span<const float> occupancy = layers.Values(ids.occupancy);
  const std::span<const float> vx = layers.Values(ids.velocity_x_mps);
  const std::span<const float> vy = layers.Values(ids.velocity_y_mps);
  const double cell = g.cell_size_m();

  // Moments in the odometry frame (the grid's).
  WeightedMoments position, velocity;
  std::array<double, kGridClassCount> class_sum{};
  std::vector<Vector2d> corners;
  corners.reserve(4 * cluster.cells.size());
  for (const std::size_t i : cluster.cells) {
    const double w = At(occupancy, i);
    const Vector2d centre = g.CellCenterM(g.GlobalFromStorage(i));
    position.Add(w, centre);
    velocity.Add(w, Vector2d(At(vx, i), At(vy, i)));
    for (std::size_t c = 0; c < kGridClassCount; ++c) {
      class_sum[c] += w * At(layers.Values(ids.class_pmf[c]), i);
    }
    for (const double sx : {-0.5, 0.5}) {
      for (const double sy : {-0.5, 0.5}) corners.push_back(centre + cell * Vector2d(sx, sy));
    }
  }
  const Vector2d centroid_odom = position.Mean();
  const Vector2d velocity_odom = velocity.Mean();
  const double n_eff = position.EffectiveCount();

  // Front segment: the cells at the two extreme bearings from the lidar, bearings taken
  // relative to the centroid's so that a cluster across the lidar's -pi/pi line is one interval.
  const Pose2 lidar_odom = context.ego_pose * context.lidar_mount;
  const Vector2d to_centroid = centroid_odom - lidar_odom.translation;
  const double centroid_bearing = std::atan2(to_centroid.y(), to_centroid.x());
  struct Extreme {
    double bearing;
    double range;
    Vector2d point;
  };
  Extreme lowest{std::numeric_limits<double>::infinity(), 0.0, centroid_odom};
  Extreme highest{-std::numeric_limits<double>::infinity(), 0.0, centroid_odom};
  constexpr double kSameBearingRad = 1e-9;
  for (const std::size_t i : cluster.cells) {
    const Vector2d centre = g.CellCenterM(g.GlobalFromStorage(i));
    const Vector2d ray = centre - lidar_odom.translation;
    const double bearing = WrapAngle(std::atan2(ray.y(), ray.x()) - centroid_bearing);
    const double range = ray.norm();
    if (bearing < lowest.bearing - kSameBearingRad ||
        (bearing <= lowest.bearing + kSameBearingRad && range < lowest.range)) {
      lowest = {std::min(bearing, lowest.bearing), range, centre};
    }
    if (bearing > highest.bearing + kSameBearingRad ||
        (bearing >= highest.bearing - kSameBearingRad && range < highest.range)) {
      highest = {std::max(bearing, highest.bearing), range, centre};
    }
  }

  // Extent, its length turned along the motion.
  OrientedRectangle extent = MinAreaRectangle(corners);
  const double speed = velocity_odom.norm();
  if (speed > options.min_speed_mps &&
      velocity_odom.dot(Vector2d(std::cos(extent.yaw_rad), std::sin(extent.yaw_rad))) < 0.0) {
    extent.yaw_rad = WrapAngle(extent.yaw_rad + kPi);
  }

  // Uncertainties (odometry axes).
  const Matrix2d quantisation_m2 = Matrix2d::Identity() * (cell * cell / 12.0);
  const double cell_speed = cell / context.dt_s;
  const Matrix2d point_covariance = quantisation_m2 + position.Spread() / n_eff;
  const Matrix2d velocity_covariance =
      velocity.Spread() / velocity.EffectiveCount() +
      Matrix2d::Identity() * (cell_speed * cell_speed / 12.0);

  // Into the vehicle frame.
  const Pose2 vehicle_from_odom = context.ego_pose.Inverse();
  const Matrix2d r = vehicle_from_odom.Rotation();
  LidarObject o;
  o.centroid_m = vehicle_from_odom * centroid_odom;
  o.front_start_m = vehicle_from_odom * lowest.point;
  o.front_end_m = vehicle_from_odom * highest.point;
  o.point_m = 0.5 * (o.front_start_m + o.front_end_m);
  o.point_covariance = Rotated(r, point_covariance);
  const Vector2d centroid_lidar = context.lidar_mount.Inverse() * o.centroid_m;
  o.range_m = centroid_lidar.norm();
  o.bearing_rad = std::atan2(centroid_lidar.y(), centroid_lidar.x());
  o.yaw_rad = WrapAngle(extent.yaw_rad - context.ego_pose.yaw);
  o.length_m = extent.length_m;
  o.width_m = extent.width_m;
  o.velocity_mps = r * velocity_odom;
  o.velocity_covariance = Rotated(r, velocity_covariance);
  o.class_pmf = ToObjectClassPmf(class_sum);
  o.cell_count = static_cast<std::uint32_t>(cluster.cells.size());
  o.point_count = 0;  // the grid holds no scan points
  o.dynamic = speed > options.min_speed_mps;
  return o;
}

LidarObjectFrame ExtractGridObjects(const ExtendedGrid& grid, const ObjectFrameContext& context,
                                    const GridObjectOptions& options) {
  LidarObjectFrame frame;
  frame.stamp = context.stamp;
  frame.mount = context.lidar_mount;
  frame.ego_pose = context.ego_pose;
  const std::vector<std::uint8_t> dynamic = DynamicCellMask(grid.layers(), grid.ids(), options);
  const std::vector<GridCluster> clusters =
      FindRigidClusters(grid.layers(), grid.ids(), dynamic, options);
  frame.objects.reserve(clusters.size());
  for (const GridCluster& cluster : clusters) {
    frame.objects.push_back(DescribeCluster(grid, cluster, context, options));
    frame.objects.back().id = static_cast<std::uint32_t>(frame.objects.size() - 1);
  }
  return frame;
}

}  // namespace lookout::grid
