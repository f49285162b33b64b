// compress_least_squares: the compressed block must reproduce |r|², Jᵀr and JᵀJ, whatever J's rank.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "core/compress_least_squares.h"

using namespace hairfit;

namespace {

using Rows = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

struct Block {
  Eigen::VectorXd r;
  Rows j;
};

Block random_block(int m, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Block b{Eigen::VectorXd(m), Rows(m, 6)};
  for (int i = 0; i < m; ++i) {
    b.r[i] = n(rng);
    for (int k = 0; k < 6; ++k) b.j(i, k) = n(rng) * std::pow(10.0, k - 3);  // columns 1e-3 … 1e2
  }
  return b;
}

// The three identities, relative to the size of each quantity.
void check_equivalent(const Block& b) {
  double r7[7], j42[42];
  REQUIRE(compress_least_squares<6>(static_cast<int>(b.r.size()), b.r.data(), b.j.data(), r7, j42));
  const Eigen::Map<const Eigen::Matrix<double, 7, 1>> rc(r7);
  const Eigen::Map<const Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> jc(j42);
  CHECK(std::abs(rc.squaredNorm() - b.r.squaredNorm()) <= 1e-12 * b.r.squaredNorm());
  const Eigen::Matrix<double, 6, 1> g = b.j.transpose() * b.r, gc = jc.transpose() * rc;
  CHECK((gc - g).norm() <= 1e-10 * (b.j.norm() * b.r.norm()));
  const Eigen::Matrix<double, 6, 6> n = b.j.transpose() * b.j, nc = jc.transpose() * jc;
  CHECK((nc - n).norm() <= 1e-12 * n.norm());
  for (int k = 0; k < 6; ++k) CHECK(std::abs(jc.col(k).norm() - b.j.col(k).norm()) <= 1e-12 * b.j.col(k).norm() + 1e-300);
  CHECK(jc.row(6).norm() == 0.0);
}

}  // namespace

TEST_CASE("a compressed full-rank block keeps the cost, the gradient and the Gauss-Newton matrix") {
  std::mt19937 rng(7);
  for (int m : {6, 7, 40, 374}) {
    CAPTURE(m);
    check_equivalent(random_block(m, rng));
  }
}

TEST_CASE("a rank-deficient or short block is compressed by QR with the same guarantees") {
  std::mt19937 rng(11);
  Block b = random_block(50, rng);
  b.j.col(4) = 2.0 * b.j.col(1) - b.j.col(0);  // rank 5
  b.j.col(5).setZero();                         // rank 4
  check_equivalent(b);
  for (int m : {1, 3, 5}) {  // fewer residuals than parameters
    CAPTURE(m);
    check_equivalent(random_block(m, rng));
  }
  // r in J's range: nothing left outside it.
  Block in = random_block(30, rng);
  in.r = in.j * Eigen::Matrix<double, 6, 1>(1, -2, 0.5, 3, -1, 0.25);
  double r7[7], j42[42];
  REQUIRE(compress_least_squares<6>(30, in.r.data(), in.j.data(), r7, j42));
  CHECK(r7[6] <= 1e-6 * in.r.norm());
}

TEST_CASE("a block with a non-finite entry is refused") {
  std::mt19937 rng(3);
  Block b = random_block(10, rng);
  double r7[7], j42[42];
  b.r[2] = NAN;
  CHECK_FALSE(compress_least_squares<6>(10, b.r.data(), b.j.data(), r7, j42));
  b.r[2] = 0.0;
  b.j(4, 3) = INFINITY;
  CHECK_FALSE(compress_least_squares<6>(10, b.r.data(), b.j.data(), r7, j42));
}
