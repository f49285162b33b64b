// A field sampled from an analytic function, for tests of what reads distance fields.
#pragma once
#include <utility>

#include "field/distance_field.h"

namespace hairfit::test {

// f sampled on the grid origin + h·(i, j, k), dims n³; no band or seam flags, so lookups are the
// plain trilinear interpolant of the samples.
template <class F>
DistanceField sampled(const F& f, const Vec3& origin, double h, int n) {
  DistanceFieldParts parts;
  parts.origin = origin;
  parts.voxel = h;
  parts.dims = Vec3i(n, n, n);
  parts.band_width = 0.0;
  parts.samples.resize(static_cast<std::size_t>(n) * n * n);
  parts.flags.assign(parts.samples.size(), 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) parts.samples[i + n * (j + n * k)] = f(origin + h * Vec3(i, j, k));
  return DistanceField::from_parts(std::move(parts));
}

}  // namespace hairfit::test
