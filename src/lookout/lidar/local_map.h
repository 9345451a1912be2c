#pragma once

// The local occupancy map of the static environment (seed 004 section IV.A): clamped log-odds
// in square cells, a window that moves with the vehicle, and beside it the likelihood field
// (the distance from each cell to the nearest occupied cell) that the particle filter and the
// scan matcher read.
//
// Cells are addressed by global integer indices (floor(x / cell_size)); the window holds
// window_cells x window_cells of them in a circular buffer, so moving the window clears the
// strips that leave instead of copying the rest (as grid_map does). Anything outside the window
// reads as unknown (log-odds 0, distance = field maximum). On a log that loops back into a
// part that has left the window, that part is mapped afresh: no loop is closed.
//
// Update rules, one scan at a time:
// - every cell is updated at most once per scan: a cell hit by two beams gets one hit;
// - hits first, then misses: a cell both hit by one beam and passed through by another in the
//   same scan counts as hit (so a grazing beam cannot erase the wall it runs along);
// - log-odds are clamped to [log_odds_min, log_odds_max] so that a cell can change its mind.
// The likelihood field is kept exact incrementally: a cell that becomes occupied lowers the
// distances around it; around a cell that stops being occupied, the cells whose distance it
// was are searched again. A cell is occupied when its log-odds exceed occupied_log_odds.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

// A copy of part of the map for pictures and tests: log-odds in a GridGeometry (row-major,
// row 0 at the bottom, as GridGeometry has it).
struct MapRaster {
  GridGeometry geometry;
  std::vector<float> log_odds;
};

class LocalMap {
 public:
  // Validates the options (lookout::InputError). The window starts centred on the origin.
  explicit LocalMap(const MapOptions& options = {});

  const MapOptions& options() const { return options_; }

  // Global cell of a point and the point at a cell's centre.
  CellIndex CellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d CellCentre(const CellIndex& c) const;
  bool InWindow(const CellIndex& c) const;
  // The window's lower-left global cell.
  CellIndex WindowOrigin() const { return window_origin_; }

  // Moves the window so that p is at its centre when p is further than recentre_share of the
  // window's side from the centre; returns whether it moved.
  bool RecentreOn(const Eigen::Vector2d& p);

  // Integrates one scan taken from `origin` (the sensor's position in the map frame): a ray to
  // each point of `hits` ending in an occupied cell, and a ray to each point of `free_ends`
  // that only clears space (a beam with no return, or a hit beyond max_insert_range_m, which
  // is clipped to that range here, as are hits).
  // `empty_ends`: rays of beams that saw nothing (no return within the scanner's range), which
  // clear space only up to the first cell that is occupied at the start of the scan: a beam
  // with no return through a mapped wall is the wall's return lost (glass, a dark surface, a
  // dropout), not the wall gone.
  // `bare_hits`: returns whose cell is hit but whose ray the caller clears itself (as a free
  // end short of the return), e.g. only up to where the neighbouring beams found a surface.
  void InsertScan(const Eigen::Vector2d& origin, std::span<const Eigen::Vector2d> hits,
                  std::span<const Eigen::Vector2d> free_ends,
                  std::span<const Eigen::Vector2d> empty_ends = {},
                  std::span<const Eigen::Vector2d> bare_hits = {});

  float LogOdds(const CellIndex& c) const;  // 0 outside the window
  bool Occupied(const CellIndex& c) const { return LogOdds(c) > options_.occupied_log_odds; }

  // Distance from the cell's centre to the nearest occupied cell's centre, in metres, capped
  // at field_max_distance_m (which is also the answer outside the window).
  float FieldDistance(const CellIndex& c) const {
    return InWindow(c) ? distance_[Slot(c)] : max_distance_;
  }
  // FieldDistance of the cell holding p.
  float FieldDistanceAt(const Eigen::Vector2d& p) const { return FieldDistance(CellOf(p)); }

  // Bilinear interpolation of the field between cell centres, and its gradient (per metre):
  // what Gauss-Newton needs, continuous across cell borders.
  struct FieldSample {
    double distance_m = 0.0;
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  };
  FieldSample InterpolatedField(const Eigen::Vector2d& p) const;

  std::int64_t scans_inserted() const { return scans_inserted_; }
  // Whether any scan has marked a cell occupied.
  bool HasOccupied() const { return has_occupied_; }

  // The cells that scans have touched (within the window), or an empty raster.
  MapRaster Raster() const;

 private:
  struct Offset {
    int dx;
    int dy;
    float distance_m;
  };

  // The cells are stored in 8 x 8 tiles, row-major inside a tile and tile by tile: a ray or a
  // field search that runs along y touches a cache line every two cells, not every cell (a
  // row of the 4096-cell window is 16 KB).
  std::size_t Slot(const CellIndex& c) const {
    const std::uint32_t x = static_cast<std::uint32_t>(c.ix) & mask_;
    const std::uint32_t y = static_cast<std::uint32_t>(c.iy) & mask_;
    return (static_cast<std::size_t>(y >> 3) << (shift_ + 3)) |
           (static_cast<std::size_t>(x >> 3) << 6) | static_cast<std::size_t>((y & 7u) << 3) |
           static_cast<std::size_t>(x & 7u);
  }
  void ResetCell(const CellIndex& c);
  // Applies one hit or miss to a cell not yet updated in this scan.
  void UpdateCell(const CellIndex& c, bool hit);
  void Traverse(const CellIndex& from, const CellIndex& to, bool hit_at_end,
                bool stop_at_occupied = false);
  void LowerFieldAround(const CellIndex& c);
  void RepairFieldAround(const CellIndex& c);
  float SearchDistance(const CellIndex& c) const;
  Eigen::Vector2d ClipToRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& p,
                              bool* clipped) const;

  MapOptions options_;
  int n_;                 // window side in cells
  std::uint32_t mask_;    // n_ - 1
  int shift_;             // log2(n_)
  float max_distance_;
  CellIndex window_origin_;
  std::vector<float> log_odds_;
  std::vector<float> distance_;
  std::vector<std::uint16_t> stamp_;  // scan counter of the last update, 0 = never
  std::uint16_t current_stamp_ = 0;
  std::vector<Offset> offsets_;  // within field_max_distance_m, nearest first
  std::vector<CellIndex> became_occupied_;
  std::vector<CellIndex> became_free_;
  std::int64_t scans_inserted_ = 0;
  bool has_occupied_ = false;
  bool touched_any_ = false;
  CellIndex touched_min_;
  CellIndex touched_max_;
};

}  // namespace lookout::lidar
