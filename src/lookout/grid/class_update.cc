#include "lookout/grid/class_update.h"

#include <algorithm>
#include <cmath>

#include "lookout/core/planar_geometry.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {
namespace {

constexpr std::size_t kStatic = static_cast<std::size_t>(GridClass::kStatic);
constexpr std::size_t kPedestrian = static_cast<std::size_t>(GridClass::kPedestrian);
constexpr std::size_t kCyclist = static_cast<std::size_t>(GridClass::kCyclist);
constexpr std::size_t kVehicle = static_cast<std::size_t>(GridClass::kVehicle);
constexpr std::size_t kUnknown = static_cast<std::size_t>(GridClass::kUnknown);

// exp(-excess^2 / (2 s^2)) for the amount by which v leaves [lo, hi].
double Soft(double v, double lo, double hi, double s) {
  const double excess = v < lo ? lo - v : (v > hi ? v - hi : 0.0);
  return std::exp(-excess * excess / (2.0 * s * s));
}

}  // namespace

ClassPmf SpeedClassLikelihood(double speed_mps) {
  ClassPmf l{};
  l[kStatic] = static_cast<float>(Soft(speed_mps, 0.0, 0.0, 0.3));
  l[kPedestrian] = static_cast<float>(Soft(speed_mps, 0.0, 2.5, 0.5));
  l[kCyclist] = static_cast<float>(Soft(speed_mps, 2.0, 10.0, 1.5));
  l[kVehicle] = static_cast<float>(Soft(speed_mps, 2.0, 40.0, 3.0));
  l[kUnknown] = 0.3f;
  return l;
}

ClassPmf ExtentClassLikelihood(double occupied_cells, double box_side_cells) {
  // In box-side units: a pedestrian's or cyclist's footprint (<= 0.8 m, ~5 cells) fills under
  // about one box side of cells; a vehicle's (>= 1.6 m) or a wall's fills more.
  const double n = occupied_cells / box_side_cells;
  ClassPmf l{};
  l[kStatic] = 1.0f;
  l[kPedestrian] = static_cast<float>(Soft(n, 0.0, 1.0, 0.3));
  l[kCyclist] = static_cast<float>(Soft(n, 0.0, 1.4, 0.4));
  l[kVehicle] = static_cast<float>(Soft(n, 1.2, 1e9, 0.4));
  l[kUnknown] = 0.3f;
  return l;
}

