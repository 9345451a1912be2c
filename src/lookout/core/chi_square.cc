#include "lookout/core/chi_square.h"

#include <boost/math/distributions/chi_squared.hpp>

namespace lookout {

double ChiSquareCdf(double x, double dof) {
  if (x <= 0.0) return 0.0;
  return boost::math::cdf(boost::math::chi_squared_distribution<double>(dof), x);
}

double ChiSquareQuantile(double p, double dof) {
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), p);
}

}  // namespace lookout
