#include "lookout/lidar/local_map.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <optional>

namespace lookout::lidar {

LocalMap::LocalMap(const MapOptions& options) : options_(options) {
  options_.Validate();
  n_ = options_.window_cells;
  mask_ = static_cast<std::uint32_t>(n_ - 1);
  shift_ = 0;
  while ((1 << shift_) < n_) ++shift_;
  max_distance_ = static_cast<float>(options_.field_max_distance_m);
  window_origin_ = {-n_ / 2, -n_ / 2};
  const std::size_t cells = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  log_odds_.assign(cells, 0.0f);
  distance_.assign(cells, max_distance_);
  stamp_.assign(cells, 0);

  const int r = static_cast<int>(std::ceil(options_.field_max_distance_m / options_.cell_size_m));
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const double d = options_.cell_size_m * std::hypot(dx, dy);
      if (d <= options_.field_max_distance_m) {
        offsets_.push_back({dx, dy, static_cast<float>(d)});
      }
    }
  }
  // Nearest first, so a search stops at the first occupied neighbour; ties in a fixed order.
  std::stable_sort(offsets_.begin(), offsets_.end(),
                   [](const Offset& a, const Offset& b) { return a.distance_m < b.distance_m; });
}

CellIndex LocalMap::CellOf(const Eigen::Vector2d& p) const {
  return {static_cast<int>(std::floor(p.x() / options_.cell_size_m)),
          static_cast<int>(std::floor(p.y() / options_.cell_size_m))};
}

Eigen::Vector2d LocalMap::CellCentre(const CellIndex& c) const {
  return {(static_cast<double>(c.ix) + 0.5) * options_.cell_size_m,
          (static_cast<double>(c.iy) + 0.5) * options_.cell_size_m};
}

bool LocalMap::InWindow(const CellIndex& c) const {
  return c.ix >= window_origin_.ix && c.iy >= window_origin_.iy &&
         c.ix < window_origin_.ix + n_ && c.iy < window_origin_.iy + n_;
}

float LocalMap::LogOdds(const CellIndex& c) const {
  return InWindow(c) ? log_odds_[Slot(c)] : 0.0f;
}

void LocalMap::ResetCell(const CellIndex& c) {
  const std::size_t s = Slot(c);
  log_odds_[s] = 0.0f;
  distance_[s] = max_distance_;
  stamp_[s] = 0;
}

bool LocalMap::RecentreOn(const Eigen::Vector2d& p) {
  const CellIndex c = CellOf(p);
  const int limit = static_cast<int>(options_.recentre_share * static_cast<double>(n_));
  const int centre_x = window_origin_.ix + n_ / 2;
  const int centre_y = window_origin_.iy + n_ / 2;
  if (std::abs(c.ix - centre_x) <= limit && std::abs(c.iy - centre_y) <= limit) return false;

  const CellIndex old_origin = window_origin_;
  const CellIndex new_origin{c.ix - n_ / 2, c.iy - n_ / 2};
  window_origin_ = new_origin;
  // The kept cells, in both windows: [keep_lo, keep_hi) per axis, empty when the move is a
  // whole window or more.
  const CellIndex keep_lo{std::max(old_origin.ix, new_origin.ix),
                          std::max(old_origin.iy, new_origin.iy)};
  const CellIndex keep_hi{std::min(old_origin.ix, new_origin.ix) + n_,
                          std::min(old_origin.iy, new_origin.iy) + n_};
  const bool kept_any = keep_lo.ix < keep_hi.ix && keep_lo.iy < keep_hi.iy;
  // The cells that enter share their slots with the cells that leave: resetting the entering
  // cells forgets the leaving ones. Only they are visited (a strip per axis).
  for (int gy = new_origin.iy; gy < new_origin.iy + n_; ++gy) {
    const bool row_kept = kept_any && gy >= keep_lo.iy && gy < keep_hi.iy;
    for (int gx = new_origin.ix; gx < new_origin.ix + n_; ++gx) {
      if (row_kept && gx == keep_lo.ix) {
        gx = keep_hi.ix - 1;  // skip the kept run of this row
        continue;
      }
      ResetCell({gx, gy});
    }
  }
  // Only the kept cells within field reach of the kept rectangle's border can be affected:
  // an occupied one lowers the entering cells around it (reset to the field's maximum); any
  // other may have measured its distance to a forgotten cell and is searched again, unless
  // it is at the maximum already (forgetting cells cannot lower a distance).
  if (kept_any) {
    const int reach = static_cast<int>(std::ceil(options_.field_max_distance_m /
                                                 options_.cell_size_m));
    for (int gy = keep_lo.iy; gy < keep_hi.iy; ++gy) {
      const bool row_near = gy - reach < keep_lo.iy || gy + reach >= keep_hi.iy;
      for (int gx = keep_lo.ix; gx < keep_hi.ix; ++gx) {
        if (!row_near && gx - reach >= keep_lo.ix && gx + reach < keep_hi.ix) {
          gx = std::max(gx, keep_hi.ix - reach - 1);  // the row's middle is out of reach
          continue;
        }
        float& d = distance_[Slot({gx, gy})];
        if (log_odds_[Slot({gx, gy})] > options_.occupied_log_odds) {
          LowerFieldAround({gx, gy});  // the entering cells within its reach
        } else if (d < max_distance_) {
          d = SearchDistance({gx, gy});
        }
      }
    }
  }
  if (touched_any_) {
    touched_min_ = {std::max(touched_min_.ix, new_origin.ix),
                    std::max(touched_min_.iy, new_origin.iy)};
    touched_max_ = {std::min(touched_max_.ix, new_origin.ix + n_ - 1),
                    std::min(touched_max_.iy, new_origin.iy + n_ - 1)};
    if (touched_min_.ix > touched_max_.ix || touched_min_.iy > touched_max_.iy) {
      touched_any_ = false;
    }
  }
  return true;
}

