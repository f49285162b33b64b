#include "scalp/flow_lookup.h"

#include <cmath>

namespace hairfit {

FlowLookup::FlowLookup(const Mesh& scalp, const std::vector<Vec3>& normals, const DirectionField& field, double radius)
    : positions_(scalp.positions), normals_(normals), directions_(field.directions), grid_(scalp.positions, radius),
      radius_(radius) {}

Vec3 FlowLookup::at(const Vec3& p, Vec3* normal) const {
  Vec3 direction = Vec3::Zero(), n = Vec3::Zero();
  const double s2 = 0.25 * radius_ * radius_;
  grid_.for_each_within(p, radius_, [&](int i, double d2) {
    const double w = std::exp(-d2 / s2) - std::exp(-4.0);  // 0 at the radius: continuous
    direction += w * directions_[i];
    n += w * normals_[i];
  });
  if (!(n.norm() > 0.0)) return Vec3::Zero();
  n.normalize();
  direction -= direction.dot(n) * n;
  if (normal) *normal = n;
  const double m = direction.norm();
  return m > 1e-12 ? Vec3(direction / m) : Vec3::Zero();
}

}  // namespace hairfit
