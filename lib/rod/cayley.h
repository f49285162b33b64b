// The Cayley map of so(3) and its inverse, templated on the scalar (double, ceres::Jet, or the
// integrator's own dual number): cay(θ) = (I − [θ]/2)⁻¹(I + [θ]/2) = I + 4/(4+|θ|²)·([θ] + [θ]²/2),
// an exact rotation by 2·atan(|θ|/2) about θ computed without trigonometry. Internal to lib/rod.
//
// Written entry by entry on the scalar, not with Eigen expressions: on jets GCC leaves Eigen's
// small fixed-size kernels as calls, which made the rod integrator ~25× slower than in double.
#pragma once
#include <Eigen/Core>

namespace hairfit::cayley {

// cay(θ) column-major into q[9] (q[3c + r] = entry (r, c)). With [θ]² = θθᵀ − |θ|²I the diagonal
// is 1 − c/2·(θ_j² + θ_k²), which keeps the columns unit to round-off.
template <typename S>
inline S square(const S& x) {  // the integrator's dual number overloads this with a cheaper one
  return x * x;
}

template <typename S>
inline void fill_matrix(const S* theta, S* q) {
  const S xx = square(theta[0]), yy = square(theta[1]), zz = square(theta[2]);
  const S c = 4.0 / (4.0 + ((xx + yy) + zz));
  const S ch = 0.5 * c;
  const S cx = c * theta[0], cy = c * theta[1], cz = c * theta[2];
  const S xy = ch * (theta[0] * theta[1]), xz = ch * (theta[0] * theta[2]), yz = ch * (theta[1] * theta[2]);
  q[0] = 1.0 - ch * (yy + zz);
  q[1] = xy + cz;
  q[2] = xz - cy;
  q[3] = xy - cz;
  q[4] = 1.0 - ch * (xx + zz);
  q[5] = yz + cx;
  q[6] = xz + cy;
  q[7] = yz - cx;
  q[8] = 1.0 - ch * (xx + yy);
}

template <typename T>
Eigen::Matrix<T, 3, 3> matrix(const Eigen::Matrix<T, 3, 1>& theta) {
  const T t[3] = {theta(0), theta(1), theta(2)};
  Eigen::Matrix<T, 3, 3> q;
  fill_matrix<T>(t, q.data());
  return q;
}

// θ with cay(θ) = Q for a rotation Q (not a half turn): θ = 2·vee(Q − Qᵀ)/(1 + tr Q).
template <typename T>
Eigen::Matrix<T, 3, 1> log(const Eigen::Matrix<T, 3, 3>& q) {
  const T scale = T(2.0) / (T(1.0) + q.trace());
  return scale * Eigen::Matrix<T, 3, 1>(q(2, 1) - q(1, 2), q(0, 2) - q(2, 0), q(1, 0) - q(0, 1));
}

}  // namespace hairfit::cayley
