#include "field/hair_region.h"

#include <cmath>

namespace hairfit {

HairRegion::HairRegion(const Mesh& hull, const Mesh& scalp, bool hull_closed)
    : hull_(hull), scalp_(hull_closed ? Mesh{} : scalp), closed_(hull_closed) {}

double HairRegion::winding(const Vec3& p) const { return closed_ ? hull_(p) : hull_(p) - scalp_(p); }

bool HairRegion::inside_hull(const Vec3& p) const {
  const WindingEstimate h = hull_.estimate(p);
  if (closed_) return std::abs(h.value - 0.5) > h.error_bound ? h.value > 0.5 : hull_.direct(p) > 0.5;
  const WindingEstimate s = scalp_.estimate(p);
  const double value = h.value - s.value;
  if (std::abs(value - 0.5) > h.error_bound + s.error_bound) return value > 0.5;
  return hull_.direct(p) - scalp_.direct(p) > 0.5;
}

}  // namespace hairfit
