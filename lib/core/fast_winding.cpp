#include "core/fast_winding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/parallel.h"

// The far field. With F(y) = y/|y|³, a triangle's solid angle seen from p is ∫ n·F(x − p) dA.
// Expanding F about a centre c, with r = c − p and d = x − c, to first order,
//   n·F(r + d) ≈ n·r/|r|³ + nᵀ (I/|r|³ − 3 r rᵀ/|r|⁵) d,
// and integrating over triangles (n is constant on each, so ∫ n dA = a_t n_t and
// ∫ n dᵀ dA = a_t n_t (g_t − c)ᵀ exactly) gives their solid angle to second order:
//   Ω ≈ (N·r + tr M)/|r|³ − 3 rᵀ M r/|r|⁵,  N = Σ a_t n_t,  M = Σ a_t n_t (g_t − c)ᵀ.
// About a single triangle's centroid M = 0.
//
// Its error, with D = |r|, R the radius of a ball about c holding the triangles, ρ = R/D < 1 and
// Q = ∫ |d|² dA; both bounds below are rigorous and the smaller is taken.
// (1) Taylor: along the segment c→x (inside the ball, so |ξ − p| ≥ D − R) the remainder is
// ½ dᵀ H d with H_jk = −n_i ∂i∂j∂k(1/|y|) at y = ξ − p. With ŷ = y/|y|, α = ŷ·n, μ = ŷ·u for a
// unit u and γ = n·u, |y|⁴ ∂³(1/|y|)[n, u, u] = −15 α μ² + 6 μ γ + 3 α. Writing
// γ = α μ + √((1 − α²)(1 − μ²)) cos φ, this is α (3 − 9 μ²) + 6 μ √((1 − α²)(1 − μ²)) cos φ,
// at most √((3 − 9 μ²)² + 36 μ² (1 − μ²)) = √(9 − 18 μ² + 45 μ⁴) in magnitude over α and φ:
// convex in μ², so at most its value 6 at μ² = 1. Hence the remainder is within
// 3 |d|²/(D − R)⁴ at x and within 3 Q/(D − R)⁴ = Q/D⁴ · 3/(1 − ρ)⁴ over the triangles: K = 3 in
// the form A R² K/(4π (D − R)⁴), as Q ≤ A R² (bounding the three terms one by one gives 12).
// (2) Multipoles: 1/|r + d| = Σ_l H_l(d), H_l homogeneous harmonic of degree l with
// |H_l| = |d|^l |P_l(cos θ)|/D^(l+1), and the expansion keeps the degrees 0 and 1 of
// n·F = −n·∇_d(1/|r + d|), i.e. l = 1, 2. In spherical coordinates
// |∇H_l|² D^(2l+2)/|d|^(2l−2) = l² P_l² + (1 − t²) P_l'², and g = P_l² + (1 − t²) P_l'²/(l(l+1))
// has g' = 2 t P_l'²/(l(l+1)) (Legendre's equation), so g ≤ g(±1) = 1 and
// |∇H_l| ≤ √(l(l+1)) |d|^(l−1)/D^(l+1). The remainder at x is within
// Σ_{l≥3} √(l(l+1)) |d|^(l−1)/D^(l+1), which over |d|² increases with |d| ≤ R, so over the
// triangles within Q/D⁴ · (√12 + Σ_{k≥1} (k + 3.5) ρ^k) = Q/D⁴ · (√12 + ρ/(1 − ρ)² + 3.5 ρ/(1 − ρ))
// (√(l(l+1)) ≤ l + ½). At ρ = ½ that is 9.0 against (1)'s 48.
//
// Round-off, to first order in the unit round-off u. A far triangle's |Ω_t| ≤ a_t/(D − R)² and
// an expansion's magnitude is at most (1 + 4ρ) A/D² ≤ 5 A/(D − R)² (|N| ≤ A, |tr M|, |rᵀ M r|/D²
// ≤ A R), so S = Σ_near |Ω_t| + 5 Σ_far A/(D − R)² bounds the Σ|terms| of both sums. The direct
// sum of n terms and the fast one of m terms are each within (count − 1) u S of their exact
// values; the coefficients, each a sum over at most n triangles, are within n u S in effect;
// the expansions' few dozen operations within 128 u S. A far triangle's computed solid angle,
// which only the direct sum evaluates, is off by twice (|δ num| + |δ den|)/|(num, den)| plus a
// few ulps: with a, b, c its vertices relative to p, |(num, den)|² = 2 (1 + â·b̂)(1 + b̂·ĉ)(1 + ĉ·â)
// |a|²|b|²|c|², each 1 + cos ≥ 2 (1 − 1/beta²) as the vertices lie within asin(1/beta) of the
// direction of the centre, and the perturbations are within 128 u |a||b||c| (about 90 by a term
// by term count). The near triangles' terms are the same function of the same numbers in both
// sums and agree bit for bit.
//
// A ball of points (estimate_box): centre c, radius ρ_b, a node at centre m, r₀ = m − c, D₀ = |r₀|.
// For p in the ball, x − p = r₀ + d′ with d′ = (x − m) − (p − c), |d′| ≤ R + ρ_b, so the first-order
// expansion in d′ about r₀ gives Ω(p) ≈ Ω_exp(c) − (N/D₀³ − 3 (N·r₀) r₀/D₀⁵)·(p − c): the node's
// usual expansion at c plus a linear term, one linear function per ball. Both bounds above hold
// with d′ for d, R + ρ_b for R and D₀ for D ((1): the segment r₀ → r₀ + d′ stays D₀ − R − ρ_b from
// the origin; (2): the series is in d′, |d′| ≤ R + ρ_b), with ∫|d′|² dA for Q, and
// ∫|d′|² dA = Q + |p − c|² A − 2 (p − c)·∫(x − m) dA, whose last term vanishes as m is the
// area-weighted centroid (up to its rounding, which kCentroid allows for).
// Its magnitude is at most (1 + 4ρ′ + 2ρ′) A/D₀² with ρ′ = (R + ρ_b)/D₀ < 1, under 8 A/(D₀ − R − ρ_b)²
// in the round-off allowance; at every point of the ball the node is beyond beta × R, so the far
// triangles' round-off allowance is the same.

