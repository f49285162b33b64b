// The generalised winding number of a triangle soup (Jacobson, Kavan and Sorkine-Hornung 2013),
// evaluated hierarchically as in Barill, Dickson, Schmidt, Levin and Jacobson 2018 ("Fast
// winding numbers for soups and clouds"): a bounding-sphere tree over the triangles, whose nodes
// far from the query point are replaced by a second-order expansion of their solid angle, with a
// rigorous bound on what that replacement costs. Exact near the point (each triangle's solid
// angle), so the value differs from the direct sum only by the far field's truncation.
#pragma once
#include <cstddef>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

// What one evaluation returns: the value and a bound on |value − direct sum|: the expansions'
// Taylor remainders (rigorous) plus an allowance for round-off (first-order error analysis).
struct WindingEstimate {
  double value = 0.0;
  double error_bound = 0.0;
};

class FastWindingNumber {
 public:
  // beta (> 1; throws std::invalid_argument otherwise): a node is replaced by its expansion when
  // the query is farther than beta × the node's radius from the node's centre; larger is more
  // accurate and slower. Any soup is accepted (open, non-manifold, duplicated, flipped); an empty
  // mesh has winding number 0 everywhere. Positions must be finite and indices in range.
  // `threads` (0 = all) builds the tree's subtrees side by side; the tree is the same for any count.
  explicit FastWindingNumber(const Mesh& mesh, double beta = 2.0, int threads = 1);

  double operator()(const Vec3& p) const;  // estimate(p).value, bit for bit, without the bound
  // The hierarchical value with another accuracy parameter (> 1) than the constructor's.
  double at_beta(const Vec3& p, double beta) const;
  WindingEstimate estimate(const Vec3& p) const;
  // The estimate with another accuracy parameter (> 1) than the constructor's.
  WindingEstimate estimate(const Vec3& p, double beta) const { return evaluate(p, beta * beta); }
  // The sum of every triangle's solid angle (triangle_solid_angle) over 4π, in tree order (so
  // within round-off of winding_number(mesh, p)). On the surface it is what that formula gives:
  // a triangle containing p adds 0 or ±2π as rounding falls (a closed mesh's w is 0 or 1 at a
  // face's centroid, ½ at a vertex); never NaN.
  double direct(const Vec3& p) const;
  // Whether direct(p) > threshold, exactly: an estimate decides where it lies farther from the
  // threshold than its error bound, tried at b = max(beta, 3), 2b and 4b (the rigorous bound is
  // some ten times the actual error); the direct sum decides elsewhere, i.e. within about the
  // bound of the threshold (on or right next to the surface, for a closed mesh and threshold ½).
  bool above(const Vec3& p, double threshold) const;
  // The betas above() tries before the direct sum, the first at least `beta`.
  static constexpr double kFirstCertifiedBeta = 3.0;
  static constexpr int kCertifiedPasses = 3;

  // Estimates at many points with one traversal: `out[q]` estimates the direct sum at points[q],
  // with a rigorous bound on its error. The points span a ball (the centre of their bounding box,
  // the farthest one's distance); a node farther than beta·(its radius + the ball's) from the
  // centre counts through its expansion about the centre taken to first order in the point's
  // offset (one linear function for all points, its Taylor remainder bounded over the ball); the
  // other triangles are visited at each point as estimate() visits them (their expansion beyond
  // beta × their radius, their solid angle within). Values differ from estimate(p, beta)'s in the
  // last bits; the bound is looser the larger the ball.
  void estimate_box(const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) const;

  std::size_t size() const { return size_; }  // triangles of the mesh, zero-area ones included
  double beta() const { return beta_; }

