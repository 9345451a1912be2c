#include "lookout/grid/interaction_constraints.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace lookout::grid {
namespace {

DisplacementMoments MomentsOf(const Associations& a, std::size_t s) {
  const SearchWindow& w = a.window[s];
  const std::size_t first = a.first_entry[s];
  double sum = 0.0, mx = 0.0, my = 0.0, mxx = 0.0;
  w.ForEachDisplacement([&](std::size_t k, const CellIndex& d) {
    const double p = static_cast<double>(a.weight[first + k]);
    sum += p;
    mx += p * d.ix;
    my += p * d.iy;
    mxx += p * (d.ix * d.ix + d.iy * d.iy);
  });
  DisplacementMoments m;
  if (sum <= 0.0) return m;
  m.mean_x_cells = mx / sum;
  m.mean_y_cells = my / sum;
  const double total_var =
      mxx / sum - m.mean_x_cells * m.mean_x_cells - m.mean_y_cells * m.mean_y_cells;
  m.variance_cells2 = std::max(0.0, 0.5 * total_var);
  return m;
}

// The strength of source s's rigidity link in direction d in eq. 11: min(1, gain D(s, y)).
double LinkStrength(const Associations& a, const FilterOptions& options, std::size_t s,
                    std::size_t d) {
  return std::min(
      1.0, options.rigidity_link_gain * static_cast<double>(a.rigidity[s * kNeighbourCount + d]));
}

// exp(-delta^2 / (2 r^2)) for integer offsets delta = 0, 1, ...: every displacement is whole
// cells, so the rigidity kernel's 1-D factors are table reads (the same values as the exp).
std::vector<double> IntegerKernel(double r2, int max_offset) {
  std::vector<double> k(static_cast<std::size_t>(max_offset) + 1);
  for (int d = 0; d <= max_offset; ++d) {
    k[static_cast<std::size_t>(d)] = std::exp(-static_cast<double>(d) * d / (2.0 * r2));
  }
  return k;
}

double KernelAt(const std::vector<double>& k, int delta) {
  const auto a = static_cast<std::size_t>(std::abs(delta));
  return a < k.size() ? k[a] : 0.0;
}

// B_y(d) = sum_a' Pw_y(a') K(d - a') at a displacement d that is not one of y's window samples
// (y's window has another stride or centre than the cell's): summed directly over y's window,
// separably over its lattice (K is a product of two 1-D Gaussians), entry by entry over its
// dense core. Exact, as the blurred table is where it applies
// (FilterOptions::rigidity_exact_across_lattices).
double BlurAt(const SearchWindow& w, const float* p, const CellIndex& d,
              const std::vector<double>& kernel) {
  const int n = w.size();
  std::array<double, kMaxWindowSideCells> kx{}, ky{};
  for (int u = 0; u < n; ++u) {
    const int offset = w.stride * (u - w.half);
    kx[static_cast<std::size_t>(u)] = KernelAt(kernel, d.ix - (w.center.ix + offset));
    ky[static_cast<std::size_t>(u)] = KernelAt(kernel, d.iy - (w.center.iy + offset));
  }
  double sum = 0.0;
  for (int v = 0; v < n; ++v) {
    const double gy = ky[static_cast<std::size_t>(v)];
    if (gy == 0.0) continue;
    const float* row = p + static_cast<std::size_t>(v) * static_cast<std::size_t>(n);
    double row_sum = 0.0;
    for (int u = 0; u < n; ++u) {
      row_sum += static_cast<double>(row[u]) * kx[static_cast<std::size_t>(u)];
    }
    sum += gy * row_sum;
  }
  w.ForEachDenseOffset([&](std::size_t k, const CellIndex& o) {
    sum += static_cast<double>(p[k]) * KernelAt(kernel, d.ix - (w.center.ix + o.ix)) *
           KernelAt(kernel, d.iy - (w.center.iy + o.iy));
  });
  return sum;
}

// The lattice part of B_y: P (n x n, row-major) blurred by the table K (n x n, symmetric) along
// u, then along v, into out. N: the side where known at compile time, so that the loops unroll;
// 0: any side, n. The same sums in the same order either way.
template <std::size_t N>
void BlurLattice(const float* p, const double* kernel, std::size_t any_n, float* out) {
  const std::size_t n = N > 0 ? N : any_n;
  constexpr auto kMax = static_cast<std::size_t>(kMaxWindowSideCells);
  std::array<double, kMax * kMax> rows;
  std::array<double, kMax> column;
  // Both passes accumulate whole rows (the inner loops have no reduction and vectorise).
  for (std::size_t v = 0; v < n; ++v) {  // along u: rows(v, u) = sum_u2 P(v, u2) K(u2, u)
    double* row = &rows[v * n];
    for (std::size_t u = 0; u < n; ++u) row[u] = 0.0;
    for (std::size_t u2 = 0; u2 < n; ++u2) {
      const double pv = static_cast<double>(p[v * n + u2]);
      const double* k = &kernel[u2 * n];
      for (std::size_t u = 0; u < n; ++u) row[u] += pv * k[u];
    }
  }
  for (std::size_t v = 0; v < n; ++v) {  // along v: B(v, u) = sum_v2 K(v, v2) rows(v2, u)
    for (std::size_t u = 0; u < n; ++u) column[u] = 0.0;
    for (std::size_t v2 = 0; v2 < n; ++v2) {
      const double k = kernel[v * n + v2];
      for (std::size_t u = 0; u < n; ++u) column[u] += k * rows[v2 * n + u];
    }
    for (std::size_t u = 0; u < n; ++u) out[v * n + u] = static_cast<float>(column[u]);
  }
}

}  // namespace

