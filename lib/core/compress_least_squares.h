// A least-squares block of m residuals in 6 parameters, compressed to 7 residuals that a
// Gauss–Newton or Levenberg–Marquardt solver cannot tell from the original at that point: the
// same ½|r|², gradient Jᵀr, Gauss–Newton matrix JᵀJ, and column norms of J.
#pragma once

namespace hairfit {

// r[m] and jacobian[m × 6] (row-major) in; out_r[7] and out_jacobian[7 × 6] (row-major) out, with
//   |out_r|² = |r|²,  out_Jᵀ·out_J = JᵀJ,  out_Jᵀ·out_r = Jᵀr   (to round-off).
// Through the Cholesky factor JᵀJ = RᵀR: out_r = (R⁻ᵀJᵀr, ρ), out_J = (R; 0), ρ² = |r|² − |R⁻ᵀJᵀr|²
// (the part of r outside J's range). When JᵀJ is singular or nearly so (Cholesky squares J's
// condition number), by Householder QR J = QR instead: out_r = (first rows of Qᵀr, |rest|).
// Returns false (and writes nothing) if an input is not finite.
bool compress_least_squares(int m, const double* r, const double* jacobian, double* out_r, double* out_jacobian);

}  // namespace hairfit
