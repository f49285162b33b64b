// LU with partial pivoting of a band matrix, for the multiple-shooting Jacobian (rod_shooting),
// where a residual couples only its own piece and the next: nonzeros lie within `lower` below and
// `upper` above the diagonal. Row swaps widen the upper band by `lower` (LAPACK's gbtrf scheme:
// earlier multipliers stay in place and the solve interleaves swaps with elimination), so the
// work is O(n·lower·(lower + upper)) instead of O(n³): ~40× less for 15 pieces. Internal to lib/rod.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace hairfit {

class BandLU {
 public:
  BandLU(Eigen::MatrixXd a, int lower, int upper)
      : lu_(std::move(a)), lower_(lower), upper_(upper + lower), pivots_(lu_.rows()) {
    const int n = static_cast<int>(lu_.rows());
    for (int j = 0; j < n; ++j) {
      const int last_row = std::min(n - 1, j + lower_), last_col = std::min(n - 1, j + upper_);
      int pivot = j;
      for (int i = j + 1; i <= last_row; ++i)
        if (std::fabs(lu_(i, j)) > std::fabs(lu_(pivot, j))) pivot = i;
      pivots_[j] = pivot;
      if (lu_(pivot, j) == 0.0) {  // singular: the solve returns NaN, which callers reject
        singular_ = true;
        continue;
      }
      if (pivot != j)
        for (int c = j; c <= last_col; ++c) std::swap(lu_(j, c), lu_(pivot, c));
      for (int i = j + 1; i <= last_row; ++i) {
        const double l = lu_(i, j) / lu_(j, j);
        lu_(i, j) = l;
        if (l != 0.0)
          for (int c = j + 1; c <= last_col; ++c) lu_(i, c) -= l * lu_(j, c);
      }
    }
  }

  // A⁻¹·B for one or several right-hand sides.
  Eigen::MatrixXd solve(Eigen::MatrixXd b) const {
    const int n = static_cast<int>(lu_.rows());
    if (singular_) return Eigen::MatrixXd::Constant(b.rows(), b.cols(), NAN);
    for (int j = 0; j < n; ++j) {
      if (pivots_[j] != j) b.row(j).swap(b.row(pivots_[j]));
      for (int i = j + 1; i <= std::min(n - 1, j + lower_); ++i) b.row(i) -= lu_(i, j) * b.row(j);
    }
    for (int j = n - 1; j >= 0; --j) {
      for (int c = j + 1; c <= std::min(n - 1, j + upper_); ++c) b.row(j) -= lu_(j, c) * b.row(c);
      b.row(j) /= lu_(j, j);
    }
    return b;
  }

 private:
  Eigen::MatrixXd lu_;
  int lower_, upper_;
  std::vector<int> pivots_;
  bool singular_ = false;
};

}  // namespace hairfit
