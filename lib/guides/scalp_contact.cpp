#include "guides/scalp_contact.h"

#include <cmath>

namespace hairfit {

double ContactLaw::ramp(double phi, double* slope) const {
  double g = 0.0, dg = 0.0;
  if (phi < 0.0) {
    g = 0.5 * layer - phi;
    dg = -1.0;
  } else if (phi < layer) {
    g = (layer - phi) * (layer - phi) / (2.0 * layer);
    dg = -(layer - phi) / layer;
  }
  if (slope) *slope = dg;
  return g;
}

namespace {

constexpr double kSmoothReach = 3.4641016151377544;  // 2√3: smooth(p) reads samples this many voxels away

}  // namespace

Vec3 contact_force(const DistanceField& scalp, const ContactLaw& law, const Vec3& p) {
  if (!law.active() || !p.allFinite() || scalp.nearest_sample(p) > law.layer + kSmoothReach * scalp.voxel())
    return Vec3::Zero();
  const FieldSmooth s = scalp.smooth(p);
  return law.stiffness * law.ramp(s.value) * s.gradient;
}

ScalpContact::ScalpContact(const DistanceField& scalp, const ContactLaw& law, const Vec3& root, double length,
                           double bending)
    : scalp_(scalp),
      law_(law),
      root_(root),
      length_(length),
      scale_(length * length * length / bending),
      reach_(law.layer + kSmoothReach * scalp.voxel()) {}

void ScalpContact::force(const double r[3], double c[3], double* jacobian) const {
  const Vec3 p = root_ + length_ * Vec3(r[0], r[1], r[2]);
  c[0] = c[1] = c[2] = 0.0;
  if (jacobian)
    for (int i = 0; i < 9; ++i) jacobian[i] = 0.0;
  if (!p.allFinite() || scalp_.nearest_sample(p) > reach_) return;
  const FieldSmooth s = scalp_.smooth(p);
  double slope = 0.0;
  const double g = law_.ramp(s.value, &slope);
  if (g == 0.0 && slope == 0.0) return;
  const double k = law_.stiffness * scale_;
  for (int i = 0; i < 3; ++i) c[i] = k * g * s.gradient[i];
  if (jacobian) {
    // ∂c/∂r = k·(g'·∇φ∇φᵀ + g·∇²φ)·L (p = root + L·r).
    const Mat3 j = (k * length_) * (slope * s.gradient * s.gradient.transpose() + g * s.hessian);
    for (int i = 0; i < 9; ++i) jacobian[i] = j.data()[i];
  }
}

double ScalpContact::stiffness() const {
  // |∂c/∂r| ≤ k·L⁴/EI·(|∇φ|² + g·|∇²φ|), with |∇φ| ≈ 1 and g·|∇²φ| small beside it.
  return law_.stiffness * scale_ * length_;
}

}  // namespace hairfit
