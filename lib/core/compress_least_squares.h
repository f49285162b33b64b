// A least-squares block of m residuals in N parameters, compressed to N + 1 residuals that a
// Gauss–Newton or Levenberg–Marquardt solver cannot tell from the original at that point: the
// same ½|r|², gradient Jᵀr, Gauss–Newton matrix JᵀJ, and column norms of J.
#pragma once

namespace hairfit {

// r[m] and jacobian[m × N] (row-major) in; out_r[N + 1] and out_jacobian[(N + 1) × N] (row-major)
// out, with
//   |out_r|² = |r|²,  out_Jᵀ·out_J = JᵀJ,  out_Jᵀ·out_r = Jᵀr   (to round-off).
// Through the Cholesky factor JᵀJ = RᵀR: out_r = (R⁻ᵀJᵀr, ρ), out_J = (R; 0), ρ² = |r|² − |R⁻ᵀJᵀr|²
// (the part of r outside J's range). When JᵀJ is singular or nearly so (Cholesky squares J's
// condition number), by Householder QR J = QR instead: out_r = (first rows of Qᵀr, |rest|).
// Returns false (and writes nothing) if an input is not finite.
// Instantiated for N = 6, 9, 12 and 15 (the guides' six loads and 1–3 interior point forces).
template <int N>
bool compress_least_squares(int m, const double* r, const double* jacobian, double* out_r, double* out_jacobian);

}  // namespace hairfit
