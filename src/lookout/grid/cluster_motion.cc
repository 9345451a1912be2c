#include "lookout/grid/cluster_motion.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/grid_objects.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {
namespace {

void RequireClusterMotionOption(bool ok, const std::string& source, const std::string& field,
                                const char* problem) {
  if (!ok) throw InputError(source, 0, "grid.filter.cluster_motion." + field, problem);
}

bool WithinUnit(double v) { return v >= 0.0 && v <= 1.0; }  // NaN: false

bool HitBefore(const HitMaps& m, const CellIndex& c) {
  return m.Inside(c.ix, c.iy) && m.before[m.At(c.ix, c.iy)] != 0;
}

// The doubled score of one hit now explained by the previous scan at (x, y): 2 for a hit there,
// 1 for a hit next to it, 0 otherwise.
int BeforeScore(const HitMaps& m, int x, int y) {
  if (m.Inside(x, y)) {
    const std::size_t i = m.At(x, y);
    return m.before[i] != 0 ? 2 : (m.before_near[i] != 0 ? 1 : 0);
  }
  // Off the maps: a hit of the previous scan may still lie next to it.
  for (int ny = y - 1; ny <= y + 1; ++ny) {
    for (int nx = x - 1; nx <= x + 1; ++nx) {
      if (HitBefore(m, {nx, ny})) return 1;
    }
  }
  return 0;
}

// The doubled score of `hits` moved back by (dx, dy): each explained by the baseline's scan
// there (BeforeScore).
int ScoreOf(const HitMaps& m, std::span<const CellIndex> hits, int dx, int dy) {
  int s = 0;
  for (const CellIndex& h : hits) s += BeforeScore(m, h.ix - dx, h.iy - dy);
  return s;
}

// The vertex of the parabola through (-1, a), (0, b), (1, c), b the largest: within
// [-0.5, 0.5] (beyond, a neighbour would have been the best).
double ParabolaVertex(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  if (!(curvature < 0.0)) return 0.0;  // flat: no sub-cell information
  return std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
}

GridObjectOptions RigidClusterOptions(const ClusterMotionOptions& o) {
  GridObjectOptions c;
  c.min_occupancy = o.min_occupancy;
  c.min_speed_mps = o.min_speed_mps;
  c.min_velocity_confidence = o.min_velocity_confidence;
  c.min_link = o.min_link;
  c.min_cells = o.min_cells;
  return c;
}

// A hit the stage explains as a moving body's arrival: at least the occupancy the hit gives to
// unknown space (its measurement), and seen (ClusterMotionOptions::births).
void BearHit(std::size_t s, const MeasurementGrid& z, std::span<float> occupancy,
             std::span<float> seen) {
  if (occupancy[s] >= z.p_occupied[s]) return;
  occupancy[s] = z.p_occupied[s];
  seen[s] = 1.0f;
}

// What a cell is to this cycle's stage: held by a dynamic cluster, attached to one as a hit
// arriving, or taken into a still body already.
enum CellRole : std::uint8_t { kFree = 0, kMember, kAttached, kInStillBody };

// A body of hits: its cells (window-local) and their bounding box.
struct HitBody {
  std::vector<CellIndex> cells;
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int Extent() const { return std::max(x1 - x0, y1 - y0) + 1; }
};

// The 8-connected body of the free cells `member` accepts that holds window-local `start`
// (itself such a cell), breadth-first; its cells' role becomes kInStillBody.
template <typename Member>
void GrowBody(const ScrollingGridGeometry& g, const CellIndex& start, const Member& member,
              std::vector<std::uint8_t>& role, HitBody& body) {
  body.cells.assign(1, start);
  body.x0 = body.x1 = start.ix;
  body.y0 = body.y1 = start.iy;
  role[g.StorageIndexOfLocal(start)] = kInStillBody;
  for (std::size_t q = 0; q < body.cells.size(); ++q) {
    const CellIndex c = body.cells[q];
    body.x0 = std::min(body.x0, c.ix);
    body.x1 = std::max(body.x1, c.ix);
    body.y0 = std::min(body.y0, c.iy);
    body.y1 = std::max(body.y1, c.iy);
    for (int y = std::max(0, c.iy - 1); y <= std::min(g.height() - 1, c.iy + 1); ++y) {
      for (int x = std::max(0, c.ix - 1); x <= std::min(g.width() - 1, c.ix + 1); ++x) {
        const std::size_t s = g.StorageIndexOfLocal({x, y});
        if (role[s] != kFree || !member(s)) continue;
        role[s] = kInStillBody;
        body.cells.push_back({x, y});
      }
    }
  }
}

// The share of the older scan's hits around `body` (its box grown by the displacement) that
// this scan misses and sees free; nullopt when fewer than two are missed.
std::optional<double> VacatedShare(const HitMaps& older, const HitBody& body,
                                   const ClusterMotion& m) {
  const int mx = static_cast<int>(std::ceil(std::abs(m.dx_cells))) + 1;
  const int my = static_cast<int>(std::ceil(std::abs(m.dy_cells))) + 1;
  int left = 0, vacated = 0;
  for (int y = std::max(0, body.y0 - my); y <= std::min(older.height - 1, body.y1 + my); ++y) {
    for (int x = std::max(0, body.x0 - mx); x <= std::min(older.width - 1, body.x1 + mx); ++x) {
      const std::size_t k = older.At(x, y);
      if (older.before[k] == 0 || older.now[k] == 2) continue;
      ++left;
      if (older.free_now[k] != 0) ++vacated;
    }
  }
  if (left < 2) return std::nullopt;
  return static_cast<double>(vacated) / left;
}

// Whether `cells` (hits) lie on one line (their spread across it under half a cell) and (dx, dy)
// moves them along it by more than half a cell: a line's motion along itself is not in the
// scan (the aperture problem; a wall's hits sliding along it as the ego drives), only its motion
// across it (a car's front face).
bool SlidesAlongItsLine(std::span<const CellIndex> cells, double dx, double dy) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const CellIndex& c : cells) mean += Eigen::Vector2d(c.ix, c.iy);
  mean /= static_cast<double>(cells.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const CellIndex& c : cells) {
    const Eigen::Vector2d d = Eigen::Vector2d(c.ix, c.iy) - mean;
    scatter += d * d.transpose();
  }
  scatter /= static_cast<double>(cells.size());
  // Eigenvalues ascending: the first is the spread across the principal axis.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
  if (eigen.eigenvalues()(0) >= 0.25) return false;  // (1/2 cell)^2
  return std::abs(eigen.eigenvectors().col(1).dot(Eigen::Vector2d(dx, dy))) > 0.5;
}

