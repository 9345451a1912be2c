#include "lookout/tracking/chi_square.h"

#include <cassert>
#include <cmath>

namespace lookout::tracking {
namespace {

// P(a, x) by the series e^-x x^a / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n)).
double LowerSeries(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < 1000; ++n) {
    term *= x / (a + static_cast<double>(n));
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) = 1 - P(a, x) by its continued fraction, evaluated with the modified Lentz method.
double UpperFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 1000; ++i) {
    const double di = static_cast<double>(i);
    const double an = -di * (di - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double ChiSquareCdf(double x, double dof) {
  assert(dof > 0.0);
  if (x <= 0.0) return 0.0;
  const double a = dof / 2.0;
  const double half = x / 2.0;
  return half < a + 1.0 ? LowerSeries(a, half) : 1.0 - UpperFraction(a, half);
}

double ChiSquareQuantile(double p, double dof) {
  assert(p > 0.0 && p < 1.0 && dof > 0.0);
  double lo = 0.0;
  double hi = dof + 10.0 * std::sqrt(2.0 * dof) + 10.0;
  while (ChiSquareCdf(hi, dof) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace lookout::tracking
