#include "lookout/core/chi_square.h"

#include <cmath>

#include <gtest/gtest.h>

namespace lookout {
namespace {

// Published table values (Abramowitz and Stegun, table 26.8; NIST/SEMATECH e-Handbook 1.3.6.7.4).
TEST(ChiSquare, QuantilesMatchTables) {
  EXPECT_NEAR(ChiSquareQuantile(0.95, 1.0), 3.841459, 1e-6);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 2.0), 9.210340, 1e-6);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 4.0), 9.487729, 1e-6);
  EXPECT_NEAR(ChiSquareQuantile(0.05, 10.0), 3.940299, 1e-6);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 100.0), 129.561, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 100.0), 74.222, 1e-3);
}

// Two degrees of freedom have the closed form P(x) = 1 - exp(-x / 2).
TEST(ChiSquare, TwoDegreesOfFreedomIsExponential) {
  for (const double x : {0.01, 0.5, 2.0, 9.0, 40.0}) {
    EXPECT_NEAR(ChiSquareCdf(x, 2.0), 1.0 - std::exp(-x / 2.0), 1e-13) << x;
  }
  EXPECT_NEAR(ChiSquareQuantile(0.999, 2.0), -2.0 * std::log(0.001), 1e-9);
  EXPECT_EQ(ChiSquareCdf(-1.0, 3.0), 0.0);
}

}  // namespace
}  // namespace lookout