// The share of `body`'s hits on cells the grid believed free (O < 1/2).
double ArrivedShare(const ScrollingGridGeometry& g, const HitBody& body,
                    std::span<const float> occupancy) {
  int arrived = 0;
  for (const CellIndex& c : body.cells) {
    if (occupancy[g.StorageIndexOfLocal(c)] < 0.5f) ++arrived;
  }
  return static_cast<double>(arrived) / static_cast<double>(body.cells.size());
}

// A body's cells (window-local) projected on its displacement (dx, dy) and across it, cells:
// how far it reaches along its motion (rear to front) and its band across.
struct MotionExtent {
  double ux = 0.0, uy = 0.0;  // unit along the motion
  double rear = std::numeric_limits<double>::infinity();
  double front = -std::numeric_limits<double>::infinity();
  double lo = std::numeric_limits<double>::infinity();  // across
  double hi = -std::numeric_limits<double>::infinity();
  double Along(const CellIndex& c) const { return c.ix * ux + c.iy * uy; }
  double Across(const CellIndex& c) const { return c.iy * ux - c.ix * uy; }
};

// Precondition: (dx, dy) is not zero.
MotionExtent ExtentAlong(const ScrollingGridGeometry& g, std::span<const std::size_t> cells,
                         double dx, double dy) {
  MotionExtent e;
  const double length = std::hypot(dx, dy);
  e.ux = dx / length;
  e.uy = dy / length;
  for (const std::size_t cell : cells) {
    const CellIndex c = g.LocalFromGlobal(g.GlobalFromStorage(cell));
    e.rear = std::min(e.rear, e.Along(c));
    e.front = std::max(e.front, e.Along(c));
    e.lo = std::min(e.lo, e.Across(c));
    e.hi = std::max(e.hi, e.Across(c));
  }
  return e;
}

