#include "lookout/grid/hidden_bodies.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "lookout/core/input_error.h"
#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/filter_state.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::grid {
namespace {

// The global cell of a body's cell at the body's current anchor, shifted by (dx, dy) cells.
CellIndex GlobalCellOf(const HiddenBody& body, const HiddenBody::Cell& cell, int dx = 0,
                       int dy = 0) {
  return {static_cast<int>(std::lround(body.anchor_x_cells)) + cell.offset.ix + dx,
          static_cast<int>(std::lround(body.anchor_y_cells)) + cell.offset.iy + dy};
}

// What the scan says of a body's cells, shifted by (dx, dy) cells from where they are.
struct BodyView {
  int in_window = 0;
  int unobserved = 0;
  int free = 0;
};

BodyView ViewOf(const HiddenBody& body, const ScrollingGridGeometry& g, const MeasurementGrid& z,
                int dx = 0, int dy = 0) {
  BodyView v;
  for (const HiddenBody::Cell& cell : body.cells) {
    const CellIndex c = GlobalCellOf(body, cell, dx, dy);
    if (!g.Contains(c)) continue;
    ++v.in_window;
    const float p = z.p_occupied[g.StorageIndex(c)];
    if (!Observed(p)) {
      ++v.unobserved;
    } else if (p < kUnknownProbability) {
      ++v.free;
    }
  }
  return v;
}

// Step 1's negative information: among the shifts within +-shift_cells, the one with the fewest
// cells seen free (ties: the shortest, then the first in row order) moves the body; its view.
BodyView PlaceWhereNotSeenFree(HiddenBody& body, const ScrollingGridGeometry& g,
                               const MeasurementGrid& z, int shift_cells) {
  BodyView best = ViewOf(body, g, z);
  if (best.free == 0) return best;
  int best_dx = 0, best_dy = 0;
  for (int dy = -shift_cells; dy <= shift_cells; ++dy) {
    for (int dx = -shift_cells; dx <= shift_cells; ++dx) {
      const BodyView v = ViewOf(body, g, z, dx, dy);
      const int length2 = dx * dx + dy * dy;
      const int best_length2 = best_dx * best_dx + best_dy * best_dy;
      if (v.free < best.free || (v.free == best.free && length2 < best_length2)) {
        best = v;
        best_dx = dx;
        best_dy = dy;
      }
    }
  }
  body.anchor_x_cells += best_dx;
  body.anchor_y_cells += best_dy;
  return best;
}

// The body of `cells` (storage indices) anchored at its first cell, occupancies from
// `occupancy`; no velocity yet.
HiddenBody BodyOf(std::span<const std::size_t> cells, const ScrollingGridGeometry& g,
                  std::span<const float> occupancy) {
  HiddenBody body;
  const CellIndex anchor = g.GlobalFromStorage(cells.front());
  body.anchor_x_cells = anchor.ix;
  body.anchor_y_cells = anchor.iy;
  for (const std::size_t s : cells) {
    const CellIndex c = g.GlobalFromStorage(s);
    body.cells.push_back({{c.ix - anchor.ix, c.iy - anchor.iy}, occupancy[s]});
  }
  return body;
}

void Carry(HiddenBody& body, double dt_s, double cells_per_m) {
  body.anchor_x_cells += body.velocity_x_mps * dt_s * cells_per_m;
  body.anchor_y_cells += body.velocity_y_mps * dt_s * cells_per_m;
  body.hidden_s += dt_s;
}

// Sets of cells as sorted storage indices: a few hundred cells a cycle, where a mask over the
// window would clear 160,000 (the stage's first form cost 0.3 ms more a cycle in `lookout bench`).
using CellSet = std::vector<std::size_t>;

CellSet MeasuredCells(const std::vector<MeasuredBody>& measured) {
  CellSet cells;
  for (const MeasuredBody& m : measured) cells.insert(cells.end(), m.cells.begin(), m.cells.end());
  std::sort(cells.begin(), cells.end());
  return cells;
}

CellSet CellsOf(std::span<const HiddenBody> bodies, const ScrollingGridGeometry& g) {
  CellSet cells;
  for (const HiddenBody& body : bodies) {
    for (const HiddenBody::Cell& cell : body.cells) {
      const CellIndex c = GlobalCellOf(body, cell);
      if (g.Contains(c)) cells.push_back(g.StorageIndex(c));
    }
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

bool In(const CellSet& set, std::size_t s) { return std::binary_search(set.begin(), set.end(), s); }

bool Intersect(const CellSet& a, const CellSet& b) {
  for (auto i = a.begin(), j = b.begin(); i != a.end() && j != b.end();) {
    if (*i == *j) return true;
    if (*i < *j) {
      ++i;
    } else {
      ++j;
    }
  }
  return false;
}

bool Overlaps(const HiddenBody& body, const ScrollingGridGeometry& g, const CellSet& set) {
  return std::any_of(body.cells.begin(), body.cells.end(), [&](const HiddenBody::Cell& cell) {
    const CellIndex c = GlobalCellOf(body, cell);
    return g.Contains(c) && In(set, g.StorageIndex(c));
  });
}

bool Forgotten(const HiddenBody& body, const BodyView& view, const HiddenBodyOptions& options) {
  if (body.hidden_s > options.max_hidden_s || view.in_window == 0) return true;
  if (view.unobserved == 0) return true;  // seen whole again: the filter holds it
  return view.free >= options.drop_free_share * view.in_window;
}

// How many of the confirmed movers measured within confirm_s overlap each cluster.
std::vector<int> MeasurementsOf(const std::vector<std::vector<std::size_t>>& clusters,
                                const std::vector<HiddenBody>& confirmed,
                                const ScrollingGridGeometry& g, double confirm_s) {
  std::vector<std::pair<std::size_t, std::size_t>> cluster_of;  // (cell, cluster), sorted
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    for (const std::size_t s : clusters[k]) cluster_of.emplace_back(s, k);
  }
  std::sort(cluster_of.begin(), cluster_of.end());
  std::vector<int> count(clusters.size(), 0);
  std::vector<std::size_t> counted_for(clusters.size(), confirmed.size());  // none yet
  for (std::size_t r = 0; r < confirmed.size(); ++r) {
    if (confirmed[r].hidden_s > confirm_s) continue;
    for (const HiddenBody::Cell& cell : confirmed[r].cells) {
      const CellIndex c = GlobalCellOf(confirmed[r], cell);
      if (!g.Contains(c)) continue;
      const std::size_t s = g.StorageIndex(c);
      const auto it =
          std::lower_bound(cluster_of.begin(), cluster_of.end(), std::pair{s, std::size_t{0}});
      if (it == cluster_of.end() || it->first != s) continue;
      const std::size_t ku = it->second;
      if (counted_for[ku] == r) continue;
      counted_for[ku] = r;
      ++count[ku];
    }
  }
  return count;
}

// Step 3 for one body: its occupancy, velocity and confidence into its cells the scan does not
// observe and where it says more than the filter, but for walls' places and the never observed.
void WriteBody(const HiddenBody& body, GridLayers& layers, const FilterLayerIds& ids,
               const MeasurementGrid& z, int staying_min_hit_scans) {
  const ScrollingGridGeometry& g = layers.geometry();
  const std::span<float> occupancy = layers.Values(ids.occupancy);
  const std::span<const float> hit_scans = layers.Values(ids.hit_scans);
  for (const HiddenBody::Cell& cell : body.cells) {
    const CellIndex c = GlobalCellOf(body, cell);
    if (!g.Contains(c)) continue;
    const std::size_t s = g.StorageIndex(c);
    if (Observed(z.p_occupied[s]) || occupancy[s] >= cell.occupancy ||
        occupancy[s] == kUnknownProbability ||
        hit_scans[s] >= static_cast<float>(staying_min_hit_scans)) {
      continue;
    }
    occupancy[s] = cell.occupancy;
    layers.Values(ids.velocity_x_mps)[s] = static_cast<float>(body.velocity_x_mps);
    layers.Values(ids.velocity_y_mps)[s] = static_cast<float>(body.velocity_y_mps);
    layers.Values(ids.velocity_confidence)[s] = static_cast<float>(body.confidence);
    layers.Values(ids.seen)[s] = 1.0f;
  }
}

// Step 4's body of a cluster: its cells and occupancy, its occupancy-weighted mean velocity and
// confidence.
HiddenBody BodyOfCluster(std::span<const std::size_t> cluster, const GridLayers& layers,
                         const FilterLayerIds& ids) {
  const std::span<const float> occupancy = layers.Values(ids.occupancy);
  HiddenBody body = BodyOf(cluster, layers.geometry(), occupancy);
  double weight = 0.0;
  for (const std::size_t s : cluster) {
    const auto o = static_cast<double>(occupancy[s]);
    weight += o;
    body.velocity_x_mps += o * static_cast<double>(layers.Values(ids.velocity_x_mps)[s]);
    body.velocity_y_mps += o * static_cast<double>(layers.Values(ids.velocity_y_mps)[s]);
    body.confidence += o * static_cast<double>(layers.Values(ids.velocity_confidence)[s]);
  }
  body.velocity_x_mps /= weight;
  body.velocity_y_mps /= weight;
  body.confidence /= weight;
  return body;
}

// Step 5: the movers lost before their shadow. A mover that leaves the field of view or goes
// behind an occluder within a cycle or two (a car at 30 m/s relative to the ego) is gone from the
// rigid clusters before half of one is unobserved: eq. 8 spreads its unobserved cells under the
// clusters' occupancy at once; a far walker that a nearer one starts to cover drops under the
// clusters' three cells while half in view, and reaches the shadow some cycles later. Its
// measurements are where it was: the newest, measured within lost_memory_s, and those
// overlapping it measured within confirm_s before it, if at least confirm_min_measurements.
// Carried at their mean velocity (a car's measurements scatter by +-0.7 m/s; their mean is within
// 0.1 of the truth on fast-car), it is where a body without new evidence would be. Each group is
// looked at once, newest first; a group remembered leaves the confirmed movers.
void RememberLostMovers(std::vector<HiddenBody>& confirmed, std::vector<HiddenBody>& bodies,
                        const ScrollingGridGeometry& g, const MeasurementGrid& z,
                        const CellSet& measured_now, const HiddenBodyOptions& options) {
  std::vector<CellSet> cells(confirmed.size());
  for (std::size_t r = 0; r < confirmed.size(); ++r) {
    cells[r] = CellsOf(std::span(&confirmed[r], 1), g);
  }
  std::vector<std::size_t> newest_first(confirmed.size());
  std::iota(newest_first.begin(), newest_first.end(), std::size_t{0});
  std::stable_sort(newest_first.begin(), newest_first.end(), [&](std::size_t a, std::size_t b) {
    return confirmed[a].hidden_s < confirmed[b].hidden_s;
  });
  const CellSet covered = CellsOf(bodies, g);
  std::vector<bool> looked_at(confirmed.size(), false);
  std::vector<bool> remembered(confirmed.size(), false);
  for (const std::size_t r : newest_first) {
    const HiddenBody& newest = confirmed[r];
    if (looked_at[r] || newest.hidden_s > options.lost_memory_s) continue;
    std::vector<std::size_t> group;
    for (std::size_t q = 0; q < confirmed.size(); ++q) {
      if (!looked_at[q] && confirmed[q].hidden_s - newest.hidden_s <= options.confirm_s &&
          (q == r || Intersect(cells[r], cells[q]))) {
        group.push_back(q);
        looked_at[q] = true;
      }
    }
    const BodyView view = ViewOf(newest, g, z);
    const bool hidden =
        view.in_window > 0 &&
        view.unobserved >= options.min_hidden_share * static_cast<double>(view.in_window);
    if (static_cast<int>(group.size()) < options.confirm_min_measurements || !hidden ||
        Intersect(cells[r], measured_now) || Intersect(cells[r], covered)) {
      continue;
    }
    HiddenBody body = newest;
    body.velocity_x_mps = 0.0;
    body.velocity_y_mps = 0.0;
    const auto n = static_cast<double>(group.size());
    for (const std::size_t q : group) {
      body.velocity_x_mps += confirmed[q].velocity_x_mps / n;
      body.velocity_y_mps += confirmed[q].velocity_y_mps / n;
      remembered[q] = true;
    }
    bodies.push_back(std::move(body));
  }
  std::vector<HiddenBody> left;
  for (std::size_t q = 0; q < confirmed.size(); ++q) {
    if (!remembered[q]) left.push_back(std::move(confirmed[q]));
  }
  confirmed = std::move(left);
}

}  // namespace

void HiddenBodyOptions::Validate(const std::string& source) const {
  const auto require = [&source](bool ok, const char* field, const char* problem) {
    if (!ok) {
      throw InputError(source, 0, std::string("grid.filter.hidden_bodies.") + field, problem);
    }
  };
  const auto share = [](double v) { return v >= 0.0 && v <= 1.0; };  // NaN: false
  require(share(min_hidden_share), "min_hidden_share", "must be in [0, 1]");
  require(std::isfinite(max_hidden_s) && max_hidden_s >= 0.0, "max_hidden_s",
          "must be finite and >= 0");
  require(share(drop_free_share), "drop_free_share", "must be in [0, 1]");
  require(std::isfinite(confirm_s) && confirm_s >= 0.0, "confirm_s", "must be finite and >= 0");
  require(confirm_min_measurements >= 1, "confirm_min_measurements", "must be >= 1");
  require(std::isfinite(lost_memory_s) && lost_memory_s >= 0.0, "lost_memory_s",
          "must be finite and >= 0");
  require(shift_cells >= 0 && shift_cells <= 4, "shift_cells", "must be in [0, 4]");
}

void HiddenBodies::Update(GridLayers& layers, const FilterLayerIds& ids, const MeasurementGrid& z,
                          double dt_s, const ClusterStageOutput& found, int staying_min_hit_scans,
                          const HiddenBodyOptions& options) {
  if (!options.enabled) {
    bodies_.clear();
    confirmed_.clear();
    return;
  }
  const ScrollingGridGeometry& g = layers.geometry();
  const double cells_per_m = 1.0 / g.cell_size_m();
  const CellSet measured_now = MeasuredCells(found.measured);

  // 1-3: carry, forget, write.
  std::vector<HiddenBody> kept;
  kept.reserve(bodies_.size());
  for (HiddenBody& body : bodies_) {
    Carry(body, dt_s, cells_per_m);
    const BodyView view = PlaceWhereNotSeenFree(body, g, z, options.shift_cells);
    if (Forgotten(body, view, options) || Overlaps(body, g, measured_now)) continue;
    WriteBody(body, layers, ids, z, staying_min_hit_scans);
    kept.push_back(std::move(body));
  }
  bodies_ = std::move(kept);

  // The confirmed movers: carried, aged out, and this cycle's added. Kept as long as step 5 may
  // look at a newest measurement (lost_memory_s) and count confirm_s of measurements before it
  // (step 4 counts confirm_s of them).
  const double memory_s = options.lost_memory_s + options.confirm_s;
  std::erase_if(confirmed_, [&](HiddenBody& body) {
    Carry(body, dt_s, cells_per_m);
    return body.hidden_s > memory_s;
  });
  for (const MeasuredBody& m : found.measured) {
    if (m.cells.empty()) continue;
    HiddenBody& body = confirmed_.emplace_back(BodyOfCluster(m.cells, layers, ids));
    body.velocity_x_mps = m.velocity_x_mps;
    body.velocity_y_mps = m.velocity_y_mps;
  }

  // 4: remember the clusters going into a shadow.
  const CellSet covered = CellsOf(bodies_, g);
  const std::vector<int> measurements =
      MeasurementsOf(found.clusters, confirmed_, g, options.confirm_s);
  for (std::size_t k = 0; k < found.clusters.size(); ++k) {
    const std::vector<std::size_t>& cluster = found.clusters[k];
    if (measurements[k] < options.confirm_min_measurements) continue;
    int unobserved = 0;
    bool taken = false;
    for (const std::size_t s : cluster) {
      if (!Observed(z.p_occupied[s])) ++unobserved;
      taken = taken || In(covered, s);
    }
    if (taken || unobserved < options.min_hidden_share * static_cast<double>(cluster.size())) {
      continue;
    }
    bodies_.push_back(BodyOfCluster(cluster, layers, ids));
  }

  // 5: remember the movers lost before their shadow.
  RememberLostMovers(confirmed_, bodies_, g, z, measured_now, options);
}

std::vector<std::uint8_t> HiddenBodyMask(const HiddenBodies& bodies,
                                         const ScrollingGridGeometry& geometry) {
  const GridGeometry window = geometry.WindowGeometry();
  std::vector<std::uint8_t> mask(geometry.CellCount(), 0);
  for (const HiddenBody& body : bodies.bodies()) {
    for (const HiddenBody::Cell& cell : body.cells) {
      const CellIndex c = GlobalCellOf(body, cell);
      if (!geometry.Contains(c)) continue;
      mask[static_cast<std::size_t>(window.LinearIndex(geometry.LocalFromGlobal(c)))] = 1;
    }
  }
  return mask;
}

}  // namespace lookout::grid
