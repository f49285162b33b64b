// Central differences of the guide residuals (guide_residuals), the independent answer the
// residuals' jets are checked against.
#pragma once
#include <algorithm>
#include <vector>

#include "guides/objective.h"

namespace hairfit::testing {

// ∂r_i/∂η_j ≈ (r(η + h e_j) − r(η − h e_j)) / 2h for the targets' load_count() loads at eta:
// row-major, load_count() per residual, as guide_residuals lays out its Jacobian.
inline std::vector<double> residual_differences(const GuideTargets& t, const double* eta, double h) {
  const int loads = t.load_count();
  std::vector<double> differences;
  for (int j = 0; j < loads; ++j) {
    std::vector<double> plus(eta, eta + loads), minus(eta, eta + loads);
    plus[j] += h;
    minus[j] -= h;
    const std::vector<double> rp = guide_residuals(t, plus.data()), rm = guide_residuals(t, minus.data());
    differences.resize(rp.size() * loads);
    for (std::size_t i = 0; i < rp.size(); ++i) differences[loads * i + j] = (rp[i] - rm[i]) / (2.0 * h);
  }
  return differences;
}

}  // namespace hairfit::testing