void UpdateClasses(const Associations& a, const TargetIndex& targets,
                   const std::vector<UpdateCell>& cells, const ScrollingGridGeometry& geometry,
                   const WindowIndexer& indexer, const FilterOptions& options,
                   const ClassInputs& in, const std::vector<StereoClassRegion>& stereo,
                   const std::array<std::span<float>, kGridClassCount>& class_pmf) {
  const auto active = static_cast<float>(options.active_occupancy);
  const int w = indexer.width();
  const int h = indexer.height();
  // The extent proxy is counted directly in the box of each occupied update cell: a street scene
  // has a few hundred of them, fewer lookups than a summed-area table of the whole window. It
  // counts the occupied cells this scan hits: the visible surface, for which the cue's sizes
  // hold. The grid also keeps occupied the cells of a tracked body it no longer sees (a
  // cyclist's far side, seen as it turned): counted, they made a cyclist a car.
  const auto occupied_in_box = [&](const CellIndex& local, int r) {
    int n = 0;
    for (int y = std::max(0, local.iy - r); y <= std::min(h - 1, local.iy + r); ++y) {
      for (int x = std::max(0, local.ix - r); x <= std::min(w - 1, local.ix + r); ++x) {
        const std::size_t s = indexer.Storage(x, y);
        const bool hit = in.measured.empty() || in.measured[s] > 0.5f;
        n += in.occupancy[s] >= active && hit ? 1 : 0;
      }
    }
    return n;
  };
  const int r = static_cast<int>(options.extent_radius_cells);
  const double box_side = 2.0 * r + 1.0;
  const double floor = options.class_floor;

  ParallelForBlocks(cells.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t u = begin; u < end; ++u) {
      const UpdateCell& c = cells[u];
      // A cell that only got a measurement and holds no occupancy keeps its pmf: nothing moved
      // into or out of it and there is nothing to classify (most of the update list: free space).
      if (c.target_slot == FilterWorkspace::kNone && c.source == FilterWorkspace::kNone &&
          in.occupancy[c.cell] < active) {
        continue;
      }
      std::array<double, kGridClassCount> pmf{};
      double sum = 0.0;
      if (c.target_slot != FilterWorkspace::kNone) {
        sum = GatherWeighted(a, targets, c.target_slot,
                             [&](std::uint32_t, std::uint32_t s, double wt) {
                               for (std::size_t k = 0; k < kGridClassCount; ++k) {
                                 pmf[k] += wt * static_cast<double>(
                                                    a.class_pmf[s * kGridClassCount + k]);
                               }
                             });
      }
      const double uniform = 1.0 / kGridClassCount;
      if (sum > 0.0) {
        const double s = static_cast<double>(in.seen[c.cell]);
        for (double& p : pmf) p = s * p / sum + (1.0 - s) * uniform;
      } else if (c.source != FilterWorkspace::kNone) {
        pmf.fill(uniform);
      } else {
        for (std::size_t k = 0; k < kGridClassCount; ++k) {
          pmf[k] = static_cast<double>(class_pmf[k][c.cell]);
        }
      }
      if (in.occupancy[c.cell] >= active) {
        const double speed = std::hypot(static_cast<double>(in.velocity_x_mps[c.cell]),
                                        static_cast<double>(in.velocity_y_mps[c.cell]));
        const double conf = static_cast<double>(in.confidence[c.cell]);
        const ClassPmf by_speed = SpeedClassLikelihood(speed);
        for (std::size_t k = 0; k < kGridClassCount; ++k) {
          pmf[k] *= std::pow(static_cast<double>(by_speed[k]), conf);
        }
        const bool hidden_mover = !in.measured.empty() && !Observed(in.measured[c.cell]) &&
                                  speed >= options.unobserved_mover_speed_mps;
        if (!hidden_mover) {
          // The cell's local position, for the extent box.
          const CellIndex local = geometry.LocalFromGlobal(geometry.GlobalFromStorage(c.cell));
          const double occupied = occupied_in_box(local, r);
          const ClassPmf by_extent = ExtentClassLikelihood(occupied, box_side);
          for (std::size_t k = 0; k < kGridClassCount; ++k) {
            pmf[k] *= std::pow(static_cast<double>(by_extent[k]), conf);
          }
        }
      }
      double total = 0.0;
      for (const double p : pmf) total += p;
      for (std::size_t k = 0; k < kGridClassCount; ++k) {
        const double p = total > 0.0 ? pmf[k] / total : uniform;
        class_pmf[k][c.cell] = static_cast<float>((1.0 - floor) * p + floor * uniform);
      }
    }
  });

  // Stereo objects: their likelihood multiplies the pmf of the occupied cells they cover.
  if (options.stereo_weight <= 0.0) return;
  for (const StereoClassRegion& region : stereo) {
    if (region.polygon_m.size() < 3) continue;
    Eigen::Vector2d lo = region.polygon_m[0], hi = region.polygon_m[0];
    for (const Eigen::Vector2d& p : region.polygon_m) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const CellIndex g0 = geometry.GlobalCellAt(lo);
    const CellIndex g1 = geometry.GlobalCellAt(hi);
    for (int gy = g0.iy; gy <= g1.iy; ++gy) {
      for (int gx = g0.ix; gx <= g1.ix; ++gx) {
        const CellIndex g{gx, gy};
        if (!geometry.Contains(g) || !InsidePolygon(region.polygon_m, geometry.CellCenterM(g))) {
          continue;
        }
        const std::size_t cell = geometry.StorageIndex(g);
        if (in.occupancy[cell] < active) continue;
        std::array<double, kGridClassCount> pmf{};
        double total = 0.0;
        for (std::size_t k = 0; k < kGridClassCount; ++k) {
          pmf[k] = static_cast<double>(class_pmf[k][cell]) *
                   std::pow(static_cast<double>(region.likelihood[k]), options.stereo_weight);
          total += pmf[k];
        }
        if (total <= 0.0) continue;
        for (std::size_t k = 0; k < kGridClassCount; ++k) {
          class_pmf[k][cell] = static_cast<float>(pmf[k] / total);
        }
      }
    }
  }
}

}  // namespace lookout::grid
