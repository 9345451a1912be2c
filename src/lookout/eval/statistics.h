#pragma once

#include <vector>

namespace lookout::eval {

// The median of `values` (the mean of the two middle ones for an even count); NaN when empty.
double Median(std::vector<double> values);

}  // namespace lookout::eval
