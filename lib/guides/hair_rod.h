// What pre-guides and principal guides share: a hair fibre as a clamped Cosserat rod rooted on
// the scalp, its root frame and the plane it bends in.
#pragma once
#include "guides/scalp_contact.h"
#include "rod/rod.h"

namespace hairfit {

struct HairMaterial {
  double youngs_modulus = 3.89e10;  // E, dyn/cm²
  double shear_modulus = 0.89e10;   // G, dyn/cm²
  double cross_section = 1.5e-5;    // A, cm²
  double mass_density = 1.32;       // ρ, g/cm³
  Vec3 gravity = Vec3::Zero();      // g, cm/s² as a world vector; zero when gravity is off
  ContactLaw contact;               // the scalp as a support (effects.contact); inactive when off
};

// The dimensionless load (weight ρAgL³/EI or terminal force F·L²/EI) beyond which one forward
// integration loses precision: m(1) depends on m(0) like exp(√load).
constexpr double kHeavyRod = 50.0;

// How a hair's rod is solved and optimised, chosen here once for pre-guides and guides alike.
enum class RodScheme {
  // One forward integration from the root: the rod's unknowns are its root loads (f_L, m(0)),
  // and its shape is traced from them.
  single_shooting,
  // The rod library's multiple shooting (rod_shooting.h): the unknowns are the terminal loads
  // (f_L, t_L), m(0) is solved for, and the shape is traced piece by piece from the solution.
  multiple_shooting,
};

// Multiple shooting for a rod on a support (its force resultant is no longer known in closed
// form) or loaded beyond kHeavyRod, by its weight or by the terminal force `terminal_load`
// (dimensionless) it is solved at; single shooting otherwise.
inline RodScheme rod_scheme(const RodModel& model, double terminal_load = 0.0) {
  const bool heavy = model.support || model.force_per_length.norm() > kHeavyRod || terminal_load > kHeavyRod;
  return heavy ? RodScheme::multiple_shooting : RodScheme::single_shooting;
}

// A fibre of the given length (cm): circular section, straight at rest, loaded by its weight
// ρ·A·g per length when the material has gravity.
Rod hair_rod(double length, const HairMaterial& material);

// The dimensionless model of that fibre clamped at `root`, on the scalp as its support when the
// material declares contact (`scalp` is then required).
RodModel hair_rod_model(double length, const HairMaterial& material, const RodRoot& root, const DistanceField* scalp);

// The direction a fibre at a root bends in (paper §3.4): perpendicular to the growth direction, in
// the plane of the surface normal and the growth direction, pointing away from the normal (the
// way the tilt leans). Where the growth direction is the normal, toward `down` projected; where
// that vanishes too, toward −front projected. Unit, never NaN.
Vec3 bending_direction(const Vec3& normal, const Vec3& direction, const Vec3& down, const Vec3& front);

// The clamp at a root: d3 = growth direction, d1 = bending direction, d2 = d3 × d1.
Mat3 root_frame(const Vec3& direction, const Vec3& bending);

}  // namespace hairfit
