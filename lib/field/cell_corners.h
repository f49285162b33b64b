// What the field's lookups and its far-field fill both do with the 8 corners of a grid cell
// (c[x + 2y + 4z]). Internal to lib/field.
#pragma once
#include <cmath>

#include "core/types.h"

namespace hairfit::field {

// Trilinear interpolation of the 8 corner values at fractions f ∈ [0,1]³, and (kGradient) its
// derivative with respect to f. The value is the same expression either way, so value() and
// value_and_gradient() agree bit for bit.
template <bool kGradient>
void trilinear(const double c[8], const double f[3], double& value, Vec3* gradient) {
  const double x0 = 1 - f[0], y0 = 1 - f[1], z0 = 1 - f[2];
  const double c00 = c[0] * x0 + c[1] * f[0], c10 = c[2] * x0 + c[3] * f[0];
  const double c01 = c[4] * x0 + c[5] * f[0], c11 = c[6] * x0 + c[7] * f[0];
  const double c0 = c00 * y0 + c10 * f[1], c1 = c01 * y0 + c11 * f[1];
  value = c0 * z0 + c1 * f[2];
  if constexpr (kGradient) {
    gradient->z() = c1 - c0;
    gradient->y() = (c10 - c00) * z0 + (c11 - c01) * f[2];
    const double dx00 = c[1] - c[0], dx10 = c[3] - c[2], dx01 = c[5] - c[4], dx11 = c[7] - c[6];
    gradient->x() = (dx00 * y0 + dx10 * f[1]) * z0 + (dx01 * y0 + dx11 * f[1]) * f[2];
  }
}

// Whether a cell of edge `spacing` whose signed corner distances are c is a seam of the inside:
// corners of both signs, but no pair of opposite sign that a surface could pass between, since a
// surface point x on the segment between corners a and b would make |d_a| + |d_b| ≤ |a − x| +
// |x − b| = |a − b|. False for a cell whose corners all share a sign.
inline bool is_seam(const double c[8], double spacing) {
  bool mixed = false;
  for (int a = 0; a < 8; ++a) {
    if (!(c[a] > 0)) continue;
    for (int b = 0; b < 8; ++b) {
      if (!(c[b] < 0)) continue;
      mixed = true;
      const int differ = ((a ^ b) & 1) + ((a ^ b) >> 1 & 1) + ((a ^ b) >> 2 & 1);
      if (c[a] - c[b] <= spacing * std::sqrt(double(differ)) * (1 + 1e-9)) return false;
    }
  }
  return mixed;
}

}  // namespace hairfit::field
