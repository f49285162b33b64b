// Trilinear interpolation over one grid cell, for every grid of the library (the distance fields'
// nodes, the density grids' cells). Corners are numbered c[x + 2y + 4z]; f ∈ [0,1]³ is the point's
// fraction of the cell. It comes in two arithmetic forms of the same interpolant, each where its
// rounding is relied on:
// - trilinear: nested linear blends, the value and (kGradient) its derivative in f from the same
//   expressions, so that a field's value() and value_and_gradient() agree bit for bit;
// - trilinear_weights: the eight corner weights and their derivatives in f, for sums over corners
//   of other per-corner quantities (a density grid's blended central differences and their
//   Jacobian read the derivatives of the weights themselves).
#pragma once
#include "core/types.h"

namespace hairfit {

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

struct TrilinearWeights {
  double w[8];   // Σ w = 1
  Vec3 dw[8];    // ∂w/∂f
};

inline TrilinearWeights trilinear_weights(const Vec3& f) {
  TrilinearWeights out;
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    const double wx = dx ? f.x() : 1.0 - f.x();
    const double wy = dy ? f.y() : 1.0 - f.y();
    const double wz = dz ? f.z() : 1.0 - f.z();
    const double sx = dx ? 1.0 : -1.0, sy = dy ? 1.0 : -1.0, sz = dz ? 1.0 : -1.0;
    out.w[c] = wx * wy * wz;
    out.dw[c] = Vec3(sx * wy * wz, wx * sy * wz, wx * wy * sz);
  }
  return out;
}

}  // namespace hairfit
