// What the field's lookups and its far-field fill both do with the 8 corners of a grid cell
// (c[x + 2y + 4z]): the trilinear interpolation (core/trilinear.h) and the seam test. Internal to
// lib/field.
#pragma once
#include <cmath>

#include "core/trilinear.h"
#include "core/types.h"

namespace hairfit::field {

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