RigidityBlur BlurForRigidity(const Associations& a, const WindowIndexer& indexer,
                             const FilterWorkspace& workspace, const FilterOptions& options) {
  // Each source's Pw blurred by the rigidity kernel on its own window lattice:
  // B_y(a) = sum_a' Pw(y moves by a') K(a - a'), separable (K is a product of two 1-D Gaussians),
  // O(M^3) per source. A linked neighbour whose window has the same lattice as the cell's enters
  // through B_y exactly; otherwise through its two moments (a Gaussian in place of its pmf), or,
  // with rigidity_exact_across_lattices, through B_y where the cell's displacement is one of y's
  // samples and BlurAt where it is not.
  RigidityBlur result;
  if (!options.enable_rigidity_constraint) return result;
  const bool exact = options.rigidity_exact_across_lattices;
  if (!exact) result.moments.resize(a.SourceCount());
  result.blurred.resize(a.EntryCount());
  const double r2 = options.rigidity_sigma_cells * options.rigidity_sigma_cells;
  // Offsets between two samples of windows up to 31 wide, stride 4, centred up to 64 cells apart.
  result.integer_kernel = IntegerKernel(r2, 4 * 64 + 4 * 31);
  const std::vector<double>& integer_kernel = result.integer_kernel;
  std::vector<DisplacementMoments>& moments = result.moments;
  std::vector<float>& blurred = result.blurred;
  // K(u, u2) = exp(-(stride (u - u2))^2 / (2 r^2)) as an n x n table per window shape (a fine
  // and a coarse one), built once before the loop, so both passes are plain dot products.
  // (Rebuilt inside the loop at each change of shape, they cost 78 tables of 49-169
  // exponentials a cycle on the junction: docs/PERFORMANCE.md, "Serial passes, load balance, page
  // faults".)
  struct KernelTable {
    std::size_t n;
    int stride;
    std::vector<double> k;
  };
  std::vector<KernelTable> tables;
  for (const SearchWindow& w : a.window) {
    const auto n = static_cast<std::size_t>(w.size());
    const bool known = std::any_of(tables.begin(), tables.end(), [&](const KernelTable& t) {
      return t.n == n && t.stride == w.stride;
    });
    if (known) continue;
    KernelTable& table = tables.emplace_back(KernelTable{n, w.stride, std::vector<double>(n * n)});
    for (std::size_t u = 0; u < n; ++u) {
      for (std::size_t u2 = 0; u2 < n; ++u2) {
        const double dist =
            static_cast<double>(w.stride) * (static_cast<double>(u) - static_cast<double>(u2));
        table.k[u * n + u2] = std::exp(-dist * dist / (2.0 * r2));
      }
    }
  }
  ParallelForBlocks(a.SourceCount(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      const SearchWindow& w = a.window[s];
      // Only what some cell's constraint reads (ApplyConstraints): s's B_y where a neighbour
      // with s's lattice links to it, its moments where one with another lattice does. Why: no
      // one links to most newly seen occupancy (37 of the junction's 85 wide windows, the
      // costliest blurs), and links across two lattices are few (124 of 824 sources read).
      bool blur_read = false, moments_read = false;
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        const std::uint32_t x = LinkedSource(a, indexer, workspace, s, d);
        if (x == FilterWorkspace::kNone ||
            LinkStrength(a, options, x, OppositeDirection(d)) <= 0.0) {
          continue;
        }
        const bool same_lattice = exact || a.window[x].SameEntries(w);
        blur_read = blur_read || same_lattice;
        moments_read = moments_read || !same_lattice;
      }
      if (moments_read) moments[s] = MomentsOf(a, s);
      if (!blur_read) continue;
      const auto n = static_cast<std::size_t>(w.size());
      const std::vector<double>& kernel =
          std::find_if(tables.begin(), tables.end(), [&](const KernelTable& t) {
            return t.n == n && t.stride == w.stride;
          })->k;
      const float* p = &a.weight[a.first_entry[s]];
      float* out = &blurred[a.first_entry[s]];
      // The default windows' sides (window_size_cells, new_window_size_cells) known at compile
      // time: the loops unroll (the blur 8.2% -> 4.7% of the update's samples on one thread).
      switch (n) {
        case 7:
          BlurLattice<7>(p, kernel.data(), n, out);
          break;
        case 13:
          BlurLattice<13>(p, kernel.data(), n, out);
          break;
        default:
          BlurLattice<0>(p, kernel.data(), n, out);
      }
      if (w.HasDenseCore()) {
        // The dense core: its entries blurred onto the lattice, and the whole window (lattice
        // and core) blurred onto each core entry, directly (a few entries).
        std::array<double, kMaxWindowSideCells> kx{}, ky{};
        w.ForEachDenseOffset([&](std::size_t q, const CellIndex& o) {
          const double pq = static_cast<double>(p[q]);
          if (pq == 0.0) return;
          for (std::size_t u = 0; u < n; ++u) {
            const int lu = w.stride * (static_cast<int>(u) - w.half);
            kx[u] = KernelAt(integer_kernel, lu - o.ix);
            ky[u] = KernelAt(integer_kernel, lu - o.iy);
          }
          for (std::size_t v = 0; v < n; ++v) {
            for (std::size_t u = 0; u < n; ++u) {
              out[v * n + u] += static_cast<float>(pq * ky[v] * kx[u]);
            }
          }
        });
        w.ForEachDenseOffset([&](std::size_t q, const CellIndex& o) {
          out[q] = static_cast<float>(
              BlurAt(w, p, CellIndex{w.center.ix + o.ix, w.center.iy + o.iy}, integer_kernel));
        });
      }
    }
  });
  return result;
}

