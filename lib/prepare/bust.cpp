#include "prepare/bust.h"

#include <algorithm>
#include <cmath>

#include "core/shapes.h"
#include "core/smoothstep.h"

namespace hairfit {

namespace {

constexpr double kDegree = M_PI / 180.0;

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

Vec3 BustShape::cap_axis() const {
  return Vec3(0.0, std::cos(cap_tilt * kDegree), -std::sin(cap_tilt * kDegree));
}

double BustShape::cap_angle(const Vec3& u) const { return angle_between(u, cap_axis()); }

double BustShape::skin_radius(const Vec3& u) const {
  const Vec3& a = head_axes;
  const double head = 1.0 / std::sqrt(std::pow(u.x() / a.x(), 2) + std::pow(u.y() / a.y(), 2) + std::pow(u.z() / a.z(), 2));
  // The neck, a cylinder from the bottom cut up to 2 cm above the centre (inside the head): the
  // ray leaves it through its side, bottom or top, whichever comes first (a smooth minimum rounds
  // the bust's lower rim); a smooth maximum joins it to the head.
  const double side = neck_radius / std::max(1e-9, std::hypot(u.x(), u.z()));
  const double end = u.y() < -1e-9 ? neck_bottom / u.y() : u.y() > 1e-9 ? 2.0 / u.y() : 1e9;
  const double neck = std::pow(std::pow(side, -12.0) + std::pow(end, -12.0), -1.0 / 12.0);
  return std::pow(std::pow(head, 8.0) + std::pow(neck, 8.0), 1.0 / 8.0);
}

double BustShape::bumps(const Vec3& u) const {
  // Bun: a round knot at the back of the crown, about 7 cm across, flat-topped with steep sides.
  const Vec3 bun_direction = Vec3(0.0, 0.45, -0.9).normalized();
  const double a = angle_between(u, bun_direction);
  double height = bun_height * std::exp(-std::pow(a / 0.3, 4));
  // Braids: along the circle 52° from the cap axis, one on each side from the temple to behind
  // the ear, plaited (the height swells every 1.6 cm of arc).
  const Vec3 axis = cap_axis(), e1 = Vec3::UnitX(), e2 = axis.cross(e1);
  const double theta = cap_angle(u);
  const double phi = std::atan2(u.dot(e2), u.dot(e1));  // 0 at the left side, +90° at the front
  const double ring = 52.0 * kDegree, width = 0.085;
  for (double side : {1.0, -1.0}) {
    // Distance along the ring from the braid's span φ ∈ [−80°, 40°] (mirrored for the right).
    const double local = side > 0 ? phi : (phi >= 0 ? M_PI - phi : -M_PI - phi);
    const double lo = -80.0 * kDegree, hi = 40.0 * kDegree;
    const double along = std::max({lo - local, local - hi, 0.0}) * std::sin(ring);
    const double across = std::hypot(theta - ring, along);
    const double arc = local * std::sin(ring) * 9.0;  // cm, roughly
    const double plait = 0.8 + 0.2 * std::cos(2.0 * M_PI * arc / 1.6);
    height += braid_height * plait * std::exp(-0.5 * std::pow(across / width, 2));
  }
  return height;
}

double BustShape::hair_layer(const Vec3& u) const {
  const double theta = cap_angle(u), edge = hairline_angle * kDegree;
  if (theta > edge) return 0.0;
  const double taper = smoothstep((edge - theta) / (taper_angle * kDegree));
  return taper * (hair_thickness + bumps(u));
}

BustScan make_bust(const BustShape& shape, int levels) {
  BustScan scan;
  scan.mesh = icosphere(levels);
  scan.directions = scan.mesh.positions;
  for (std::size_t i = 0; i < scan.mesh.positions.size(); ++i) {
    const Vec3 u = scan.directions[i];
    scan.mesh.positions[i] = shape.radius(u) * u;
    const double* c = shape.in_hair(u) ? kHairColor : kSkinColor;
    scan.colors.emplace_back(c[0], c[1], c[2]);
  }
  return scan;
}

}  // namespace hairfit
