// A distributed force per length that depends on where the rod is: a support (contact with a
// surface). It enters the rod's equations as n' = −f − c(r), so the contact force resultant n(s)
// is no longer known in closed form and is integrated with the rest (rod_integrate.h).
#pragma once

namespace hairfit {

class RodSupport {
 public:
  virtual ~RodSupport() = default;

  // c(r) at the rod-unit position r (the root at the origin, lengths in L, world axes), as a
  // dimensionless force per length (c·L³/EI_ref). When `jacobian` is non-null it receives ∂c/∂r
  // (column-major 3×3, dimensionless). C¹ in r, so that the optimiser sees a smooth rod.
  virtual void force(const double r[3], double c[3], double* jacobian) const = 0;

  // An upper bound on |∂c/∂r| (dimensionless): how stiff the support can make the rod's equations,
  // which sets how many pieces multiple shooting needs (rod_shooting.h).
  virtual double stiffness() const = 0;
};

}  // namespace hairfit