namespace hairfit {

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;
constexpr int kLeafSize = 8;
constexpr int kStackSize = 64;  // the tree's depth is at most log2(triangles) + 1 ≤ 32

// The expansion's remainder bound over Q/D⁴, at ρ = R/D < 1, given s = 1/(1 − ρ).
inline double remainder_factor(double rho, double s) {
  const double taylor = 3.0 * (s * s) * (s * s);
  const double multipole = std::sqrt(12.0) + rho * s * (s + 3.5);
  return std::min(taylor, multipole);
}

}  // namespace

// What a traversal accumulates; without kBound the value alone, summed in the same order and so
// the same bits.
template <bool kBound>
struct FastWindingNumber::Sums {
  double solid_angle = 0.0;  // in traversal order
  double truncation = 0.0;   // the expansions' remainder bounds
  double near_abs = 0.0;     // Σ |Ω_t| over the triangles summed directly
  double far_abs = 0.0;      // Σ A/(D − R)² over the expansions
  double terms = 0.0;
  double far_triangles = 0.0;

  void add_direct(double omega) {
    solid_angle += omega;
    if (kBound) {
      near_abs += std::fabs(omega);
      terms += 1.0;
    }
  }
  // One expansion, at distance d from its centre: `numerator` is N·r (+ tr M − 3 rᵀ M r/d²) and
  // inv_d3 = 1/d³.
  void add_expansion(double numerator, double inv_d3, double d, const Extent& e, int count) {
    solid_angle += numerator * inv_d3;
    if (kBound) {
      // d > beta R > R; should rounding leave no gap, the bound is infinite (and so still a bound).
      const double gap = std::max(d - e.radius, 0.0), inv_gap = 1.0 / gap;
      const double inv_d = 1.0 / d, inv_d2 = inv_d * inv_d, s = d * inv_gap;  // s = 1/(1 − ρ)
      truncation += e.second * (inv_d2 * inv_d2) * remainder_factor(e.radius * inv_d, s);
      far_abs += e.area * (inv_gap * inv_gap);
      terms += 1.0;
      far_triangles += count;
    }
  }
};

struct FastWindingNumber::Summary {
  Corners corners;
  Triangle triangle;
  Extent extent;
};