void LocalMap::UpdateCell(const CellIndex& c, bool hit) {
  const std::size_t s = Slot(c);
  if (stamp_[s] == current_stamp_) return;  // once per scan; hits are applied first
  stamp_[s] = current_stamp_;
  const float before = log_odds_[s];
  const float after = std::clamp(before + (hit ? options_.log_odds_hit : options_.log_odds_miss),
                                 options_.log_odds_min, options_.log_odds_max);
  log_odds_[s] = after;
  const bool was_occupied = before > options_.occupied_log_odds;
  const bool is_occupied = after > options_.occupied_log_odds;
  if (is_occupied && !was_occupied) became_occupied_.push_back(c);
  if (was_occupied && !is_occupied) became_free_.push_back(c);
  if (!touched_any_) {
    touched_any_ = true;
    touched_min_ = c;
    touched_max_ = c;
  } else {
    touched_min_ = {std::min(touched_min_.ix, c.ix), std::min(touched_min_.iy, c.iy)};
    touched_max_ = {std::max(touched_max_.ix, c.ix), std::max(touched_max_.iy, c.iy)};
  }
}

// Bresenham's line from `from` to `to`: every cell before the last is a miss; the last is a
// hit when the ray ended on a return.
void LocalMap::Traverse(const CellIndex& from, const CellIndex& to, bool hit_at_end,
                        bool stop_at_occupied) {
  int x = from.ix;
  int y = from.iy;
  const int dx = std::abs(to.ix - x);
  const int dy = -std::abs(to.iy - y);
  const int sx = x < to.ix ? 1 : -1;
  const int sy = y < to.iy ? 1 : -1;
  int err = dx + dy;
  while (x != to.ix || y != to.iy) {
    if (InWindow({x, y})) {
      // Occupied as the scan began: a cell this scan's hits just raised is stamped already
      // and unaffected either way; one they made occupied stops the ray too.
      if (stop_at_occupied && Occupied({x, y})) return;
      UpdateCell({x, y}, false);
    }
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
  if (hit_at_end || !InWindow(to)) return;
  if (stop_at_occupied && Occupied(to)) return;
  UpdateCell(to, false);
}

Eigen::Vector2d LocalMap::ClipToRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& p,
                                      bool* clipped) const {
  const Eigen::Vector2d d = p - origin;
  const double r = d.norm();
  *clipped = r > options_.max_insert_range_m;
  return *clipped ? Eigen::Vector2d(origin + d * (options_.max_insert_range_m / r)) : p;
}

