// The Cayley map of so(3) and its inverse, templated on the scalar (double or ceres::Jet):
// cay(θ) = (I − [θ]/2)⁻¹(I + [θ]/2) = I + 4/(4+|θ|²)·([θ] + [θ]²/2), an exact rotation by
// 2·atan(|θ|/2) about θ computed without trigonometry. Internal to lib/rod.
#pragma once
#include <Eigen/Core>

namespace hairfit::cayley {

template <typename T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using M3 = Eigen::Matrix<T, 3, 3>;

// cay(θ)·v without forming the matrix.
template <typename T>
V3<T> apply(const V3<T>& theta, const V3<T>& v) {
  const T c = T(4.0) / (T(4.0) + theta.squaredNorm());
  const V3<T> tv = theta.cross(v);
  return v + c * (tv + T(0.5) * theta.cross(tv));
}

template <typename T>
M3<T> matrix(const V3<T>& theta) {
  const T c = T(4.0) / (T(4.0) + theta.squaredNorm());
  M3<T> k;
  k << T(0.0), -theta(2), theta(1), theta(2), T(0.0), -theta(0), -theta(1), theta(0), T(0.0);
  return M3<T>::Identity() + c * (k + T(0.5) * (k * k));
}

// θ with cay(θ) = Q for a rotation Q (not a half turn): θ = 2·vee(Q − Qᵀ)/(1 + tr Q).
template <typename T>
V3<T> log(const M3<T>& q) {
  const T scale = T(2.0) / (T(1.0) + q.trace());
  return scale * V3<T>(q(2, 1) - q(1, 2), q(0, 2) - q(2, 0), q(1, 0) - q(0, 1));
}

}  // namespace hairfit::cayley
