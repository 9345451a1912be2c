#pragma once

// Internal to the assignment module: one step of the shortest augmenting path method
// (Jonker and Volgenant 1987; Crouse 2016, "On implementing 2D rectangular assignment
// algorithms", algorithm 1 without the initialisation heuristics). The state - duals and
// matching - is kept between steps, so that SolveLinearAssignment adds the rows one by one
// and Murty's method re-solves a child problem from its parent's state with a single step:
// forbidding entries or fixing pairs keeps the parent's duals feasible (Miller, Stone and
// Cox, "Optimizing Murty's ranked assignment method", IEEE TAES 33(3), 1997).
//
// `Cost` needs +, - and <: double, or the lexicographic cost of linear_assignment.cc.

#include <cstddef>
#include <utility>
#include <vector>

namespace lookout::assignment::internal {

inline constexpr int kNone = -1;

template <typename Cost>
struct AugmentingState {
  std::vector<Cost> u;  // row duals
  std::vector<Cost> v;  // column duals
  std::vector<int> column_of_row;
  std::vector<int> row_of_column;

  AugmentingState(std::size_t rows, std::size_t cols)
      : u(rows), v(cols), column_of_row(rows, kNone), row_of_column(cols, kNone) {}
};

// Scratch space of AugmentRow, reused between calls to spare allocations.
template <typename Cost>
struct AugmentingWorkspace {
  std::vector<Cost> shortest;
  std::vector<int> path;
  std::vector<int> remaining;
  std::vector<char> reached;  // shortest[j] holds a path cost
  std::vector<char> row_visited;
  std::vector<char> column_visited;
};

// Adds the unassigned `row` to the matching by the shortest alternating path, in reduced
// costs c(i, j) - u(i) - v(j), to a free column, then updates the duals so that reduced costs
// stay >= 0 and are 0 on the matching (Crouse eq. 14-15). `entry(i, j, &c)` returns false
// for a forbidden entry. Returns false, changing nothing, when no path reaches a free column.
// Precondition: the state's duals are feasible for `entry`.
template <typename Cost, typename Entry>
bool AugmentRow(int row, const Entry& entry, AugmentingState<Cost>& s,
                AugmentingWorkspace<Cost>& w) {
  const std::size_t n = s.u.size();
  const std::size_t m = s.v.size();
  w.shortest.assign(m, Cost{});
  w.path.assign(m, kNone);
  w.reached.assign(m, 0);
  w.row_visited.assign(n, 0);
  w.column_visited.assign(m, 0);
  // Columns not yet on the tree, in reverse so that ties go to the lowest column index.
  w.remaining.resize(m);
  for (std::size_t k = 0; k < m; ++k) w.remaining[k] = static_cast<int>(m - 1 - k);
  std::size_t remaining_count = m;

  int i = row;
  int sink = kNone;
  Cost min_value{};
  while (sink == kNone) {
    const auto ui = static_cast<std::size_t>(i);
    w.row_visited[ui] = 1;
    bool found = false;
    std::size_t lowest_at = 0;
    for (std::size_t k = 0; k < remaining_count; ++k) {
      const auto j = static_cast<std::size_t>(w.remaining[k]);
      Cost c;
      if (entry(i, static_cast<int>(j), &c)) {
        const Cost reduced = min_value + c - s.u[ui] - s.v[j];
        if (!w.reached[j] || reduced < w.shortest[j]) {
          w.path[j] = i;
          w.shortest[j] = reduced;
          w.reached[j] = 1;
        }
      }
      if (!w.reached[j]) continue;
      const std::size_t best = static_cast<std::size_t>(w.remaining[lowest_at]);
      // On a tie prefer a free column: the path ends there (Crouse's speed-up).
      if (!found || w.shortest[j] < w.shortest[best] ||
          (!(w.shortest[best] < w.shortest[j]) && s.row_of_column[j] == kNone)) {
        found = true;
        lowest_at = k;
      }
    }
    if (!found) return false;  // the duals were not touched yet
    const auto j = static_cast<std::size_t>(w.remaining[lowest_at]);
    min_value = w.shortest[j];
    w.column_visited[j] = 1;
    w.remaining[lowest_at] = w.remaining[--remaining_count];
    if (s.row_of_column[j] == kNone) {
      sink = static_cast<int>(j);
    } else {
      i = s.row_of_column[j];
    }
  }

  const auto urow = static_cast<std::size_t>(row);
  s.u[urow] = s.u[urow] + min_value;
  for (std::size_t r = 0; r < n; ++r) {
    if (w.row_visited[r] && r != urow) {
      const auto matched = static_cast<std::size_t>(s.column_of_row[r]);
      s.u[r] = s.u[r] + min_value - w.shortest[matched];
    }
  }
  for (std::size_t c = 0; c < m; ++c) {
    if (w.column_visited[c]) s.v[c] = s.v[c] - (min_value - w.shortest[c]);
  }

  // Augment along the path back from the sink.
  int j = sink;
  while (true) {
    const int r = w.path[static_cast<std::size_t>(j)];
    s.row_of_column[static_cast<std::size_t>(j)] = r;
    std::swap(s.column_of_row[static_cast<std::size_t>(r)], j);
    if (r == row) break;
  }
  return true;
}

}  // namespace lookout::assignment::internal