void LocalMap::InsertScan(const Eigen::Vector2d& origin, std::span<const Eigen::Vector2d> hits,
                          std::span<const Eigen::Vector2d> free_ends,
                          std::span<const Eigen::Vector2d> empty_ends,
                          std::span<const Eigen::Vector2d> bare_hits) {
  ++current_stamp_;
  if (current_stamp_ == 0) {  // the counter wrapped: no stale stamp may equal a new one
    std::fill(stamp_.begin(), stamp_.end(), std::uint16_t{0});
    current_stamp_ = 1;
  }
  became_occupied_.clear();
  became_free_.clear();
  const double min_range = options_.min_insert_range_m;
  // Where a ray to p begins: the origin's cell, or its point at min_insert_range_m; nullopt
  // when p is nearer than that (the ray updates nothing).
  const auto start = [&](const Eigen::Vector2d& p) -> std::optional<CellIndex> {
    if (min_range <= 0.0) return CellOf(origin);
    const Eigen::Vector2d d = p - origin;
    const double r = d.norm();
    if (r <= min_range) return std::nullopt;
    return CellOf(origin + d * (min_range / r));
  };

  // Hits first (see the header): a cell hit in this scan is then stamped and no miss of the
  // same scan can lower it.
  for (const auto& points : {hits, bare_hits}) {
    for (const Eigen::Vector2d& p : points) {
      bool clipped = false;
      const Eigen::Vector2d end = ClipToRange(origin, p, &clipped);
      const CellIndex c = CellOf(end);
      if (!clipped && InWindow(c) && start(p)) UpdateCell(c, true);
    }
  }
  // The rays: hits end on their (already updated) cell, free ends clear through theirs, empty
  // beams stop at the first cell occupied as the scan began.
  const auto rays = [&](std::span<const Eigen::Vector2d> ends, bool hit, bool stop_at_occupied) {
    for (const Eigen::Vector2d& p : ends) {
      bool clipped = false;
      const Eigen::Vector2d end = ClipToRange(origin, p, &clipped);
      if (const std::optional<CellIndex> from = start(end)) {
        Traverse(*from, CellOf(end), hit && !clipped, stop_at_occupied);
      }
    }
  };
  rays(hits, true, false);
  rays(free_ends, false, false);
  rays(empty_ends, false, true);

  for (const CellIndex& c : became_occupied_) LowerFieldAround(c);
  for (const CellIndex& c : became_free_) RepairFieldAround(c);
  if (!became_occupied_.empty()) has_occupied_ = true;
  ++scans_inserted_;
}

void LocalMap::LowerFieldAround(const CellIndex& c) {
  for (const Offset& o : offsets_) {
    const CellIndex n{c.ix + o.dx, c.iy + o.dy};
    if (!InWindow(n)) continue;
    float& d = distance_[Slot(n)];
    d = std::min(d, o.distance_m);
  }
}

void LocalMap::RepairFieldAround(const CellIndex& c) {
  // Only the cells whose distance was exactly the one to c can have measured it to c (the
  // same offset table computed both numbers, so the comparison is exact).
  for (const Offset& o : offsets_) {
    const CellIndex n{c.ix + o.dx, c.iy + o.dy};
    if (!InWindow(n)) continue;
    float& d = distance_[Slot(n)];
    if (d == o.distance_m) d = SearchDistance(n);
  }
}

float LocalMap::SearchDistance(const CellIndex& c) const {
  for (const Offset& o : offsets_) {
    const CellIndex n{c.ix + o.dx, c.iy + o.dy};
    if (InWindow(n) && log_odds_[Slot(n)] > options_.occupied_log_odds) return o.distance_m;
  }
  return max_distance_;
}

LocalMap::FieldSample LocalMap::InterpolatedField(const Eigen::Vector2d& p) const {
  // Cell centres sit at (i + 0.5) * size: u is the position in "centre" coordinates.
  const double u = p.x() / options_.cell_size_m - 0.5;
  const double v = p.y() / options_.cell_size_m - 0.5;
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int ix = static_cast<int>(fu);
  const int iy = static_cast<int>(fv);
  const double a = u - fu;
  const double b = v - fv;
  const double d00 = static_cast<double>(FieldDistance({ix, iy}));
  const double d10 = static_cast<double>(FieldDistance({ix + 1, iy}));
  const double d01 = static_cast<double>(FieldDistance({ix, iy + 1}));
  const double d11 = static_cast<double>(FieldDistance({ix + 1, iy + 1}));
  FieldSample s;
  s.distance_m = (1.0 - b) * ((1.0 - a) * d00 + a * d10) + b * ((1.0 - a) * d01 + a * d11);
  s.gradient.x() = ((1.0 - b) * (d10 - d00) + b * (d11 - d01)) / options_.cell_size_m;
  s.gradient.y() = ((1.0 - a) * (d01 - d00) + a * (d11 - d10)) / options_.cell_size_m;
  return s;
}

MapRaster LocalMap::Raster() const {
  MapRaster raster;
  if (!touched_any_) return raster;
  raster.geometry.cell_size_m = options_.cell_size_m;
  raster.geometry.width = touched_max_.ix - touched_min_.ix + 1;
  raster.geometry.height = touched_max_.iy - touched_min_.iy + 1;
  raster.geometry.origin_m = {static_cast<double>(touched_min_.ix) * options_.cell_size_m,
                              static_cast<double>(touched_min_.iy) * options_.cell_size_m};
  raster.log_odds.resize(static_cast<std::size_t>(raster.geometry.CellCount()));
  for (int y = 0; y < raster.geometry.height; ++y) {
    for (int x = 0; x < raster.geometry.width; ++x) {
      raster.log_odds[static_cast<std::size_t>(raster.geometry.LinearIndex({x, y}))] =
          LogOdds({touched_min_.ix + x, touched_min_.iy + y});
    }
  }
  return raster;
}

}  // namespace lookout::lidar