FastWindingNumber::FastWindingNumber(const Mesh& mesh, double beta, int threads)
    : beta_(beta), size_(mesh.triangles.size()) {
  if (!(beta > 1.0)) throw std::invalid_argument("FastWindingNumber: beta must exceed 1");
  const double kappa = std::sqrt(2.0) * std::pow(2.0 - 2.0 / (beta * beta), 1.5);
  far_roundoff_ = 8.0 + 256.0 / kappa;

  // Zero-area triangles have solid angle 0 from everywhere off them: they are left out.
  const int n = static_cast<int>(mesh.triangles.size());
  std::vector<Summary> summaries(n);
  std::vector<char> kept(n, 0);
  threads = resolve_thread_count(threads);
  parallel_for_ranges(n, 4096, threads, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const Vec3i& f = mesh.triangles[i];
      Summary& t = summaries[i];
      const Vec3 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
      t.corners = {a, b, c};
      t.triangle.vector_area = 0.5 * (b - a).cross(c - a);
      if (t.triangle.vector_area == Vec3::Zero()) continue;
      const Vec3 g = (a + b + c) / 3.0, da = a - g, db = b - g, dc = c - g;
      t.triangle.ball.centre = g;
      t.extent.area = t.triangle.vector_area.norm();
      // ∫ (x − g)(x − g)ᵀ dA = a/12 Σ_i (v_i − g)(v_i − g)ᵀ over a triangle.
      t.extent.second = t.extent.area / 12.0 * (da.squaredNorm() + db.squaredNorm() + dc.squaredNorm());
      // Enlarged by a few ulps so that the ball holds every vertex despite rounding.
      t.extent.radius = std::max({da.norm(), db.norm(), dc.norm()}) * (1.0 + 8.0 * kUnitRoundoff);
      t.triangle.ball.radius2 = t.extent.radius * t.extent.radius;
      kept[i] = 1;
    }
  });
  std::vector<Summary> all;
  all.reserve(n);
  for (int i = 0; i < n; ++i)
    if (kept[i]) all.push_back(summaries[i]);
  std::vector<Summary>().swap(summaries);
  if (all.empty()) return;

  std::vector<int> order(all.size());
  for (int i = 0; i < static_cast<int>(order.size()); ++i) order[i] = i;
  const int node_count = subtree_size(static_cast<int>(order.size()));
  nodes_.resize(node_count);
  node_terms_.resize(node_count);
  node_extents_.resize(node_count);
  // The top levels one level at a time (the nodes of a level split disjoint ranges, so they are
  // built side by side), down to subtrees of at most 1/16 of the triangles, which are then built
  // side by side: every node's place follows from the sizes alone.
  struct Range {
    int lo, hi, index;
  };
  std::vector<Range> level{{0, static_cast<int>(order.size()), 0}}, subtrees;
  const int small = std::max(kLeafSize, static_cast<int>(order.size()) / 16);
  while (!level.empty()) {
    std::vector<Range> split;
    for (const Range& r : level) (r.hi - r.lo <= small ? subtrees : split).push_back(r);
    std::vector<int> mids(split.size());
    parallel_for(static_cast<int>(split.size()), threads, [&](int k) {
      mids[k] = build_node(all, order, split[k].lo, split[k].hi, split[k].index);
    });
    level.clear();
    for (std::size_t k = 0; k < split.size(); ++k) {
      const Range& r = split[k];
      level.push_back({r.lo, mids[k], r.index + 1});
      level.push_back({mids[k], r.hi, r.index + 1 + subtree_size(mids[k] - r.lo)});
    }
  }
  parallel_for(static_cast<int>(subtrees.size()), threads, [&](int k) {
    build_subtree(all, order, subtrees[k].lo, subtrees[k].hi, subtrees[k].index);
  });
  triangles_.reserve(order.size());
  triangle_extents_.reserve(order.size());
  corners_.reserve(order.size());
  for (int i : order) {
    triangles_.push_back(all[i].triangle);
    triangle_extents_.push_back(all[i].extent);
    corners_.push_back(all[i].corners);
  }
}

int FastWindingNumber::subtree_size(int n) { return n <= kLeafSize ? 1 : 1 + subtree_size(n / 2) + subtree_size(n - n / 2); }

