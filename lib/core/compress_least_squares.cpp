#include "core/compress_least_squares.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace hairfit {

namespace {

using Normal = Eigen::Matrix<double, 6, 6>;
using Out = Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>>;
using Rows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>>;

void compress_by_qr(int m, const double* r, const Rows& j, double* out_r, Out& out_j) {
  const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 6>> qr(j);
  Eigen::VectorXd qtr = Eigen::Map<const Eigen::VectorXd>(r, m);
  qtr.applyOnTheLeft(qr.householderQ().adjoint());
  const int k = std::min(m, 6);
  for (int i = 0; i < k; ++i) out_r[i] = qtr[i];
  out_r[6] = qtr.tail(m - k).norm();
  out_j.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
}

}  // namespace

bool compress_least_squares(int m, const double* r, const double* jacobian, double* out_r, double* out_jacobian) {
  const Rows j(jacobian, m, 6);
  const Eigen::Map<const Eigen::VectorXd> rv(r, m);
  if (!rv.allFinite() || !j.allFinite()) return false;
  Out out_j(out_jacobian);
  out_j.setZero();
  std::fill(out_r, out_r + 7, 0.0);
  // JᵀJ and Jᵀr row by row, a column of JᵀJ at a time (vectorised; Eigen's general product takes
  // its blocked path for an m × 6 matrix, several times the work).
  Normal normal = Normal::Zero();
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> row;
  for (int i = 0; i < m; ++i) {
    row = j.row(i).transpose();
    for (int c = 0; c < 6; ++c) normal.col(c) += row[c] * row;
    gradient += r[i] * row;
  }
  const Eigen::LLT<Normal> cholesky(normal);
  const double smallest_pivot = cholesky.matrixLLT().diagonal().cwiseAbs2().minCoeff();
  if (m >= 6 && cholesky.info() == Eigen::Success && smallest_pivot > 1e-12 * normal.diagonal().maxCoeff()) {
    const Eigen::Matrix<double, 6, 1> qtr = cholesky.matrixL().solve(gradient);
    for (int i = 0; i < 6; ++i) out_r[i] = qtr[i];
    out_r[6] = std::sqrt(std::max(0.0, rv.squaredNorm() - qtr.squaredNorm()));
    out_j.topRows<6>() = cholesky.matrixU();
  } else {
    compress_by_qr(m, r, j, out_r, out_j);
  }
  return true;
}

}  // namespace hairfit
