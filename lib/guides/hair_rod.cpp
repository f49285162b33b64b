#include "guides/hair_rod.h"

#include <cmath>

namespace hairfit {

Rod hair_rod(double length, const HairMaterial& m) {
  Rod rod = make_circular_rod(length, m.youngs_modulus, m.shear_modulus, m.cross_section);
  rod.force_per_length = m.mass_density * m.cross_section * m.gravity;  // g/cm³ · cm² · cm/s² = dyn/cm
  return rod;
}

RodModel hair_rod_model(double length, const HairMaterial& material, const RodRoot& root, const DistanceField* scalp) {
  const Rod rod = hair_rod(length, material);
  RodModel model = make_rod_model(rod, root);
  if (material.contact.active() && scalp)
    model.support = std::make_shared<ScalpContact>(*scalp, material.contact, root.position, length, rod.stiffness[0]);
  return model;
}

Vec3 bending_direction(const Vec3& normal, const Vec3& direction, const Vec3& down, const Vec3& front) {
  const Vec3 d = direction.normalized();
  const Vec3 candidates[] = {d.dot(normal) * d - normal, down, -front, Vec3::UnitX(), Vec3::UnitY()};
  for (const Vec3& candidate : candidates) {
    const Vec3 perpendicular = candidate - candidate.dot(d) * d;
    if (perpendicular.norm() > 1e-6) return perpendicular.normalized();
  }
  return Vec3::UnitZ();  // unreachable: X and Y cannot both be parallel to d
}

Mat3 root_frame(const Vec3& direction, const Vec3& bending) {
  Mat3 frame;
  frame.col(2) = direction.normalized();
  frame.col(0) = (bending - bending.dot(frame.col(2)) * frame.col(2)).normalized();
  frame.col(1) = frame.col(2).cross(frame.col(0));
  return frame;
}

}  // namespace hairfit
