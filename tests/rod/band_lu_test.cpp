// The band LU of the multiple-shooting Jacobian against Eigen's dense LU on random band matrices,
// including ones whose diagonal is tiny so that every column needs a row swap.
#include <doctest/doctest.h>

#include <Eigen/LU>
#include <random>

#include "rod/band_lu.h"

using namespace hairfit;

namespace {

Eigen::MatrixXd random_band(int n, int lower, int upper, double diagonal_scale, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - lower); j <= std::min(n - 1, i + upper); ++j) a(i, j) = u(rng);
  for (int i = 0; i < n; ++i) a(i, i) *= diagonal_scale;
  return a;
}

}  // namespace

TEST_CASE("band LU solves like the dense LU, with and without row swaps") {
  std::mt19937 rng(5);
  for (const double diagonal_scale : {1.0, 1e-9}) {
    for (const int n : {3, 9, 27, 87}) {
      CAPTURE(diagonal_scale);
      CAPTURE(n);
      const Eigen::MatrixXd a = random_band(n, 8, 8, diagonal_scale, rng);
      const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 6);
      const Eigen::MatrixXd expected = a.fullPivLu().solve(b);
      const Eigen::MatrixXd x = BandLU(a, 8, 8).solve(b);
      CHECK((x - expected).norm() <= 1e-9 * (1.0 + expected.norm()));
      CHECK((a * x - b).norm() <= 1e-9 * (1.0 + b.norm()));
    }
  }
}

TEST_CASE("a singular band matrix gives a non-finite solution, never a wrong finite one") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(10, 10);
  a(4, 4) = 0.0;
  CHECK(!BandLU(a, 2, 2).solve(Eigen::VectorXd::Ones(10)).allFinite());
}