int FastWindingNumber::build_node(const std::vector<Summary>& all, std::vector<int>& order, int lo, int hi, int index) {
  Node node;
  Terms terms;
  Extent extent;
  node.first = lo;
  node.count = hi - lo;

  Vec3 weighted = Vec3::Zero();
  for (int i = lo; i < hi; ++i) {
    extent.area += all[order[i]].extent.area;
    weighted += all[order[i]].extent.area * all[order[i]].triangle.ball.centre;
  }
  const Vec3 centre = weighted / extent.area;
  terms.normal = Vec3::Zero();
  terms.moment = Mat3::Zero();
  double radius2 = 0.0;
  for (int i = lo; i < hi; ++i) {
    const Summary& t = all[order[i]];
    const Vec3 offset = t.triangle.ball.centre - centre;
    terms.normal += t.triangle.vector_area;
    terms.moment += t.triangle.vector_area * offset.transpose();
    extent.second += t.extent.second + t.extent.area * offset.squaredNorm();  // parallel axes
    for (const Vec3* v : {&t.corners.a, &t.corners.b, &t.corners.c})
      radius2 = std::max(radius2, (*v - centre).squaredNorm());
  }
  // The largest distance to a corner: sqrt is monotone and correctly rounded, so the root of the
  // largest square is the largest root.
  extent.radius = std::sqrt(radius2) * (1.0 + 8.0 * kUnitRoundoff);
  terms.trace = terms.moment.trace();
  node.ball = {centre, extent.radius * extent.radius};

  int mid = -1;
  if (hi - lo <= kLeafSize) {
    std::sort(order.begin() + lo, order.begin() + hi);  // a leaf keeps the mesh's order
  } else {
    // Median split along the longest side of the centroids' box; ties broken by index, so the
    // halves are the same sets whatever the standard library's nth_element does.
    Vec3 low = Vec3::Constant(INFINITY), high = Vec3::Constant(-INFINITY);
    for (int i = lo; i < hi; ++i) {
      low = low.cwiseMin(all[order[i]].triangle.ball.centre);
      high = high.cwiseMax(all[order[i]].triangle.ball.centre);
    }
    int axis = 0;
    (high - low).maxCoeff(&axis);
    mid = lo + (hi - lo) / 2;
    std::nth_element(order.begin() + lo, order.begin() + mid, order.begin() + hi, [&](int x, int y) {
      const double cx = all[x].triangle.ball.centre[axis], cy = all[y].triangle.ball.centre[axis];
      return cx < cy || (cx == cy && x < y);
    });
    node.right = index + 1 + subtree_size(mid - lo);
  }
  nodes_[index] = node;
  node_terms_[index] = terms;
  node_extents_[index] = extent;
  return mid;
}

void FastWindingNumber::build_subtree(const std::vector<Summary>& all, std::vector<int>& order, int lo, int hi,
                                      int index) {
  const int mid = build_node(all, order, lo, hi, index);
  if (mid < 0) return;
  build_subtree(all, order, lo, mid, index + 1);
  build_subtree(all, order, mid, hi, nodes_[index].right);
}

double FastWindingNumber::numerator(const Terms& t, const Vec3& r, double inv_d2) {
  const Mat3& m = t.moment;
  const double rmr = r[0] * (m(0, 0) * r[0] + m(0, 1) * r[1] + m(0, 2) * r[2]) +
                     r[1] * (m(1, 0) * r[0] + m(1, 1) * r[1] + m(1, 2) * r[2]) +
                     r[2] * (m(2, 0) * r[0] + m(2, 1) * r[1] + m(2, 2) * r[2]);
  return t.normal.dot(r) + (t.trace - 3.0 * rmr * inv_d2);
}

// Visits the tree depth-first from the root: visit(i) handles node i and returns whether to go on
// to its children (an inner node's).
template <class Visit>
void FastWindingNumber::walk(Visit&& visit) const {
  int stack[kStackSize];
  int top = 0;
  int i = 0;
  while (!nodes_.empty()) {
    if (visit(i) && nodes_[i].right >= 0) {
      stack[top++] = nodes_[i].right;
      ++i;
      continue;
    }
    if (top == 0) break;
    i = stack[--top];
  }
}

// Triangle k seen from p: its expansion beyond beta × its radius, its solid angle within.
template <bool kBound>
void FastWindingNumber::add_triangle(Sums<kBound>& sums, int k, const Vec3& p, double beta2) const {
  const Triangle& t = triangles_[k];
  const Vec3 rt = t.ball.centre - p;
  const double dt2 = rt.squaredNorm();
  if (dt2 > beta2 * t.ball.radius2) {
    const double dt = std::sqrt(dt2);
    sums.add_expansion(t.vector_area.dot(rt), 1.0 / (dt2 * dt), dt, triangle_extents_[k], 1);
  } else {
    const Corners& c = corners_[k];
    sums.add_direct(triangle_solid_angle(c.a - p, c.b - p, c.c - p));
  }
}