// ClusterMotionOptions::sides: the body of this scan's hits 8-connected to `cells` (a cluster
// of extent `e` along its motion) through hits no cluster holds, within the cluster's band
// across its motion (a cell either side), at most side_max_cells behind its front and each hit
// for fewer than `wall_scans` scans (their role becomes kAttached: the body's); of these, the
// cells behind the cluster's rear (its trailing side; the hits beside it are another body's as
// often as its own: a walker's neighbour, a cyclist's).
template <typename HitNow>
std::vector<std::size_t> TrailingSide(const ScrollingGridGeometry& g,
                                      std::span<const std::size_t> cells, const MotionExtent& e,
                                      const HitNow& hit_now, std::span<const float> hit_scans,
                                      double wall_scans, const ClusterMotionOptions& options,
                                      std::vector<std::uint8_t>& role) {
  std::vector<CellIndex> queue;
  for (const std::size_t cell : cells)
    queue.push_back(g.LocalFromGlobal(g.GlobalFromStorage(cell)));
  std::vector<std::size_t> trailing;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const CellIndex c = queue[q];
    for (int y = std::max(0, c.iy - 1); y <= std::min(g.height() - 1, c.iy + 1); ++y) {
      for (int x = std::max(0, c.ix - 1); x <= std::min(g.width() - 1, c.ix + 1); ++x) {
        const std::size_t s = g.StorageIndexOfLocal({x, y});
        const CellIndex n{x, y};
        if (role[s] != kFree || !hit_now(s) || e.Across(n) < e.lo - 1.0 ||
            e.Across(n) > e.hi + 1.0 || e.Along(n) < e.front - options.side_max_cells ||
            static_cast<double>(hit_scans[s]) >= wall_scans) {
          continue;
        }
        role[s] = kAttached;
        if (e.Along(n) < e.rear) trailing.push_back(s);
        queue.push_back(n);
      }
    }
  }
  return trailing;
}

// The still bodies of ClusterMotionOptions::still_bodies, among the cells `role` leaves free.
void MoveStillBodies(const ScrollingGridGeometry& g, const MeasurementGrid& z,
                     std::span<const std::size_t> hits_now, const ScanFlow& flow,
                     std::vector<std::uint8_t>& role, double dt_s, double known_confidence,
                     const ClusterMotionOptions& options, std::span<float> occupancy,
                     std::span<float> seen, std::span<float> vx, std::span<float> vy,
                     std::span<float> confidence, std::vector<MeasuredBody>& measured) {
  const HitMaps* older = flow.long_pair();
  if (older == nullptr) return;
  // The bodies' measurements read the previous scans' outlines (scan_flow.h).
  const HitMaps& short_outline = flow.short_outline_pair();
  const HitMaps& older_outline = *flow.long_outline_pair();
  const int search_half = 2 * options.search_half_cells;
  const double cells_per_mps = dt_s / g.cell_size_m();
  const auto member = [&](std::size_t s) {
    return z.p_occupied[s] > 0.5f &&
           (options.births || static_cast<double>(occupancy[s]) > options.min_occupancy);
  };
  const auto speed = [&](const CellIndex& c) {
    const std::size_t s = g.StorageIndexOfLocal(c);
    return std::hypot(static_cast<double>(vx[s]), static_cast<double>(vy[s]));
  };
  const WindowIndexer indexer(g);
  HitBody body;
  std::vector<CellIndex> outline;
  // Bodies start from this scan's hits in the measurement's order; each body is measured and
  // written alone, so the order does not change the result.
  for (const std::size_t first : hits_now) {
    if (role[first] != kFree || !member(first)) continue;
    GrowBody(g, g.LocalFromGlobal(g.GlobalFromStorage(first)), member, role, body);
    // A body larger than a walker is measured only when most of it lies where the grid
    // believed free space (a vehicle new in view): a large body on cells the grid holds is
    // structure it has seen, and measuring every wall twice a cycle costs 1.8 ms.
    if (static_cast<int>(body.cells.size()) < options.min_hits ||
        body.Extent() > options.new_body_max_extent_cells ||
        (body.Extent() > options.still_max_extent_cells &&
         !(options.births &&
           ArrivedShare(g, body, occupancy) >= options.still_min_arrived_share))) {
      continue;
    }
    const auto far_enough = [&](const ClusterMotion& m, int half) {
      return m.measured &&
             std::hypot(m.dx_cells, m.dy_cells) >= options.still_min_displacement_cells &&
             std::max(std::abs(m.dx_cells), std::abs(m.dy_cells)) <= half - 1;
    };
    // The long pair holds a walker's displacement; a body faster than its search (1 cell a
    // cycle over 6 scans: a 3 m/s car's face moves 1.6), the one-cycle pair with the same
    // search (a 5 m/s truck moves 2.7 cells a cycle), where it moves
    // still_min_displacement_cells or more, but not along a line of hits.
    // A body is measured on the scans' outlines (scan_flow.h).
    outline.clear();
    std::copy_if(body.cells.begin(), body.cells.end(), std::back_inserter(outline),
                 [&](const CellIndex& c) { return OnOutline(z, indexer, c.ix, c.iy); });
    const HitMaps* baseline = older;
    double per_cycle = flow.long_lag_scale();
    ClusterMotion m = MeasureClusterMotion(older_outline, outline, {0, 0}, search_half, options);
    if (!m.measured || std::max(std::abs(m.dx_cells), std::abs(m.dy_cells)) > search_half - 1) {
      m = MeasureClusterMotion(short_outline, outline, {0, 0}, search_half, options);
      if (!far_enough(m, search_half) || SlidesAlongItsLine(outline, m.dx_cells, m.dy_cells)) {
        continue;
      }
      baseline = &flow.short_pair();
      per_cycle = 1.0;
    } else if (!far_enough(m, search_half)) {
      continue;
    }
    const std::optional<double> vacated = VacatedShare(*baseline, body, m);
    if ((!vacated || *vacated < options.still_min_vacated_share) &&
        !(options.births && ArrivedShare(g, body, occupancy) >= options.still_min_arrived_share)) {
      continue;
    }
    // The last cycle agrees: the hits moved back by one cycle's share land on its scan's.
    const int sx = static_cast<int>(std::lround(m.dx_cells * per_cycle));
    const int sy = static_cast<int>(std::lround(m.dy_cells * per_cycle));
    if (baseline == older &&
        ScoreOf(short_outline, outline, sx, sy) <
            options.min_matched_share * 2.0 * static_cast<double>(outline.size())) {
      continue;
    }
    // The grid believed it slower.
    const double body_vx = m.dx_cells * per_cycle / cells_per_mps;
    const double body_vy = m.dy_cells * per_cycle / cells_per_mps;
    double believed = 0.0;
    for (const CellIndex& c : body.cells) believed += speed(c);
    believed /= static_cast<double>(body.cells.size());
    if (believed > options.still_believed_share * std::hypot(body_vx, body_vy)) continue;
    MeasuredBody& moved = measured.emplace_back();
    moved.velocity_x_mps = body_vx;
    moved.velocity_y_mps = body_vy;
    for (const CellIndex& c : body.cells) {
      const std::size_t s = g.StorageIndexOfLocal(c);
      moved.cells.push_back(s);
      vx[s] = static_cast<float>(body_vx);
      vy[s] = static_cast<float>(body_vy);
      confidence[s] = static_cast<float>(known_confidence);
      if (options.births) BearHit(s, z, occupancy, seen);
    }
  }
}

}  // namespace

