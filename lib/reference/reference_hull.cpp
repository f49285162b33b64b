#include "reference/reference_hull.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "field/distance_field.h"
#include "prepare/marching_tetrahedra.h"

namespace hairfit {

namespace {

// The two meshes as one soup (the distance field reads any soup).
Mesh joined(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const int offset = static_cast<int>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (const Vec3i& t : b.triangles) m.triangles.push_back(t + Vec3i::Constant(offset));
  return m;
}

// Marks every node with a positive value that a 6-connected path of positive nodes joins to the
// grid's faces: the outside. Positive nodes not marked are enclosed.
std::vector<char> outside_nodes(const SampleGrid& grid, const std::vector<double>& values) {
  std::vector<char> outside(values.size(), 0);
  std::vector<std::int64_t> stack;
  const Vec3i d = grid.dims;
  auto push = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= d.x() || j >= d.y() || k >= d.z()) return;
    const std::int64_t n = grid.node(i, j, k);
    if (outside[n] || !(values[n] > 0.0)) return;
    outside[n] = 1;
    stack.push_back(n);
  };
  for (int k = 0; k < d.z(); ++k)
    for (int j = 0; j < d.y(); ++j)
      for (int i = 0; i < d.x(); ++i)
        if (i == 0 || j == 0 || k == 0 || i == d.x() - 1 || j == d.y() - 1 || k == d.z() - 1) push(i, j, k);
  while (!stack.empty()) {
    const std::int64_t n = stack.back();
    stack.pop_back();
    const int i = static_cast<int>(n % d.x()), j = static_cast<int>((n / d.x()) % d.y()),
              k = static_cast<int>(n / (std::int64_t(d.x()) * d.y()));
    push(i - 1, j, k), push(i + 1, j, k), push(i, j - 1, k), push(i, j + 1, k), push(i, j, k - 1), push(i, j, k + 1);
  }
  return outside;
}

}  // namespace

ReferenceHull reference_hull(const Mesh& hair, const Mesh& scalp, const ReferenceHullOptions& o) {
  if (!(o.voxel > 0.0) || !(o.dilation > 0.0))
    throw std::invalid_argument("reference_hull: needs voxel > 0 and dilation > 0");
  FieldSpec spec;
  spec.voxel = o.voxel;
  spec.band = std::ceil(o.dilation / o.voxel) + 2.0;  // exact distances wherever the zero set can be
  spec.margin = o.dilation + 2.0 * o.voxel;           // the occupancy stays off the grid's faces
  spec.name = "reference hair";
  const DistanceField field = make_distance_field(joined(hair, scalp), spec, o.threads);

  SampleGrid grid;
  grid.origin = field.origin();
  grid.spacing = field.voxel();
  grid.dims = field.dims();
  std::vector<double> values(grid.nodes());
  ReferenceHull hull;
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const double v = std::abs(field.sample(i, j, k)) - o.dilation;
        values[grid.node(i, j, k)] = v;
        hull.occupied_nodes += v <= 0.0;
      }
  const std::vector<char> outside = outside_nodes(grid, values);
  for (std::int64_t n = 0; n < grid.nodes(); ++n)
    if (values[n] > 0.0 && !outside[n]) {
      values[n] = -o.voxel;
      ++hull.filled_nodes;
    }
  hull.mesh = marching_tetrahedra(grid, values).mesh;
  return hull;
}

}  // namespace hairfit
