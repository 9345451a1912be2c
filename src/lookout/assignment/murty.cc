#include "lookout/assignment/murty.h"

#include <cmath>
#include <cstdint>
#include <queue>
#include <utility>

#include "lookout/assignment/augmenting_path.h"

namespace lookout::assignment {
namespace {

using State = internal::AugmentingState<double>;
using Workspace = internal::AugmentingWorkspace<double>;
using internal::kNone;

// The problem made square: rows < columns get one dummy row per spare column, free to take
// any column at cost 0. In a square problem every column ends up matched, so the duals of the
// parent stay optimal for a child whose matching lost one pair (a freed column of a
// rectangular problem could keep a negative dual and be passed over). Dummy rows never
// take part in the partitions, so each real assignment still comes out once.
struct Problem {
  const Eigen::MatrixXd& cost;
  int real_rows = 0;
  int size = 0;  // rows and columns of the square problem
};

// A subset of the solution space: the assignments that keep every forced pair and use no
// forbidden one, with its best assignment and the duals that prove it optimal.
struct Node {
  State state;
  double cost = 0.0;                           // of the real rows
  std::vector<int> forced_column;              // per real row, kNone when free
  std::vector<std::pair<int, int>> forbidden;  // (row, column) pairs
  std::uint64_t sequence = 0;                  // creation order, to break ties between equal costs
};

struct CostlierFirst {
  bool operator()(const Node& a, const Node& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    return a.sequence > b.sequence;
  }
};

// Whether (i, j) may be used in `node`'s subset, and at what cost. `forbidden_mask` (size x
// size, row-major) marks the node's forbidden pairs: a lookup in the inner loop, where the
// node's short list would be searched.
bool Entry(const Problem& p, const Node& node, const std::vector<int>& forced_row_of_column,
           const std::vector<char>& forbidden_mask, int i, int j, double* c) {
  const auto ui = static_cast<std::size_t>(i);
  const auto uj = static_cast<std::size_t>(j);
  if (forbidden_mask[ui * static_cast<std::size_t>(p.size) + uj]) return false;
  if (i < p.real_rows && node.forced_column[ui] != kNone) {
    if (node.forced_column[ui] != j) return false;
  } else if (forced_row_of_column[uj] != kNone) {
    return false;  // kept for another row
  }
  if (i >= p.real_rows) {
    *c = 0.0;
    return true;
  }
  const double x = p.cost(i, j);
  if (!std::isfinite(x)) return false;
  *c = x;
  return true;
}

double RealCost(const Problem& p, const State& s) {
  double sum = 0.0;  // row order, so equal assignments have bit-equal costs
  for (int i = 0; i < p.real_rows; ++i) {
    sum += p.cost(i, s.column_of_row[static_cast<std::size_t>(i)]);
  }
  return sum;
}

std::vector<int> ForcedRowOfColumn(const Problem& p, const Node& node) {
  std::vector<int> row_of(static_cast<std::size_t>(p.size), kNone);
  for (int i = 0; i < p.real_rows; ++i) {
    const int j = node.forced_column[static_cast<std::size_t>(i)];
    if (j != kNone) row_of[static_cast<std::size_t>(j)] = i;
  }
  return row_of;
}

}  // namespace

std::vector<Assignment> MurtyBestAssignments(const Eigen::MatrixXd& cost, std::size_t m) {
  std::vector<Assignment> ranked;
  if (m == 0 || cost.rows() > cost.cols()) return ranked;
  const Problem p{cost, static_cast<int>(cost.rows()), static_cast<int>(cost.cols())};
  const auto size = static_cast<std::size_t>(p.size);
  Workspace workspace;

  Node root{State(size, size),
            0.0,
            std::vector<int>(static_cast<std::size_t>(p.real_rows), kNone),
            {},
            0};
  // Set to a child's forbidden pairs while it is solved, and cleared after: one buffer,
  // never copied with the nodes.
  std::vector<char> forbidden_mask(size * size, 0);
  {
    const std::vector<int> no_forced(size, kNone);
    const auto entry = [&](int i, int j, double* c) {
      return Entry(p, root, no_forced, forbidden_mask, i, j, c);
    };
    for (int row = 0; row < p.size; ++row) {
      if (!internal::AugmentRow(row, entry, root.state, workspace)) return ranked;
    }
  }
  root.cost = RealCost(p, root.state);

  std::uint64_t sequence = 1;
  std::priority_queue<Node, std::vector<Node>, CostlierFirst> queue;
  queue.push(std::move(root));
  while (!queue.empty() && ranked.size() < m) {
    Node node = queue.top();
    queue.pop();

    // Murty's partition of the rest of the node's subset: child k keeps the node's pairs of
    // the first k free real rows and forbids its pair of row k. Each child starts from the
    // node's matching without that pair and its duals, which stay feasible (the child only
    // has fewer allowed entries), so one augmenting path re-solves it.
    if (ranked.size() + 1 < m) {
      Node child_template = node;
      for (int i = 0; i < p.real_rows; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        if (node.forced_column[ui] != kNone) continue;
        const int j = node.state.column_of_row[ui];
        Node child = child_template;
        child.forbidden.emplace_back(i, j);
        child.state.column_of_row[ui] = kNone;
        child.state.row_of_column[static_cast<std::size_t>(j)] = kNone;
        const std::vector<int> forced_rows = ForcedRowOfColumn(p, child);
        const auto entry = [&](int r, int c, double* x) {
          return Entry(p, child, forced_rows, forbidden_mask, r, c, x);
        };
        const auto mark = [&](char value) {
          for (const auto& [fr, fc] : child.forbidden) {
            forbidden_mask[static_cast<std::size_t>(fr) * size + static_cast<std::size_t>(fc)] =
                value;
          }
        };
        mark(1);
        const bool solved = internal::AugmentRow(i, entry, child.state, workspace);
        mark(0);
        if (solved) {
          child.cost = RealCost(p, child.state);
          child.sequence = sequence++;
          queue.push(std::move(child));
        }
        child_template.forced_column[ui] = j;  // the next children keep this pair
      }
    }

    Assignment best;
    best.column_of_row.assign(node.state.column_of_row.begin(),
                              node.state.column_of_row.begin() + p.real_rows);
    best.cost = node.cost;
    ranked.push_back(std::move(best));
  }
  return ranked;
}

}  // namespace lookout::assignment