std::vector<std::size_t> CountHitScans(const MeasurementGrid& z, std::span<float> hit_scans) {
  constexpr float kCap = 1000.0f;  // 80 s at 12.5 Hz: far beyond any threshold, and exact
  std::vector<std::size_t> hits;
  for (const std::size_t cell : z.touched) {
    const float p = z.p_occupied[cell];
    if (p > kUnknownProbability) {
      hit_scans[cell] = std::min(hit_scans[cell] + 1.0f, kCap);
      hits.push_back(cell);
    } else if (p < kUnknownProbability) {
      hit_scans[cell] = 0.0f;  // seen free: whatever stood there left
    }
  }
  return hits;
}

void ClusterMotionOptions::Validate(const std::string& source) const {
  RequireClusterMotionOption(WithinUnit(blend), source, "blend", "must be in [0, 1]");
  RequireClusterMotionOption(search_half_cells >= 0 && search_half_cells <= 16, source,
                             "search_half_cells", "must be in [0, 16]");
  RequireClusterMotionOption(attach_cells >= 0 && attach_cells <= 8, source, "attach_cells",
                             "must be in [0, 8]");
  RequireClusterMotionOption(std::isfinite(birth_min_cells) && birth_min_cells >= 0.0, source,
                             "birth_min_cells", "must be finite and >= 0");
  RequireClusterMotionOption(staying_min_hit_scans >= 0, source, "staying_min_hit_scans",
                             "must be >= 0");
  RequireClusterMotionOption(std::isfinite(side_max_cells) && side_max_cells >= 0.0, source,
                             "side_max_cells", "must be finite and >= 0");
  RequireClusterMotionOption(std::isfinite(side_min_disagreement) && side_min_disagreement >= 0.0,
                             source, "side_min_disagreement", "must be finite and >= 0");
  RequireClusterMotionOption(min_hits >= 1, source, "min_hits", "must be >= 1");
  RequireClusterMotionOption(small_body_max_hits >= 0, source, "small_body_max_hits",
                             "must be >= 0");
  RequireClusterMotionOption(
      std::isfinite(small_body_max_change_mps) && small_body_max_change_mps >= 0.0, source,
      "small_body_max_change_mps", "must be finite and >= 0");
  RequireClusterMotionOption(WithinUnit(min_matched_share), source, "min_matched_share",
                             "must be in [0, 1]");
  RequireClusterMotionOption(std::isfinite(ambiguity_radius_cells) && ambiguity_radius_cells >= 0.0,
                             source, "ambiguity_radius_cells", "must be finite and >= 0");
  RequireClusterMotionOption(WithinUnit(ambiguity_share), source, "ambiguity_share",
                             "must be in [0, 1]");
  RequireClusterMotionOption(new_body_max_extent_cells >= 1, source, "new_body_max_extent_cells",
                             "must be >= 1");
  RequireClusterMotionOption(still_max_extent_cells >= 1, source, "still_max_extent_cells",
                             "must be >= 1");
  RequireClusterMotionOption(
      std::isfinite(still_min_displacement_cells) && still_min_displacement_cells >= 0.0, source,
      "still_min_displacement_cells", "must be finite and >= 0");
  RequireClusterMotionOption(WithinUnit(still_min_vacated_share), source, "still_min_vacated_share",
                             "must be in [0, 1]");
  RequireClusterMotionOption(std::isfinite(still_believed_share) && still_believed_share >= 0.0,
                             source, "still_believed_share", "must be finite and >= 0");
  RequireClusterMotionOption(WithinUnit(still_min_arrived_share), source, "still_min_arrived_share",
                             "must be in [0, 1]");
  RigidClusterOptions(*this).Validate(source);
}

