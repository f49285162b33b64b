// The check both the heavy and the supported rod tests make of shooting_sensitivity: node
// derivatives traced with the implicit load derivatives against central finite differences of
// the boundary-value solve itself.
#pragma once
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rod/rod_jet.h"
#include "rod/rod_sensitivity.h"
#include "rod/rod_shooting.h"

namespace hairfit::test {

// The worst relative error, over every node coordinate and the six loads, of the traced
// derivative at the solution `at` of (force, torque) against (x(+h) − x(−h))/2h, h = 1e-5.
inline double worst_load_derivative_error(const RodModel& model, const ShootingOptions& options,
                                          const ShootingResult& at, const Vec3& force, const Vec3& torque) {
  const auto sensitivity = shooting_sensitivity(model, at, options);
  REQUIRE(sensitivity.size() + 1 == at.breaks.size());
  const int n = options.segments + 1;
  std::vector<RodJet6> nodes(3 * n);
  trace_pieces(model, options.integrator, options.segments, at, sensitivity,
               RodTrace<RodJet6>{nodes.data(), nullptr, nullptr, nullptr});
  auto traced = [&](const Vec3& f, const Vec3& t) {
    const ShootingResult s = shoot_root_moment(model, f, t, at, options);
    REQUIRE(s.converged);
    std::vector<double> out(3 * n);
    trace_pieces(model, options.integrator, options.segments, s, RodTrace<double>{out.data(), nullptr, nullptr, nullptr});
    return out;
  };
  const double h = 1e-5;
  double worst = 0.0;
  for (int j = 0; j < 6; ++j) {
    Vec3 df = Vec3::Zero(), dt = Vec3::Zero();
    (j < 3 ? df : dt)[j % 3] = h;
    const std::vector<double> plus = traced(force + df, torque + dt), minus = traced(force - df, torque - dt);
    for (int i = 0; i < 3 * n; ++i) {
      const double fd = (plus[i] - minus[i]) / (2.0 * h);
      worst = std::max(worst, std::fabs(nodes[i].v[j] - fd) / (1.0 + std::fabs(fd)));
    }
  }
  return worst;
}

}  // namespace hairfit::test