 private:
  // The data are split by use, so that a query touches few cache lines: every visit reads a
  // node's Ball, an expansion its Terms, a bound its Extent, a direct sum the Corners.
  struct Ball {
    Vec3 centre;         // a node's area-weighted centroid, a triangle's centroid
    double radius2 = 0;  // squared distance from the centre to the farthest vertex
  };
  struct Node {
    Ball ball;
    int first = 0, count = 0;  // the node covers triangles [first, first + count)
    int right = -1;            // an inner node's children: the next node and this; -1 for a leaf
  };
  // Second-order coefficients about the node's centre (a_t n_t is a triangle's vector area,
  // g_t its centroid).
  struct Terms {
    Vec3 normal;       // Σ a_t n_t
    Mat3 moment;       // Σ a_t n_t (g_t − centre)ᵀ
    double trace = 0;  // of `moment`
  };
  // What the remainder bound needs.
  struct Extent {
    double radius = 0;
    double area = 0;    // Σ a_t
    double second = 0;  // ∫ |x − centre|² dA
  };
  // A triangle's own expansion, about its centroid, where the second-order term vanishes.
  struct Triangle {
    Ball ball;
    Vec3 vector_area;
  };
  struct Corners {
    Vec3 a, b, c;
  };
  // A node's expansion times |r|³, seen from r = centre − p (inv_d2 = 1/|r|²).
  static double numerator(const Terms& t, const Vec3& r, double inv_d2);
  template <bool kBound>
  struct Sums;
  template <class Visit>
  void walk(Visit&& visit) const;
  template <bool kBound>
  void add_triangle(Sums<kBound>& sums, int k, const Vec3& p, double beta2) const;
  template <bool kBound>
  Sums<kBound> traverse(const Vec3& p, double beta2) const;

  struct Summary;  // a triangle while building
  // Node `index` over order[lo, hi) (indices into `all`, in mesh order), permuting that range:
  // its terms, and for an inner node the split, returned (−1 for a leaf). Its children are nodes
  // index + 1 (over [lo, mid)) and index + 1 + subtree_size(mid − lo) (over [mid, hi)).
  int build_node(const std::vector<Summary>& all, std::vector<int>& order, int lo, int hi, int index);
  // The node over [lo, hi) and its whole subtree, depth-first from `index`.
  void build_subtree(const std::vector<Summary>& all, std::vector<int>& order, int lo, int hi, int index);
  // Nodes in the subtree over n triangles (median splits to kLeafSize).
  static int subtree_size(int n);
  struct Linear;  // a ball of points' linear part (estimate_box)
  // estimate_box below its traversal: the ball's triangles `near` that are far from the ball join
  // its linear part; the ball is split in eighths while it holds many points and near triangles
  // remain; otherwise every point sums the near ones and the linear parts of `chain` and `ball`.
  void refine_box(const std::vector<Vec3>& points, const std::vector<int>& which, const std::vector<int>& near,
                  double beta, Linear& ball, std::vector<const Linear*>& chain, std::vector<WindingEstimate>& out) const;
  // The estimate with beta² = beta2 (above() tightens it when undecided).
  WindingEstimate evaluate(const Vec3& p, double beta2) const;

  double beta_;
  std::size_t size_;
  double far_roundoff_;  // round-off allowance of a far triangle's computed solid angle, in units of u
  // The tree, depth-first from the root, and per node its terms and extent.
  std::vector<Node> nodes_;
  std::vector<Terms> node_terms_;
  std::vector<Extent> node_extents_;
  // The triangles of positive area, in tree order.
  std::vector<Triangle> triangles_;
  std::vector<Extent> triangle_extents_;
  std::vector<Corners> corners_;
};

// Whether a winding number exceeds `threshold`, decided as FastWindingNumber::above decides it:
// `estimate(β)` is its hierarchical estimate with accuracy parameter β and the error bound, which
// decides where the value lies farther from the threshold than the bound, tried at
// b = max(first_beta, 3), 2b and 4b; `direct()` is the direct sum, which decides elsewhere. For a
// weighted sum of several soups' winding numbers, the estimates' values and bounds add.
template <class Estimate, class Direct>
bool certified_above(double threshold, double first_beta, Estimate&& estimate, Direct&& direct) {
  double beta = first_beta > FastWindingNumber::kFirstCertifiedBeta ? first_beta : FastWindingNumber::kFirstCertifiedBeta;
  for (int pass = 0; pass < FastWindingNumber::kCertifiedPasses; ++pass, beta *= 2.0) {
    const WindingEstimate e = estimate(beta);
    if (e.value - threshold > e.error_bound) return true;
    if (threshold - e.value > e.error_bound) return false;
  }
  return direct() > threshold;
}

}  // namespace hairfit