std::vector<int> ClusterMotionScores(const HitMaps& maps, std::span<const CellIndex> hits_now,
                                     const CellIndex& predicted, int search_half) {
  // Hit by hit and row by row, as the scan flow's patch scores (scan_flow.cc, AddHitScores): the
  // cells under one hit's offsets along x are a run of the maps, read in one vectorised pass, in
  // place of a lookup a hit and offset (most of the clusters' stage's instructions). The run
  // goes the other way to the offsets (the cell is hit - o), so the sums are kept mirrored,
  // mirrored[r][k] = score(o) at o = (half - k, half - r), and turned round at the end.
  const int side = 2 * search_half + 1;
  const auto area = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  std::vector<int> mirrored(area, 0);
  // Off the maps, a cell scores (BeforeScore) only where a hit of the previous scan lies next to
  // it: only the cells at x or y = -1 or at the width or height are looked at.
  for (const CellIndex& h : hits_now) {
    const int x0 = h.ix - predicted.ix - search_half;  // the cell under k = 0
    const int y0 = h.iy - predicted.iy - search_half;
    const int lo = std::clamp(-x0, 0, side);
    const int hi = std::clamp(maps.width - x0, 0, side);
    for (int r = 0; r < side; ++r) {
      const int y = y0 + r;
      if (y < -1 || y > maps.height) continue;
      int* row = &mirrored[static_cast<std::size_t>(r * side)];
      if (y == -1 || y == maps.height) {
        for (int k = std::max(lo - 1, 0); k < std::min(hi + 1, side); ++k) {
          row[k] += BeforeScore(maps, x0 + k, y);
        }
        continue;
      }
      if (lo < hi) {
        // AddBefore marks before_near wherever it marks before: their sum is 2, 1 or 0.
        const std::uint8_t* before = &maps.before[maps.At(x0 + lo, y)];
        const std::uint8_t* near = &maps.before_near[maps.At(x0 + lo, y)];
        int* out = row + lo;
        for (int k = 0; k < hi - lo; ++k) out[k] += before[k] + near[k];
      }
      if (lo > 0) row[lo - 1] += BeforeScore(maps, x0 + lo - 1, y);  // x = -1
      if (hi < side && x0 + hi == maps.width) row[hi] += BeforeScore(maps, maps.width, y);
    }
  }
  std::vector<int> scores(area);
  for (std::size_t i = 0; i < area; ++i) scores[i] = mirrored[area - 1 - i];
  return scores;
}

bool LeftFreeSpace(const HitMaps& maps, std::span<const CellIndex> hits_now,
                   const CellIndex& predicted, double min_share) {
  if (hits_now.empty() || maps.width == 0) return false;
  int x0 = hits_now[0].ix, x1 = x0, y0 = hits_now[0].iy, y1 = y0;
  for (const CellIndex& h : hits_now) {
    x0 = std::min(x0, h.ix);
    x1 = std::max(x1, h.ix);
    y0 = std::min(y0, h.iy);
    y1 = std::max(y1, h.iy);
  }
  int before = 0, vacated = 0;
  for (int y = std::max(0, y0 - predicted.iy - 1);
       y <= std::min(maps.height - 1, y1 - predicted.iy + 1); ++y) {
    for (int x = std::max(0, x0 - predicted.ix - 1);
         x <= std::min(maps.width - 1, x1 - predicted.ix + 1); ++x) {
      const std::size_t k = maps.At(x, y);
      if (maps.before[k] == 0) continue;
      ++before;
      if (maps.free_now[k] != 0) ++vacated;
    }
  }
  return before > 0 && vacated >= min_share * before;
}

