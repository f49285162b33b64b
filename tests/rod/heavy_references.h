// An independent reference for the planar heavy cantilever, by a second method: Chebyshev
// spectral collocation of θ'' = w·(1 − s)·cos θ on s ∈ [0, 1] (the angle θ of the tangent from the
// horizontal clamp, EI = L = 1, gravity −w per length along y), θ(0) = 0, θ'(1) = 0, on subdomains
// that resolve the root's boundary layer of width ~ 1/√w, with Newton on the dense collocation
// system and continuation in w. Nothing here calls the rod solver.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.h"

namespace hairfit::test {

struct HeavyTip {
  double x;  // tip position, units of L
  double y;
};

// Chebyshev points x_j = cos(πj/n) on [−1, 1] and the differentiation matrix (Trefethen, Spectral
// Methods in MATLAB, cheb.m), mapped to [a, b].
struct ChebyshevPiece {
  Eigen::VectorXd s;  // points, descending from b to a
  Eigen::MatrixXd d;  // d/ds
  Eigen::VectorXd w;  // Clenshaw–Curtis weights on [a, b]
};

inline ChebyshevPiece chebyshev_piece(double a, double b, int n) {
  constexpr double pi = 3.14159265358979323846;
  Eigen::VectorXd x(n + 1), c(n + 1);
  for (int j = 0; j <= n; ++j) {
    x[j] = std::cos(pi * j / n);
    c[j] = (j == 0 || j == n ? 2.0 : 1.0) * (j % 2 ? -1.0 : 1.0);
  }
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n + 1, n + 1);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      if (i != j) d(i, j) = (c[i] / c[j]) / (x[i] - x[j]);
  for (int i = 0; i <= n; ++i) d(i, i) = -d.row(i).sum();
  // Clenshaw–Curtis weights (Trefethen's clencurt.m, n even).
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n + 1);
  for (int j = 0; j <= n; ++j) {
    const double theta = pi * j / n;
    double v = 1.0;
    for (int k = 1; k < n / 2; ++k) v -= 2.0 * std::cos(2.0 * k * theta) / (4.0 * k * k - 1.0);
    v -= std::cos(n * theta) / (static_cast<double>(n) * n - 1.0);
    w[j] = (j == 0 || j == n ? 1.0 : 2.0) * v / n;
  }
  ChebyshevPiece piece;
  const double half = 0.5 * (b - a);
  piece.s = (a + b) * 0.5 + half * x.array();
  piece.d = d / half;
  piece.w = w * half;
  return piece;
}

inline HeavyTip heavy_cantilever_reference(double weight, int points = 48) {
  std::vector<double> edges{0.0};
  for (double e : {2.0 / std::sqrt(weight), 8.0 / std::sqrt(weight), 0.3})
    if (e > edges.back() + 1e-3 && e < 1.0 - 1e-3) edges.push_back(e);
  edges.push_back(1.0);
  std::vector<ChebyshevPiece> pieces;
  for (std::size_t p = 0; p + 1 < edges.size(); ++p) pieces.push_back(chebyshev_piece(edges[p], edges[p + 1], points));
  const int m = points + 1, count = static_cast<int>(pieces.size()) * m;
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(count);
  // Continuation in w from a tenth of a unit, a factor 1.5 a level.
  std::vector<double> levels;
  for (double level = std::min(weight, 0.1); level < weight; level *= 1.5) levels.push_back(level);
  levels.push_back(weight);
  for (double level : levels) {
    for (int iteration = 0; iteration < 60; ++iteration) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(count);
      Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(count, count);
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        const ChebyshevPiece& q = pieces[p];
        const int o = static_cast<int>(p) * m;
        const Eigen::MatrixXd d2 = q.d * q.d;
        const Eigen::VectorXd t = theta.segment(o, m);
        const Eigen::VectorXd r = d2 * t;
        // Interior rows: θ'' − w(1 − s)cos θ = 0. Row 0 is the piece's right end, row m−1 its left.
        for (int i = 1; i + 1 < m; ++i) {
          f[o + i] = r[i] - level * (1.0 - q.s[i]) * std::cos(t[i]);
          jacobian.block(o + i, o, 1, m) = d2.row(i);
          jacobian(o + i, o + i) += level * (1.0 - q.s[i]) * std::sin(t[i]);
        }
        // Left end: θ(0) = 0 for the first piece, else θ' continuous with the piece before.
        if (p == 0) {
          f[o + m - 1] = t[m - 1];
          jacobian(o + m - 1, o + m - 1) = 1.0;
        } else {
          const ChebyshevPiece& before = pieces[p - 1];
          const int ob = o - m;
          f[o + m - 1] = q.d.row(m - 1).dot(t) - before.d.row(0).dot(theta.segment(ob, m));
          jacobian.block(o + m - 1, o, 1, m) = q.d.row(m - 1);
          jacobian.block(o + m - 1, ob, 1, m) = -before.d.row(0);
        }
        // Right end: θ'(1) = 0 for the last piece, else θ continuous with the next piece's left end.
        if (p + 1 == pieces.size()) {
          f[o] = q.d.row(0).dot(t);
          jacobian.block(o, o, 1, m) = q.d.row(0);
        } else {
          f[o] = t[0] - theta[o + 2 * m - 1];
          jacobian(o, o) = 1.0;
          jacobian(o, o + 2 * m - 1) = -1.0;
        }
      }
      const Eigen::VectorXd step = jacobian.partialPivLu().solve(-f);
      theta += step;
      if (step.lpNorm<Eigen::Infinity>() < 1e-14) break;
    }
  }
  HeavyTip tip{0.0, 0.0};
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (int i = 0; i < m; ++i) {
      const double t = theta[static_cast<int>(p) * m + i];
      tip.x += pieces[p].w[i] * std::cos(t);
      tip.y += pieces[p].w[i] * std::sin(t);
    }
  return tip;
}

}  // namespace hairfit::test
