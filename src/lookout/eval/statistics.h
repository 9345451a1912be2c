#pragma once

#include <vector>

namespace lookout::eval {

// The median of `values` (the mean of the two middle ones for an even count); NaN when empty.
double Median(std::vector<double> values);

// numerator / denominator, NaN when the denominator is not positive (a rate of nothing).
double Ratio(double numerator, double denominator);

}  // namespace lookout::eval