ClusterMotion MeasureClusterMotion(const HitMaps& maps, std::span<const CellIndex> hits_now,
                                   const CellIndex& predicted, int search_half,
                                   const ClusterMotionOptions& options, bool left_free_space) {
  ClusterMotion out;
  out.hits = static_cast<int>(hits_now.size());
  if (out.hits < options.min_hits || maps.width == 0) return out;
  const int side = 2 * search_half + 1;
  // Doubled scores (integral) of the offsets from `predicted`, row-major.
  const std::vector<int> scores = ClusterMotionScores(maps, hits_now, predicted, search_half);
  const auto score = [&](int ox, int oy) {
    return scores[static_cast<std::size_t>((oy + search_half) * side + ox + search_half)];
  };
  const auto length2 = [&](int ox, int oy) {
    const int x = predicted.ix + ox, y = predicted.iy + oy;
    return x * x + y * y;
  };
  int best_score = -1;
  CellIndex best{0, 0};  // offset from `predicted`
  for (int oy = -search_half; oy <= search_half; ++oy) {
    for (int ox = -search_half; ox <= search_half; ++ox) {
      const int s = score(ox, oy);
      if (s > best_score || (s == best_score && length2(ox, oy) < length2(best.ix, best.iy))) {
        best_score = s;
        best = {ox, oy};
      }
    }
  }
  out.score = 0.5 * best_score;
  if (out.score < options.min_matched_share * out.hits) return out;
  const double radius2 = options.ambiguity_radius_cells * options.ambiguity_radius_cells;
  for (int oy = -search_half; oy <= search_half; ++oy) {
    for (int ox = -search_half; ox <= search_half; ++ox) {
      const double ex = ox - best.ix, ey = oy - best.iy;
      if (ex * ex + ey * ey <= radius2) continue;
      // A staying best keeps its rivals, as in the scan flow: a body's hits that match the scan
      // before's unshifted say nothing of how far it went if it moved.
      if (left_free_space && length2(best.ix, best.iy) > 0 &&
          length2(ox, oy) > length2(best.ix, best.iy)) {
        continue;
      }
      if (score(ox, oy) >= options.ambiguity_share * best_score) return out;  // ambiguous
    }
  }
  const auto score_or_zero = [&](int ox, int oy) {
    return std::max(std::abs(ox), std::abs(oy)) > search_half ? 0.0
                                                              : static_cast<double>(score(ox, oy));
  };
  const double b = best_score;
  out.dx_cells =
      predicted.ix + best.ix +
      ParabolaVertex(score_or_zero(best.ix - 1, best.iy), b, score_or_zero(best.ix + 1, best.iy));
  out.dy_cells =
      predicted.iy + best.iy +
      ParabolaVertex(score_or_zero(best.ix, best.iy - 1), b, score_or_zero(best.ix, best.iy + 1));
  out.measured = true;
  return out;
}

ClusterStageOutput ApplyClusterMotion(GridLayers& layers, const FilterLayerIds& ids,
                                      const MeasurementGrid& z, const ScanFlow& flow, double dt_s,
                                      double known_confidence,
                                      const ClusterMotionOptions& options) {
  const std::vector<std::size_t> hits_now = CountHitScans(z, layers.Values(ids.hit_scans));
  return ApplyClusterMotion(layers, ids, z, flow, dt_s, known_confidence, options, hits_now,
                            ClusterMotionMask(layers, ids, flow, options));
}

namespace {

// Whether the stage does anything this cycle: it needs a scan pair.
bool ClusterStageRuns(const ScanFlow& flow, const ClusterMotionOptions& options) {
  return options.enabled && flow.HasPair();
}

}  // namespace

std::vector<std::uint8_t> ClusterMotionMask(const GridLayers& layers, const FilterLayerIds& ids,
                                            const ScanFlow& flow,
                                            const ClusterMotionOptions& options) {
  if (!ClusterStageRuns(flow, options)) return {};
  return DynamicCellMask(layers, ids, RigidClusterOptions(options));
}

