// The scalp as a support (effects.contact, docs/design.md §1): a unilateral force per length that holds a
// hair out of the head and lets long hair lie on it. With φ the scalp's distance (positive on the
// hair's side) and δ the contact layer, the force is k·g(φ)·∇φ, where
//   g(φ) = (δ − φ)²/(2δ) for 0 ≤ φ < δ,   δ/2 − φ below the scalp,   0 beyond δ:
// C¹ in φ; φ is the cubic B-spline of the scalp's field (C²), so the force is C¹ in position.
#pragma once
#include "field/distance_field.h"
#include "rod/rod_support.h"

namespace hairfit {

struct ContactLaw {
  double stiffness = 0.0;  // k, dyn/cm² (force per length per cm into the layer); 0: no contact
  double layer = 0.3;      // δ, cm
  bool active() const { return stiffness > 0.0; }
  // g(φ) and dg/dφ (cm).
  double ramp(double phi, double* slope = nullptr) const;
};

// The force per length (dyn/cm) the scalp exerts at a point, and its magnitude.
Vec3 contact_force(const DistanceField& scalp, const ContactLaw& law, const Vec3& p);

// The support for one rod: rooted at `root` (cm), length L (cm), reference bending stiffness EI
// (dyn·cm²), in the rod's dimensionless units (rod_support.h). Holds its own handle on the field
// (a field's copies share their samples).
class ScalpContact : public RodSupport {
 public:
  ScalpContact(const DistanceField& scalp, const ContactLaw& law, const Vec3& root, double length, double bending);
  void force(const double r[3], double c[3], double* jacobian) const override;
  double stiffness() const override;

 private:
  DistanceField scalp_;
  ContactLaw law_;
  Vec3 root_;
  double length_;
  double scale_;  // L³/EI: dyn/cm → dimensionless force per length
  double reach_;  // δ + 2√3·h: beyond it (nearest sample) the force is zero
};

}  // namespace hairfit
