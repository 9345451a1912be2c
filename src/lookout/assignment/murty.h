#pragma once

// Murty's method (K. G. Murty, "An algorithm for ranking all the assignments in order of
// increasing cost", Operations Research 16(3), 1968): the m best complete assignments of a
// cost matrix, in increasing cost. The MHT ranks its hypotheses with it; its cost matrix has
// a row per measurement and, besides a column per track, "false alarm" and "new track"
// columns, so that every row can always be explained.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "lookout/assignment/linear_assignment.h"

namespace lookout::assignment {

// The `m` least-cost assignments of every row to a distinct column through allowed (finite)
// entries, cheapest first, each with its cost; fewer when fewer exist, none when the rows
// cannot all be assigned. Equal costs come out in a fixed order (the order in which the
// partitions were made), so the result is the same on every run.
std::vector<Assignment> MurtyBestAssignments(const Eigen::MatrixXd& cost, std::size_t m);

}  // namespace lookout::assignment