ClusterStageOutput ApplyClusterMotion(GridLayers& layers, const FilterLayerIds& ids,
                                      const MeasurementGrid& z, const ScanFlow& flow, double dt_s,
                                      double known_confidence, const ClusterMotionOptions& options,
                                      std::span<const std::size_t> hits_now,
                                      const std::vector<std::uint8_t>& dynamic) {
  const std::span<float> hit_scans = layers.Values(ids.hit_scans);
  ClusterStageOutput out;
  std::vector<MeasuredBody>& measured = out.measured;
  if (!ClusterStageRuns(flow, options)) return out;
  const GridObjectOptions cluster_options = RigidClusterOptions(options);
  std::vector<GridCluster> clusters = FindRigidClusters(layers, ids, dynamic, cluster_options);
  const ScrollingGridGeometry& g = layers.geometry();
  const std::span<float> occupancy = layers.Values(ids.occupancy);
  const std::span<float> vx = layers.Values(ids.velocity_x_mps);
  const std::span<float> vy = layers.Values(ids.velocity_y_mps);
  const std::span<float> confidence = layers.Values(ids.velocity_confidence);
  const std::span<float> seen = layers.Values(ids.seen);
  const double cells_per_mps = dt_s / g.cell_size_m();
  const WindowIndexer indexer(g);
  const auto local_of = [&](std::size_t storage) { return indexer.Local(storage); };
  const auto hit_now = [&](std::size_t storage) { return z.p_occupied[storage] > 0.5f; };
  // Storage order, across clusters: every cluster's cells first, so that no cluster takes
  // another's cells among its attached hits.
  std::vector<std::uint8_t> role(g.CellCount(), kFree);
  for (const GridCluster& cluster : clusters) {
    for (const std::size_t cell : cluster.cells) role[cell] = kMember;
  }
  std::vector<std::size_t> attached;
  std::vector<CellIndex> hits;
  for (const GridCluster& cluster : clusters) {
    // The cluster's predicted displacement (its cells' occupancy-weighted mean velocity).
    double weight = 0.0, mean_x = 0.0, mean_y = 0.0;
    for (const std::size_t cell : cluster.cells) {
      const auto o = static_cast<double>(occupancy[cell]);
      weight += o;
      mean_x += o * static_cast<double>(vx[cell]);
      mean_y += o * static_cast<double>(vy[cell]);
    }
    const double px = mean_x / weight * cells_per_mps;
    const double py = mean_y / weight * cells_per_mps;

    // H: its cells hit now, and the newly hit cells next to them, on the scan's outline (a body is
    // measured on the scans' outlines, scan_flow.h).
    attached.clear();
    hits.clear();
    bool seen_whole = false;  // some of its hits lie inside an area of hits
    const auto add_hit = [&](int x, int y) {
      if (OnOutline(z, indexer, x, y)) {
        hits.push_back({x, y});
      } else {
        seen_whole = true;
      }
    };
    for (const std::size_t cell : cluster.cells) {
      const CellIndex c = local_of(cell);
      if (hit_now(cell)) add_hit(c.ix, c.iy);
      for (int y = c.iy - options.attach_cells; y <= c.iy + options.attach_cells; ++y) {
        for (int x = c.ix - options.attach_cells; x <= c.ix + options.attach_cells; ++x) {
          if (x < 0 || y < 0 || x >= g.width() || y >= g.height()) continue;
          const std::size_t s = g.StorageIndexOfLocal({x, y});
          if (role[s] != kFree || !hit_now(s) || HitBefore(flow.short_pair(), {x, y})) continue;
          role[s] = kAttached;
          attached.push_back(s);
          add_hit(x, y);
        }
      }
    }

    // The baseline: the long pair for a body too slow to move whole cells in one cycle.
    const HitMaps* maps = &flow.short_pair();
    const HitMaps* outline_maps = &flow.short_outline_pair();  // what the measurement reads
    double per_cycle = 1.0;  // this cycle's share of the baseline
    int half = options.search_half_cells;
    const bool slow = std::max(std::abs(px), std::abs(py)) <
                      static_cast<double>(flow.options().long_lag_below_cells);
    const bool long_baseline = slow && flow.long_pair() != nullptr;
    if (long_baseline) {
      maps = flow.long_pair();
      outline_maps = flow.long_outline_pair();
      per_cycle = flow.long_lag_scale();
      half = 2 * options.search_half_cells;
    }
    const CellIndex predicted{static_cast<int>(std::lround(px / per_cycle)),
                              static_cast<int>(std::lround(py / per_cycle))};
    // A body seen whole that left free space behind it, unless its hits are one line along its
    // motion (a side sliding along itself leaves its rear seen through too). Not a lidar's
    // surfaces: for every body the catalogue and three other seeds of it read better and worse
    // by turns (docs/grid.md, "A body seen whole is measured by its outline").
    const bool left_free_space =
        seen_whole &&
        LeftFreeSpace(*maps, hits, predicted, flow.options().shortest_min_vacated_share) &&
        !SlidesAlongItsLine(hits, predicted.ix, predicted.iy);
    const ClusterMotion m =
        MeasureClusterMotion(*outline_maps, hits, predicted, half, options, left_free_space);
    if (!m.measured) continue;
    const double body_vx = m.dx_cells * per_cycle / cells_per_mps;
    const double body_vy = m.dy_cells * per_cycle / cells_per_mps;
    // A few hits over the long baseline find other bodies' older hits in its search
    // (ClusterMotionOptions::small_body_max_hits).
    if (long_baseline && static_cast<int>(hits.size()) < options.small_body_max_hits &&
        std::hypot(body_vx - px / cells_per_mps, body_vy - py / cells_per_mps) >
            options.small_body_max_change_mps) {
      continue;
    }
    const double moved_cells = std::hypot(m.dx_cells, m.dy_cells);  // over the baseline
    const bool moved = moved_cells >= 1.0;
    const bool born = options.births && moved_cells * per_cycle >= options.birth_min_cells;
    if (std::hypot(body_vx, body_vy) >= options.min_speed_mps) {
      measured.push_back({cluster.cells, body_vx, body_vy});
    }
    // A wall is hit where it stands for longer than a body takes to pass: for a body moving a
    // cell a cycle or more, longer than its extent along its motion takes it, two scans spare
    // (a 4.5 m car's side at 3 m/s covers a cell for 19 scans, over staying_min_hit_scans; a
    // walker is slower and the count alone holds).
    const bool fast = moved_cells * per_cycle >= 1.0;  // a cell a cycle or more
    std::optional<MotionExtent> extent;
    if (fast) extent = ExtentAlong(g, cluster.cells, m.dx_cells, m.dy_cells);
    double wall_scans = options.staying_min_hit_scans;
    if (options.staying_min_hit_scans > 0 && fast) {
      wall_scans = std::max(wall_scans,
                            (extent->front - extent->rear + 1.0) / (moved_cells * per_cycle) + 2.0);
    }
    const double b = options.blend;
    const auto blend_to_body = [&](std::size_t cell) {
      vx[cell] = static_cast<float>((1.0 - b) * static_cast<double>(vx[cell]) + b * body_vx);
      vy[cell] = static_cast<float>((1.0 - b) * static_cast<double>(vy[cell]) + b * body_vy);
    };
    for (const std::size_t cell : cluster.cells) {
      if (moved && hit_now(cell) && HitBefore(*maps, local_of(cell)) &&
          static_cast<double>(hit_scans[cell]) >= wall_scans) {
        continue;  // staying fits
      }
      blend_to_body(cell);
    }
    // A slow body's trailing side (ClusterMotionOptions::sides): a body whose own hits say how
    // it moves (not a line sliding along itself).
    if (options.sides && long_baseline && fast &&
        !SlidesAlongItsLine(hits, m.dx_cells, m.dy_cells)) {
      const double speed = std::hypot(body_vx, body_vy);
      for (const std::size_t cell :
           TrailingSide(g, cluster.cells, *extent, hit_now, hit_scans, wall_scans, options, role)) {
        const double ex = static_cast<double>(vx[cell]) - body_vx;
        const double ey = static_cast<double>(vy[cell]) - body_vy;
        if (std::hypot(ex, ey) <= options.side_min_disagreement * speed) continue;
        blend_to_body(cell);
        confidence[cell] = std::max(confidence[cell], static_cast<float>(known_confidence));
      }
    }
    for (const std::size_t cell : attached) {
      if (born) BearHit(cell, z, occupancy, seen);
      if (static_cast<double>(confidence[cell]) >= known_confidence) continue;
      vx[cell] = static_cast<float>(body_vx);
      vy[cell] = static_cast<float>(body_vy);
      confidence[cell] = static_cast<float>(known_confidence);
    }
  }
  if (options.still_bodies) {
    MoveStillBodies(g, z, hits_now, flow, role, dt_s, known_confidence, options, occupancy, seen,
                    vx, vy, confidence, measured);
  }
  for (GridCluster& cluster : clusters) out.clusters.push_back(std::move(cluster.cells));
  return out;
}

}  // namespace lookout::grid