void ApplyConstraints(const WindowIndexer& indexer, const TargetIndex& targets,
                      const FilterWorkspace& workspace, const FilterOptions& options,
                      const RigidityBlur& blur, Associations& a) {
  // In(i) per entry's target, gathered per target (each entry belongs to one target).
  // Read only at the entries whose target is in the window, each of which the gather writes: the
  // array is left unzeroed (make_unique_for_overwrite).
  const auto inflow_at_entry = std::make_unique_for_overwrite<float[]>(a.EntryCount());
  if (options.enable_no_convergence_constraint) {
    ParallelForBlocks(targets.targets.size(), 512, [&](std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t) {
        double inflow = 0.0;
        for (std::size_t n = targets.first[t]; n < targets.first[t + 1]; ++n) {
          const std::uint32_t e = targets.entries[n];
          inflow += static_cast<double>(a.weight[e]) *
                    static_cast<double>(a.occupancy[a.entry_source[e]]);
        }
        for (std::size_t n = targets.first[t]; n < targets.first[t + 1]; ++n) {
          inflow_at_entry[targets.entries[n]] = static_cast<float>(inflow);
        }
      }
    });
  }

  const bool exact = options.rigidity_exact_across_lattices;
  const double r2 = options.rigidity_sigma_cells * options.rigidity_sigma_cells;
  const std::vector<double>& integer_kernel = blur.integer_kernel;
  const double inv_two_nc_var =
      1.0 / (2.0 * options.no_convergence_sigma * options.no_convergence_sigma);
  std::vector<float> constrained(a.EntryCount());
  ParallelForBlocks(a.SourceCount(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    struct Link {
      double strength;
      const SearchWindow* window;  // y's
      const float* weight;         // Pw_y over y's window
      const float* blurred;        // B_y over y's window
      const DisplacementMoments* moments;  // y's
      bool same_lattice;                   // y's window has the cell's lattice
    };
    std::array<Link, kNeighbourCount> links;
    std::vector<double> factor;  // the window's P(j -> i) as its factors are applied
    for (std::size_t s = begin; s < end; ++s) {
      const SearchWindow& w = a.window[s];
      const std::size_t first = a.first_entry[s];
      const double o_j = static_cast<double>(a.occupancy[s]);
      std::size_t link_count = 0;
      if (options.enable_rigidity_constraint) {
        for (std::size_t d = 0; d < kNeighbourCount; ++d) {
          const double strength = LinkStrength(a, options, s, d);
          if (strength <= 0.0) continue;
          const std::uint32_t y = LinkedSource(a, indexer, workspace, s, d);
          if (y == FilterWorkspace::kNone) continue;
          const SearchWindow& wy = a.window[y];
          const bool same_lattice = wy.SameEntries(w);
          links[link_count++] = Link{strength,
                                     &wy,
                                     &a.weight[a.first_entry[y]],
                                     &blur.blurred[a.first_entry[y]],
                                     exact ? nullptr : &blur.moments[y],
                                     same_lattice};
        }
      }
      // A link through its moments: the Gaussian r^2 / var exp(-|d - mean|^2 / (2 var)) over
      // this window's lattice as a column factor times a row factor, 2n exponentials where one
      // per entry took 26,000 a cycle on the junction (docs/PERFORMANCE.md, "Serial passes,
      // load balance, page faults"); the dense core's few entries take theirs whole.
      struct Separable {
        double scale;
        std::array<double, kMaxWindowSideCells> column, row;
      };
      std::array<Separable, kNeighbourCount> separable;
      const int side = w.size();
      for (std::size_t l = 0; l < link_count; ++l) {
        if (links[l].same_lattice || exact) continue;
        const DisplacementMoments& m = *links[l].moments;
        const double var = r2 + m.variance_cells2;
        Separable& g = separable[l];
        g.scale = r2 / var;
        for (int u = 0; u < side; ++u) {
          const double offset = w.stride * (u - w.half);
          const double ex = w.center.ix + offset - m.mean_x_cells;
          const double ey = w.center.iy + offset - m.mean_y_cells;
          g.column[static_cast<std::size_t>(u)] = std::exp(-ex * ex / (2.0 * var));
          g.row[static_cast<std::size_t>(u)] = std::exp(-ey * ey / (2.0 * var));
        }
      }
      // Factor by factor over the whole window, each pass a loop without a branch (the links'
      // kinds tested once a link, not once an entry: the pass vectorises). Each entry takes its
      // factors in the same order as the product of eq. 11 for it alone, so the values are the
      // same. Entry k in ForEachDisplacement's order: the lattice row by row, then the dense core.
      const std::size_t count = w.EntryCount();
      factor.resize(count);
      double* p = factor.data();
      for (std::size_t k = 0; k < count; ++k) p[k] = static_cast<double>(a.weight[first + k]);
      if (options.enable_no_convergence_constraint) {
        for (std::size_t k = 0; k < count; ++k) {
          const std::size_t e = first + k;
          if (a.target[e] == kOutsideWindow) continue;
          const double others = static_cast<double>(inflow_at_entry[e]) - p[k] * o_j;
          const double excess = others + o_j - 1.0;
          if (excess > 0.0) p[k] *= std::exp(-excess * excess * inv_two_nc_var);
        }
      }
      for (std::size_t l = 0; l < link_count; ++l) {
        const Link& link = links[l];
        const double keep = 1.0 - link.strength;
        const double strength = link.strength;
        if (link.same_lattice) {
          for (std::size_t k = 0; k < count; ++k) {
            p[k] *= keep + strength * static_cast<double>(link.blurred[k]);
          }
        } else if (exact) {
          w.ForEachDisplacement([&](std::size_t k, const CellIndex& d) {
            const std::int64_t ky = link.window->EntryOf(d);
            const double agree =
                ky >= 0 ? static_cast<double>(link.blurred[static_cast<std::size_t>(ky)])
                        : BlurAt(*link.window, link.weight, d, integer_kernel);
            p[k] *= keep + strength * agree;
          });
        } else {
          const Separable& g = separable[l];
          const auto n = static_cast<std::size_t>(side);
          for (std::size_t v = 0; v < n; ++v) {
            double* row = p + v * n;
            const double gy = g.row[v];
            for (std::size_t u = 0; u < n; ++u) {
              row[u] *= keep + strength * (g.scale * g.column[u] * gy);
            }
          }
          w.ForEachDenseOffset([&](std::size_t k, const CellIndex& o) {
            const double var = r2 + link.moments->variance_cells2;
            const double ex = w.center.ix + o.ix - link.moments->mean_x_cells;
            const double ey = w.center.iy + o.iy - link.moments->mean_y_cells;
            p[k] *= keep + strength * (r2 / var * std::exp(-(ex * ex + ey * ey) / (2.0 * var)));
          });
        }
      }
      double sum = 0.0;
      for (std::size_t k = 0; k < count; ++k) sum += p[k];
      if (sum <= 0.0) {  // every move forbidden (underflow): keep Pw
        for (std::size_t k = 0; k < count; ++k) constrained[first + k] = a.weight[first + k];
        continue;
      }
      // Each factor product rounded to the layers' float, then normalised (in one pass: the
      // same values as storing the product first).
      const double inv_sum = 1.0 / sum;
      for (std::size_t k = 0; k < count; ++k) {
        constrained[first + k] =
            static_cast<float>(static_cast<double>(static_cast<float>(p[k])) * inv_sum);
      }
    }
  });
  a.weight.swap(constrained);
}

}  // namespace lookout::grid