template <bool kBound>
FastWindingNumber::Sums<kBound> FastWindingNumber::traverse(const Vec3& p, double beta2) const {
  Sums<kBound> sums;  // a local (the result is a copy), so that it lives in registers
  walk([&](int i) {
    const Node& node = nodes_[i];
    const Vec3 r = node.ball.centre - p;
    const double d2 = r.squaredNorm();
    if (d2 > beta2 * node.ball.radius2) {
      const double d = std::sqrt(d2), inv_d3 = 1.0 / (d2 * d), inv_d2 = inv_d3 * d;
      sums.add_expansion(numerator(node_terms_[i], r, inv_d2), inv_d3, d, node_extents_[i], node.count);
      return false;
    }
    if (node.right < 0)
      for (int k = node.first; k < node.first + node.count; ++k) add_triangle(sums, k, p, beta2);
    return true;
  });
  const Sums<kBound> result = sums;
  return result;
}

WindingEstimate FastWindingNumber::evaluate(const Vec3& p, double beta2) const {
  const Sums<true> sums = traverse<true>(p, beta2);
  const double n = static_cast<double>(triangles_.size());
  const double roundoff = kUnitRoundoff * ((2.0 * n + sums.terms + 128.0) * (sums.near_abs + 5.0 * sums.far_abs) +
                                           sums.far_triangles * far_roundoff_);
  return {sums.solid_angle / (4.0 * M_PI), (sums.truncation + roundoff) / (4.0 * M_PI)};
}

// A ball's linear part (the expansions of the nodes far from the whole ball, about its centre):
// value a0 + grad·(p − centre), its remainder bound over the ball, and what the round-off
// allowance needs.
struct FastWindingNumber::Linear {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  double a0 = 0.0, truncation = 0.0, far_abs = 0.0, terms = 0.0, far_triangles = 0.0;
  Vec3 grad = Vec3::Zero();

  // The ball about the centre of the box of points[which], holding them all.
  Linear(const std::vector<Vec3>& points, const std::vector<int>& which) {
    Vec3 lo = points[which[0]], hi = lo;
    for (int q : which) lo = lo.cwiseMin(points[q]), hi = hi.cwiseMax(points[q]);
    centre = 0.5 * (lo + hi);
    double radius2 = 0.0;
    for (int q : which) radius2 = std::max(radius2, (points[q] - centre).squaredNorm());
    radius = std::sqrt(radius2) * (1.0 + 8.0 * kUnitRoundoff);  // enlarged by a few ulps
  }
  // Whether a ball (centre m, radius R) lies beyond beta·(R + radius) from the centre.
  bool far(const Vec3& m, double ball_radius, double beta2) const {
    const double reach = ball_radius + radius;
    return (m - centre).squaredNorm() > beta2 * reach * reach;
  }
  // One node's (or triangle's) expansion, seen from the centre: r0 = its centre − this centre.
  void add(const Vec3& r0, const Vec3& normal, double numerator, const Extent& e, int count) {
    // Relative rounding of a node's centroid, against the exact area-weighted centroid (sums of
    // a few thousand terms at most, far below this).
    constexpr double kCentroid = 1e-10;
    const double d2 = r0.squaredNorm(), d = std::sqrt(d2), inv_d3 = 1.0 / (d2 * d), inv_d2 = inv_d3 * d;
    a0 += numerator * inv_d3;
    grad -= (normal - (3.0 * normal.dot(r0) * inv_d2) * r0) * inv_d3;
    const double gap = std::max(d - e.radius - radius, 0.0), inv_gap = 1.0 / gap;
    const double q = e.second + radius * radius * e.area + 2.0 * radius * e.area * kCentroid * (r0.norm() + centre.norm() + e.radius);
    truncation += q * (inv_d2 * inv_d2) * remainder_factor((e.radius + radius) / d, d * inv_gap);
    far_abs += e.area * (inv_gap * inv_gap);
    terms += 2.0;
    far_triangles += count;
  }
  double value(const Vec3& p) const { return a0 + grad.dot(p - centre); }
};

void FastWindingNumber::estimate_box(const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) const {
  out.resize(points.size());
  if (points.empty()) return;
  std::vector<int> which(points.size());
  for (std::size_t q = 0; q < points.size(); ++q) which[q] = int(q);
  Linear ball(points, which);
  const double beta2 = beta * beta;
  std::vector<int> near;  // triangles not far from the whole ball
  walk([&](int i) {
    const Node& node = nodes_[i];
    if (ball.far(node.ball.centre, std::sqrt(node.ball.radius2), beta2)) {
      const Vec3 r0 = node.ball.centre - ball.centre;
      ball.add(r0, node_terms_[i].normal, numerator(node_terms_[i], r0, 1.0 / r0.squaredNorm()), node_extents_[i], node.count);
      return false;
    }
    if (node.right < 0)
      for (int k = node.first; k < node.first + node.count; ++k) near.push_back(k);
    return true;
  });
  std::vector<const Linear*> chain;
  refine_box(points, which, near, beta, ball, chain, out);
}

