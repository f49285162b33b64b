#include "field/hair_region.h"

#include <cmath>

namespace hairfit {

HairRegion::HairRegion(const Mesh& hull, const Mesh& scalp, bool hull_closed)
    : hull_(hull, kFirstBeta), scalp_(hull_closed ? Mesh{} : scalp, kFirstBeta), closed_(hull_closed) {}

double HairRegion::winding(const Vec3& p) const { return closed_ ? hull_(p) : hull_(p) - scalp_(p); }

bool HairRegion::inside_hull(const Vec3& p) const {
  const double value = winding(p);
  if (std::abs(value - 0.5) > kDecisive) return value > 0.5;
  const double close = closed_ ? hull_.at_beta(p, kCloseBeta) : hull_.at_beta(p, kCloseBeta) - scalp_.at_beta(p, kCloseBeta);
  return close > 0.5;
}

bool winding_above_half(const FastWindingNumber& winding, const Vec3& p) {
  const double value = winding(p);
  if (std::abs(value - 0.5) > HairRegion::kDecisive) return value > 0.5;
  return winding.at_beta(p, HairRegion::kCloseBeta) > 0.5;
}

Mesh closed_head(const Mesh& scalp) {
  const MeshTopology topology = analyse_topology(scalp);
  Mesh head = scalp;
  for (const std::vector<int>& loop : topology.boundary_loops) {
    // Boundary loops run along the triangles' turning (a→b on the scalp), so the floor runs b→a.
    Vec3 centre = Vec3::Zero();
    for (int v : loop) centre += scalp.positions[v];
    centre /= static_cast<double>(loop.size());
    const int hub = static_cast<int>(head.positions.size());
    head.positions.push_back(centre);
    for (std::size_t k = 0; k < loop.size(); ++k) head.triangles.push_back({loop[(k + 1) % loop.size()], loop[k], hub});
  }
  return head;
}

}  // namespace hairfit
