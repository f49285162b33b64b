#include "core/compress_least_squares.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace hairfit {

namespace {

template <int N>
using Normal = Eigen::Matrix<double, N, N>;
template <int N>
using Out = Eigen::Map<Eigen::Matrix<double, N + 1, N, Eigen::RowMajor>>;
template <int N>
using Rows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, N, Eigen::RowMajor>>;

template <int N>
void compress_by_qr(int m, const double* r, const Rows<N>& j, double* out_r, Out<N>& out_j) {
  const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, N>> qr(j);
  Eigen::VectorXd qtr = Eigen::Map<const Eigen::VectorXd>(r, m);
  qtr.applyOnTheLeft(qr.householderQ().adjoint());
  const int k = std::min(m, N);
  for (int i = 0; i < k; ++i) out_r[i] = qtr[i];
  out_r[N] = qtr.tail(m - k).norm();
  out_j.topRows(k) = qr.matrixQR().topRows(k).template triangularView<Eigen::Upper>();
}

}  // namespace

template <int N>
bool compress_least_squares(int m, const double* r, const double* jacobian, double* out_r, double* out_jacobian) {
  const Rows<N> j(jacobian, m, N);
  const Eigen::Map<const Eigen::VectorXd> rv(r, m);
  if (!rv.allFinite() || !j.allFinite()) return false;
  Out<N> out_j(out_jacobian);
  out_j.setZero();
  std::fill(out_r, out_r + N + 1, 0.0);
  // JᵀJ and Jᵀr row by row, a column of JᵀJ at a time (vectorised; Eigen's general product takes
  // its blocked path for an m × 6 matrix, several times the work).
  Normal<N> normal = Normal<N>::Zero();
  Eigen::Matrix<double, N, 1> gradient = Eigen::Matrix<double, N, 1>::Zero();
  Eigen::Matrix<double, N, 1> row;
  for (int i = 0; i < m; ++i) {
    row = j.row(i).transpose();
    for (int c = 0; c < N; ++c) normal.col(c) += row[c] * row;
    gradient += r[i] * row;
  }
  const Eigen::LLT<Normal<N>> cholesky(normal);
  const double smallest_pivot = cholesky.matrixLLT().diagonal().cwiseAbs2().minCoeff();
  if (m >= N && cholesky.info() == Eigen::Success && smallest_pivot > 1e-12 * normal.diagonal().maxCoeff()) {
    const Eigen::Matrix<double, N, 1> qtr = cholesky.matrixL().solve(gradient);
    for (int i = 0; i < N; ++i) out_r[i] = qtr[i];
    out_r[N] = std::sqrt(std::max(0.0, rv.squaredNorm() - qtr.squaredNorm()));
    out_j.template topRows<N>() = cholesky.matrixU();
  } else {
    compress_by_qr<N>(m, r, j, out_r, out_j);
  }
  return true;
}

template bool compress_least_squares<6>(int, const double*, const double*, double*, double*);
template bool compress_least_squares<9>(int, const double*, const double*, double*, double*);
template bool compress_least_squares<12>(int, const double*, const double*, double*, double*);
template bool compress_least_squares<15>(int, const double*, const double*, double*, double*);

}  // namespace hairfit
