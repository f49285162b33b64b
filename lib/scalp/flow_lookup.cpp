#include "scalp/flow_lookup.h"

#include <cmath>

namespace hairfit {

namespace {

constexpr double kCellsPerRadius = 4.0;

}  // namespace

// Per occupied cell of a PointGrid radius / kCellsPerRadius wide (in its cell order) the mean
// position of its vertices and the sums of their directions and normals.
FlowLookup::Gathered FlowLookup::gather(const Mesh& scalp, const std::vector<Vec3>& normals, const DirectionField& field, double radius) {
  const PointGrid cells(scalp.positions, radius / kCellsPerRadius, false);
  Gathered g;
  for (int k = 0; k < cells.cell_count(); ++k) {
    Vec3 position = Vec3::Zero(), direction = Vec3::Zero(), normal = Vec3::Zero();
    for (int i = cells.cell_begin(k); i < cells.cell_begin(k + 1); ++i) {
      const int v = cells.order()[i];
      position += scalp.positions[v];
      direction += field.directions[v];
      normal += normals[v];
    }
    g.positions.push_back(position / static_cast<double>(cells.cell_begin(k + 1) - cells.cell_begin(k)));
    g.directions.push_back(direction);
    g.normals.push_back(normal);
  }
  return g;
}

FlowLookup::FlowLookup(const Mesh& scalp, const std::vector<Vec3>& normals, const DirectionField& field, double radius)
    : FlowLookup(gather(scalp, normals, field, radius), radius) {}

FlowLookup::FlowLookup(Gathered g, double radius)
    : positions_(std::move(g.positions)), normals_(std::move(g.normals)), directions_(std::move(g.directions)),
      grid_(positions_, radius), radius_(radius) {}

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
