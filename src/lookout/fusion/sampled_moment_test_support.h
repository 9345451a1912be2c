#pragma once

// The mean of a sample of 2 x 2 products (an error's outer product, or two errors' cross
// product) and each element's standard error from the sample's own spread: the Monte Carlo
// side of the fusion tests that check a closed-form covariance against draws of what it stands
// for (gaussian_fusion_test.cc, shared_heading_test.cc). Tests only (it asserts with gtest).

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace lookout::fusion::testing {

class SampledMoment {
 public:
  void Add(const Eigen::Matrix2d& product) {
    sum_ += product;
    sum_squares_ += product.cwiseProduct(product);
    ++count_;
  }

  Eigen::Matrix2d Mean() const { return sum_ / static_cast<double>(count_); }

  Eigen::Matrix2d StandardError() const {
    const double n = static_cast<double>(count_);
    const Eigen::Matrix2d mean = Mean();
    return ((sum_squares_ / n - mean.cwiseProduct(mean)) / n).cwiseSqrt();
  }

  // Every element within `sigmas` standard errors, and `relative` of the expected element's
  // size (a linearisation's own error), of `expected`; the seed in the failure's message.
  void ExpectNear(const Eigen::Matrix2d& expected, std::uint64_t seed, double sigmas = 4.0,
                  double relative = 0.0) const {
    const Eigen::Matrix2d mean = Mean();
    const Eigen::Matrix2d error = StandardError();
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        EXPECT_NEAR(mean(i, j), expected(i, j),
                    sigmas * error(i, j) + relative * std::abs(expected(i, j)))
            << "seed " << seed << ", element (" << i << ", " << j << ")";
      }
    }
  }

 private:
  Eigen::Matrix2d sum_ = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d sum_squares_ = Eigen::Matrix2d::Zero();
  long count_ = 0;
};

}  // namespace lookout::fusion::testing
