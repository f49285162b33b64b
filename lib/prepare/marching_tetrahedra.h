// The zero set of a sampled scalar field as a triangle mesh: marching tetrahedra on the Kuhn
// (Freudenthal) split of every grid cell into six tetrahedra along its main diagonal. The field is
// taken piecewise linear on those tetrahedra, so its zero set is exactly a union of planar
// triangles and quadrilaterals, one per tetrahedron it crosses: neighbouring tetrahedra share
// faces and the split is the same in every cell, so the pieces meet edge to edge (no cracks, no
// ambiguous cases) and never cross each other. Two fields sampled on the same grid whose
// difference is one-signed inside a tetrahedron give zero sets that do not meet there.
#pragma once
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct SampleGrid {
  Vec3 origin = Vec3::Zero();  // node (0, 0, 0)
  double spacing = 1.0;        // h > 0
  Vec3i dims = Vec3i::Zero();  // nodes per axis (≥ 2 for any cell)
  std::int64_t node(int i, int j, int k) const { return i + std::int64_t(dims.x()) * (j + std::int64_t(dims.y()) * k); }
  std::int64_t nodes() const { return std::int64_t(dims.x()) * dims.y() * dims.z(); }
  Vec3 position(int i, int j, int k) const { return origin + spacing * Vec3(i, j, k); }
  Vec3 position(std::int64_t n) const;
};

// Where an output vertex lies: on the grid edge from node a to node b, at a + t·(b − a), so a
// caller interpolates any other per-node quantity there as (1 − t)·q[a] + t·q[b].
struct EdgePoint {
  std::int64_t a = 0, b = 0;
  double t = 0.0;
};

struct ZeroSet {
  Mesh mesh;                   // oriented with normals toward increasing value
  std::vector<EdgePoint> at;   // per vertex
};

// values[grid.node(i, j, k)]: a node counts as negative where its value is < 0 (a value of exactly
// 0 is read as 10⁻⁷·h, so no vertex lands on a node). Vertices are
// shared between the tetrahedra around an edge, so the mesh is a manifold wherever the zero set
// is (a closed one where the negative region stays off the grid's faces). Deterministic: cells in
// x-fastest order.
ZeroSet marching_tetrahedra(const SampleGrid& grid, const std::vector<double>& values);

}  // namespace hairfit