void FastWindingNumber::refine_box(const std::vector<Vec3>& points, const std::vector<int>& which, const std::vector<int>& near,
                                   double beta, Linear& ball, std::vector<const Linear*>& chain,
                                   std::vector<WindingEstimate>& out) const {
  constexpr std::size_t kFewPoints = 8;  // a ball of this many points or fewer is not split
  const double beta2 = beta * beta;
  // The triangles far from this ball join its linear part; the rest stay near.
  std::vector<int> still;
  for (int k : near) {
    const Triangle& t = triangles_[k];
    if (ball.far(t.ball.centre, triangle_extents_[k].radius, beta2)) {
      const Vec3 rt = t.ball.centre - ball.centre;
      ball.add(rt, t.vector_area, t.vector_area.dot(rt), triangle_extents_[k], 1);
    } else {
      still.push_back(k);
    }
  }
  chain.push_back(&ball);
  if (which.size() > kFewPoints && !still.empty()) {
    // The ball's eighths about its centre, each with its own linear part.
    std::vector<int> part[8];
    for (int q : which) {
      const Vec3& p = points[q];
      part[(p.x() >= ball.centre.x()) + 2 * (p.y() >= ball.centre.y()) + 4 * (p.z() >= ball.centre.z())].push_back(q);
    }
    for (const std::vector<int>& eighth : part) {
      if (eighth.empty()) continue;
      Linear sub(points, eighth);
      refine_box(points, eighth, still, beta, sub, chain, out);
    }
    chain.pop_back();
    return;
  }
  // The near triangles one at a time over every point (each triangle's data read once).
  std::vector<Sums<true>> sums(which.size());
  for (int k : still)
    for (std::size_t q = 0; q < which.size(); ++q) add_triangle(sums[q], k, points[which[q]], beta2);
  double truncation = 0.0, far_abs = 0.0, terms = 0.0, far_triangles = 0.0;
  for (const Linear* l : chain)
    truncation += l->truncation, far_abs += l->far_abs, terms += l->terms, far_triangles += l->far_triangles;
  const double n = static_cast<double>(triangles_.size());
  for (std::size_t q = 0; q < which.size(); ++q) {
    const Sums<true>& sq = sums[q];
    const Vec3& p = points[which[q]];
    double value = sq.solid_angle;
    for (const Linear* l : chain) value += l->value(p);
    const double roundoff =
        kUnitRoundoff * ((2.0 * n + sq.terms + terms + 128.0) * (sq.near_abs + 5.0 * sq.far_abs + 8.0 * far_abs) +
                         (sq.far_triangles + far_triangles) * far_roundoff_);
    out[which[q]] = {value / (4.0 * M_PI), (sq.truncation + truncation + roundoff) / (4.0 * M_PI)};
  }
  chain.pop_back();
}

double FastWindingNumber::operator()(const Vec3& p) const {
  return traverse<false>(p, beta_ * beta_).solid_angle / (4.0 * M_PI);
}

double FastWindingNumber::at_beta(const Vec3& p, double beta) const {
  return traverse<false>(p, beta * beta).solid_angle / (4.0 * M_PI);
}

WindingEstimate FastWindingNumber::estimate(const Vec3& p) const { return evaluate(p, beta_ * beta_); }

double FastWindingNumber::direct(const Vec3& p) const {
  double sum = 0.0;
  for (const Corners& c : corners_) sum += triangle_solid_angle(c.a - p, c.b - p, c.c - p);
  return sum / (4.0 * M_PI);
}

bool FastWindingNumber::above(const Vec3& p, double threshold) const {
  // The rigorous bound is some ten times the actual error: at beta = 2 it reaches ½ near a closed
  // surface and decides ½ for under half of the points in its box, at 3 for nearly all of them.
  // So the estimates start at beta 3 at least and double twice before the direct sum.
  return certified_above(
      threshold, beta_, [&](double beta) { return evaluate(p, beta * beta); }, [&] { return direct(p); });
}

}  // namespace hairfit
