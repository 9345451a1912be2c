#pragma once

// The chi-square distribution, for gates and consistency bands (the tracker's and fusion's
// gates, NEES and NIS bands), from Boost.Math (Debian's libboost-dev, header only): one
// well-tested implementation for the whole project rather than one per module.

namespace lookout {

// P(X <= x) for X ~ chi-square with `dof` > 0 degrees of freedom; 0 for x <= 0.
double ChiSquareCdf(double x, double dof);
// The x with ChiSquareCdf(x, dof) = p, for 0 < p < 1.
double ChiSquareQuantile(double p, double dof);

}  // namespace lookout
