#pragma once

// Chi-square distribution function and quantiles, for gates and consistency bands. Written here
// because the Debian packages the project uses (Eigen, the C++ library) have none and Boost.Math
// would be a new dependency for two functions. The regularised lower incomplete gamma function
// P(k/2, x/2) is summed by its series below a + 1 and by its continued fraction above (the
// standard split, Abramowitz and Stegun 6.5.29 and 6.5.31); quantiles invert it by bisection.

namespace lookout::tracking {

// P(X <= x) for X ~ chi-square with `dof` > 0 degrees of freedom.
double ChiSquareCdf(double x, double dof);
// The x with ChiSquareCdf(x, dof) = p, 0 < p < 1 (relative accuracy 1e-12).
double ChiSquareQuantile(double p, double dof);

}  // namespace lookout::tracking
