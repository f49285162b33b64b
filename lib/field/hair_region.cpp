#include "field/hair_region.h"

#include <cmath>

namespace hairfit {

HairRegion::HairRegion(const Mesh& hull, const Mesh& scalp, bool hull_closed)
    : hull_(hull), scalp_(hull_closed ? Mesh{} : scalp), closed_(hull_closed) {}

double HairRegion::winding(const Vec3& p) const { return closed_ ? hull_(p) : hull_(p) - scalp_(p); }

bool HairRegion::inside_hull(const Vec3& p) const {
  const double value = winding(p);
  if (std::abs(value - 0.5) > kDecisive) return value > 0.5;
  return closed_ ? hull_.direct(p) > 0.5 : hull_.direct(p) - scalp_.direct(p) > 0.5;
}

}  // namespace hairfit
