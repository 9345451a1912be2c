#include "lookout/grid/rigidity_update.h"

#include <Eigen/Core>

#include <array>

namespace lookout::grid {

std::vector<float> ComputeRigidityLinks(const Associations& a, const WindowIndexer& indexer,
                                        const FilterWorkspace& workspace) {
  std::vector<float> links(a.SourceCount() * kNeighbourCount, 0.0f);
  constexpr std::size_t kHalf = kNeighbourCount / 2;  // d and d + kHalf are opposite
  ParallelForBlocks(a.SourceCount(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t x = begin; x < end; ++x) {
      const SearchWindow& wx = a.window[x];
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        const std::uint32_t y = LinkedSource(a, indexer, workspace, x, d);
        if (y == FilterWorkspace::kNone) continue;
        const SearchWindow& wy = a.window[y];
        double overlap = 0.0;
        const float* px = &a.weight[a.first_entry[x]];
        const float* py = &a.weight[a.first_entry[y]];
        if (wy.SameEntries(wx)) {
          // One lattice (most neighbours of one body): entry k is the same displacement in both,
          // and the sum is symmetric term by term: y's link back to x, the same value, is
          // copied below rather than summed again.
          if (d >= kHalf) continue;
          for (std::size_t k = 0; k < wx.EntryCount(); ++k) {
            overlap += static_cast<double>(px[k]) * static_cast<double>(py[k]);
          }
          links[x * kNeighbourCount + d] = static_cast<float>(overlap);
          continue;
        }
        if (!wx.HasDenseCore() && !wy.HasDenseCore()) {
          // Two lattices: x's displacement (column u, row v) is y's entry (row_of[v],
          // column_of[u]) when each axis falls on y's lattice; found once an axis, not by
          // EntryOf's two divisions an entry. The same terms in the same order.
          std::array<int, kMaxWindowSideCells> column_of, row_of;
          const int n = wx.size();
          for (int u = 0; u < n; ++u) {
            const int offset = wx.stride * (u - wx.half);
            column_of[static_cast<std::size_t>(u)] =
                wy.LatticeIndex(wx.center.ix + offset - wy.center.ix);
            row_of[static_cast<std::size_t>(u)] =
                wy.LatticeIndex(wx.center.iy + offset - wy.center.iy);
          }
          const auto ny = static_cast<std::size_t>(wy.size());
          for (int v = 0; v < n; ++v) {
            const int vy = row_of[static_cast<std::size_t>(v)];
            if (vy < 0) continue;
            for (int u = 0; u < n; ++u) {
              const int uy = column_of[static_cast<std::size_t>(u)];
              if (uy < 0) continue;
              overlap += static_cast<double>(px[static_cast<std::size_t>(v * n + u)]) *
                         static_cast<double>(
                             py[static_cast<std::size_t>(vy) * ny + static_cast<std::size_t>(uy)]);
            }
          }
        } else {
          wx.ForEachDisplacement([&](std::size_t k, const CellIndex& disp) {
            const std::int64_t ky = wy.EntryOf(disp);
            if (ky < 0) return;
            overlap +=
                static_cast<double>(px[k]) * static_cast<double>(py[static_cast<std::size_t>(ky)]);
          });
        }
        links[x * kNeighbourCount + d] = static_cast<float>(overlap);
      }
    }
  });
  ParallelForBlocks(a.SourceCount(), kSourceBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t x = begin; x < end; ++x) {
      for (std::size_t d = kHalf; d < kNeighbourCount; ++d) {
        const std::uint32_t y = LinkedSource(a, indexer, workspace, x, d);
        if (y == FilterWorkspace::kNone || !a.window[y].SameEntries(a.window[x])) continue;
        links[x * kNeighbourCount + d] = links[y * kNeighbourCount + OppositeDirection(d)];
      }
    }
  });
  return links;
}

void UpdateRigidity(const Associations& a, const TargetIndex& targets,
                    std::span<const UpdateCell> cells, const WindowIndexer& indexer,
                    const FilterWorkspace& workspace,
                    const std::array<std::span<float>, kNeighbourCount>& rigidity) {
  const std::vector<float> links = ComputeRigidityLinks(a, indexer, workspace);
  // A source's eight links as doubles, in one Eigen array: the gather's eight products and the
  // eight quotients are then four vector operations each (element-wise: the same values; written
  // as scalar loops, the compiler left them scalar).
  using Links = Eigen::Array<double, kNeighbourCount, 1>;
  std::vector<Links> wide_links(a.SourceCount());
  for (std::size_t s = 0; s < a.SourceCount(); ++s) {
    for (std::size_t d = 0; d < kNeighbourCount; ++d) {
      wide_links[s](static_cast<Eigen::Index>(d)) =
          static_cast<double>(links[s * kNeighbourCount + d]);
    }
  }
  std::array<float*, kNeighbourCount> out;
  for (std::size_t d = 0; d < kNeighbourCount; ++d) out[d] = rigidity[d].data();
  ParallelForBlocks(cells.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t u = begin; u < end; ++u) {
      const UpdateCell& c = cells[u];
      Links carried = Links::Zero();
      double sum = 0.0;
      if (c.target_slot != FilterWorkspace::kNone) {
        sum = GatherWeighted(
            a, targets, c.target_slot,
            [&](std::uint32_t, std::uint32_t s, double w) { carried += w * wide_links[s]; });
      }
      if (sum <= 0.0) {
        if (c.source != FilterWorkspace::kNone) {
          for (std::size_t d = 0; d < kNeighbourCount; ++d) out[d][c.cell] = 0.0f;
        }
        continue;
      }
      carried /= sum;
      for (std::size_t d = 0; d < kNeighbourCount; ++d) {
        out[d][c.cell] = static_cast<float>(carried(static_cast<Eigen::Index>(d)));
      }
    }
  });
}

}  // namespace lookout::grid
