#include "field/hair_region.h"

namespace hairfit {

HairRegion::HairRegion(const Mesh& hull, const Mesh& scalp, bool hull_closed, int threads)
    : hull_(hull, kFirstBeta, threads), scalp_(hull_closed ? Mesh{} : scalp, kFirstBeta, threads), closed_(hull_closed) {}

double HairRegion::winding(const Vec3& p) const { return closed_ ? hull_(p) : hull_(p) - scalp_(p); }

WindingEstimate HairRegion::estimate(const Vec3& p, double beta) const {
  const WindingEstimate e = hull_.estimate(p, beta);
  if (closed_) return e;
  const WindingEstimate under = scalp_.estimate(p, beta);
  return WindingEstimate{e.value - under.value, e.error_bound + under.error_bound};
}

void HairRegion::estimate_box(const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) const {
  hull_.estimate_box(points, beta, out);
  if (closed_) return;
  std::vector<WindingEstimate> under;
  scalp_.estimate_box(points, beta, under);
  for (std::size_t q = 0; q < out.size(); ++q)
    out[q] = WindingEstimate{out[q].value - under[q].value, out[q].error_bound + under[q].error_bound};
}

bool HairRegion::inside_hull(const Vec3& p) const {
  if (closed_) return hull_.above(p, 0.5);
  return certified_above(
      0.5, kFirstBeta, [&](double beta) { return estimate(p, beta); },
      [&] { return hull_.direct(p) - scalp_.direct(p); });
}

bool winding_above_half(const FastWindingNumber& winding, const Vec3& p) { return winding.above(p, 0.5); }

WindingSoup HairRegion::soup(const Mesh& hull, const Mesh& scalp) const {
  WindingSoup s;
  s.parts.push_back({&hull, 1});
  if (!closed_) s.parts.push_back({&scalp, -1});
  s.estimate = [this](const Vec3& p) { return estimate(p, kCloseBeta); };
  s.above_half = [this](const Vec3& p) { return inside_hull(p); };
  s.estimate_box = [this](const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) {
    estimate_box(points, beta, out);
  };
  return s;
}

WindingSoup winding_soup(const Mesh& mesh, const FastWindingNumber& winding) {
  return {{{&mesh, 1}},
          [&winding](const Vec3& p) { return winding.estimate(p, HairRegion::kCloseBeta); },
          [&winding](const Vec3& p) { return winding_above_half(winding, p); },
          [&winding](const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) {
            winding.estimate_box(points, beta, out);
          }};
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
