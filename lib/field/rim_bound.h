// A bound on how fast a soup's winding number changes away from its triangles, from its rims.
// Internal to lib/field.
//
// Off the triangles, the gradient of a surface's solid angle is the Biot–Savart field of its
// boundary: ∇Ω(p) = ∮ (x − p) × dx / |x − p|³. Summed over a soup's triangles, every edge counts
// with its net multiplicity m_e (weighted faces running a→b minus those running b→a): the edges two
// faces share turning opposite ways cancel, and a closed, consistently oriented surface has none
// left. The rest are the soup's rims: open borders, non-manifold edges, the borders of flipped
// patches. So with d the distance from p to edge e,
//   |∇w(p)| ≤ (1/4π) Σ_e |m_e| · min(|e| / d², π / d),
// the first from |x − p| ≥ d along the edge, the second from the whole line through it. Rims in a
// ball (centre x₀, radius r) at least ρ from p, with net current C = Σ m_e (b − a) and weighted
// length L = Σ |m_e| |e|, add at most |C| / |x₀ − p|² + 2 r L / ρ³ (a first-order Taylor bound of
// (x − p)/|x − p|³ about x₀): a card's closed border, whose current sums to zero, counts as a
// dipole, falling off as 1/ρ³.
#pragma once
#include <limits>
#include <vector>

#include "core/types.h"
#include "field/grid_crossings.h"

namespace hairfit::field {

class RimBound {
 public:
  // Vertices at identical positions are one vertex, whichever part or index they come from (so a
  // hull's and a reversed scalp's common hairline cancels); zero-area triangles are left out, as
  // their solid angle is zero everywhere.
  explicit RimBound(const std::vector<SoupPart>& soup);

  // An upper bound on |∇w| (per cm) over the box [lo, hi]: infinite where a rim meets the box, 0
  // for a soup without rims. Where the bound would exceed `limit` it may return infinity instead
  // (what a caller that only needs to know it is below `limit` saves).
  double gradient(const Vec3& lo, const Vec3& hi,
                  double limit = std::numeric_limits<double>::infinity()) const;
  std::size_t rims() const { return rims_.size(); }

 private:
  struct Rim {
    Vec3 a, b;                // oriented so that m_e > 0
    double multiplicity = 0;  // m_e
  };
  struct Node {
    Vec3 centre;
    double radius = 0;
    Vec3 current = Vec3::Zero();  // Σ m_e (b − a) below
    double weighted_length = 0;   // Σ m_e |e| below
    int first = 0, count = 0;    // rims [first, first + count)
    int left = -1, right = -1;   // children; −1 for a leaf
  };
  int build(int first, int count);
  double bound(int node, const Vec3& lo, const Vec3& hi, double limit) const;  // limit in units of 4π·gradient

  std::vector<Rim> rims_;
  std::vector<Node> nodes_;
};

}  // namespace hairfit::field
