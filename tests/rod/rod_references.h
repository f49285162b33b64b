// Independent reference solutions for the rod tests: the exact helix under a terminal couple and
// the elliptic-integral cantilever. Nothing here calls the rod solver.
#pragma once
#include <cmath>

#include "core/types.h"

namespace hairfit::test {

constexpr double kPi = 3.14159265358979323846;

// A rod with EI1 = EI2 = EI (any GJ), no natural curvature, clamped at the origin with frame R0,
// loaded by a terminal couple m alone. Then n ≡ 0, m is constant in world axes, d3 precesses about
// m at rate ω = |m|/EI, and the material frame also spins about d3 at the rate
// c = (1/GJ − 1/EI)·(m·d3): R(s) = Rot(m̂, ωs)·R0·Rot(e3, c·s). Integrating d3 gives the helix.
struct HelixState {
  Vec3 position;
  Mat3 frame;
};

inline HelixState exact_helix(const Vec3& m, double ei, double gj, const Mat3& root_frame, double s) {
  const Vec3 d3 = root_frame.col(2);
  const double omega = m.norm() / ei;
  const double spin = (1.0 / gj - 1.0 / ei) * m.dot(d3);
  HelixState out;
  if (omega == 0.0) {
    out.position = s * d3;
    out.frame = root_frame;
    return out;
  }
  const Vec3 axis = m.normalized();
  const Vec3 along = d3.dot(axis) * axis;
  const Vec3 across = d3 - along;
  out.position = s * along + (std::sin(omega * s) / omega) * across + ((1.0 - std::cos(omega * s)) / omega) *
                                                                         axis.cross(across);
  out.frame = Eigen::AngleAxisd(omega * s, axis).toRotationMatrix() * root_frame *
              Eigen::AngleAxisd(spin * s, Vec3::UnitZ()).toRotationMatrix();
  return out;
}

// Incomplete elliptic integrals F(φ, k) and E(φ, k) by composite 8-point Gauss–Legendre
// quadrature of 1/√(1−k²sin²t) and √(1−k²sin²t) over [0, φ] (smooth for k < 1).
struct EllipticPair {
  double first;   // F(φ, k)
  double second;  // E(φ, k)
};

inline EllipticPair elliptic_by_quadrature(double phi, double k) {
  static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int panels = 400;
  const double width = phi / panels;
  EllipticPair sum{0.0, 0.0};
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * width;
    for (int j = 0; j < 4; ++j)
      for (double sign : {-1.0, 1.0}) {
        const double t = mid + sign * 0.5 * width * x[j];
        const double root = std::sqrt(1.0 - k * k * std::sin(t) * std::sin(t));
        sum.first += 0.5 * width * w[j] / root;
        sum.second += 0.5 * width * w[j] * root;
      }
  }
  return sum;
}

// The classic large-deflection cantilever (Bisshopp–Drucker): a straight rod of length 1 along +z,
// clamped at the origin, dead tip force α = P·L²/EI along +x. With θ the tangent angle from the
// z axis, θ'' = −α cos θ, θ(0) = 0, θ'(1) = 0. The substitution 1 + sin θ = 2k² sin²φ gives
//   √α = K(k) − F(φ0, k),  x_tip = 1 − 2(E(k) − E(φ0, k))/√α,  z_tip = √(2 sin θ0 / α),
// with sin φ0 = 1/(k√2) and sin θ0 = 2k² − 1. k is found by bisection.
struct CantileverTip {
  double x;      // deflection along the force, units of L
  double z;      // position along the initial axis, units of L
  double angle;  // θ0, tip tangent angle from +z toward +x
};

inline CantileverTip cantilever_tip(double alpha, bool use_std_elliptic) {
  auto integrals = [&](double phi, double k) {
    if (use_std_elliptic) return EllipticPair{std::ellint_1(k, phi), std::ellint_2(k, phi)};
    return elliptic_by_quadrature(phi, k);
  };
  auto phi0_of = [](double k) { return std::asin(std::min(1.0, 1.0 / (k * std::sqrt(2.0)))); };
  auto mismatch = [&](double k) {
    return integrals(kPi / 2, k).first - integrals(phi0_of(k), k).first - std::sqrt(alpha);
  };
  double lo = 1.0 / std::sqrt(2.0), hi = 1.0 - 1e-15;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mismatch(mid) < 0.0 ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  const double phi0 = phi0_of(k);
  const double sin_theta0 = 2.0 * k * k - 1.0;
  CantileverTip tip;
  tip.x = 1.0 - 2.0 * (integrals(kPi / 2, k).second - integrals(phi0, k).second) / std::sqrt(alpha);
  tip.z = std::sqrt(2.0 * sin_theta0 / alpha);
  tip.angle = std::asin(sin_theta0);
  return tip;
}

}  // namespace hairfit::test
