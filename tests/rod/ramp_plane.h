// A support for rod tests and benchmarks: the plane y = height (rod units, the root at the origin)
// pushing up with the scalp contact's law k·g(φ) (guides/scalp_contact.h), φ = y − height.
#pragma once
#include <cmath>

#include "guides/scalp_contact.h"
#include "rod/rod_support.h"

namespace hairfit::test {

class RampPlane : public RodSupport {
 public:
  RampPlane(double height, double stiffness, double layer) : height_(height), law_{stiffness, layer} {}
  void force(const double r[3], double c[3], double* jacobian) const override {
    double slope = 0.0;
    const double g = law_.ramp(r[1] - height_, &slope);
    c[0] = c[2] = 0.0;
    c[1] = law_.stiffness * g;
    if (jacobian) {
      for (int i = 0; i < 9; ++i) jacobian[i] = 0.0;
      jacobian[4] = law_.stiffness * slope;
    }
  }
  double stiffness() const override { return law_.stiffness; }
  // The height above the plane at which k·g carries a weight w per length.
  double resting(double w) const {
    const double k = law_.stiffness, delta = law_.layer;
    return w / k <= 0.5 * delta ? delta - std::sqrt(2.0 * delta * w / k) : 0.5 * delta - w / k;
  }

 private:
  double height_;
  ContactLaw law_;
};

}  // namespace hairfit::test
