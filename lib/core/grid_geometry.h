// A regular lattice: nodes origin + voxel·(i, j, k) for 0 ≤ i < dims.x() and so on, x fastest. A
// distance field samples at its nodes; a density grid reads node (i, j, k) as the lower corner of
// its cell (i, j, k), the box node(i, j, k) … node(i+1, j+1, k+1), whose value sits at its centre.
#pragma once
#include <cmath>
#include <cstdint>

#include "core/types.h"

namespace hairfit {

// The indices (i, j, k) of entry n of a grid of `dims` laid out x fastest, then y, then z.
inline Vec3i grid_indices(int64_t n, const Vec3i& dims) {
  const int64_t nx = dims.x(), ny = dims.y();
  return Vec3i(int(n % nx), int(n / nx % ny), int(n / (nx * ny)));
}

struct GridGeometry {
  Vec3 origin = Vec3::Zero();  // cm: node (0,0,0)
  double voxel = 1.0;          // cm: the spacing h
  Vec3i dims = Vec3i::Zero();  // nodes (cells) along x, y, z

  int64_t count() const { return int64_t(dims.x()) * dims.y() * dims.z(); }
  // x fastest, then y, then z (the NRRD order).
  int64_t index(int i, int j, int k) const { return i + int64_t(dims.x()) * (j + int64_t(dims.y()) * k); }
  Vec3i indices(int64_t n) const { return grid_indices(n, dims); }  // index's inverse
  bool contains(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < dims.x() && j < dims.y() && k < dims.z();
  }
  Vec3 node(int i, int j, int k) const { return origin + voxel * Vec3(i, j, k); }
  Vec3 node(int64_t n) const { return origin + voxel * indices(n).cast<double>(); }  // node(index(i, j, k))

  // Read as cells:
  Vec3 cell_centre(int i, int j, int k) const { return origin + voxel * Vec3(i + 0.5, j + 0.5, k + 0.5); }
  Vec3 upper() const { return origin + voxel * dims.cast<double>(); }  // cm: the far corner of the last cell
  double cell_diagonal() const { return voxel * std::sqrt(3.0); }     // cm: h·√3, the CDM normaliser
};

}  // namespace hairfit
