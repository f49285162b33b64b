// The acceptable region's robust inside (docs/design.md §2): the shell that the hull encloses together with
// the scalp, the scalp's orientation reversed, decided by generalized winding numbers (Jacobson,
// Kavan and Sorkine-Hornung 2013) evaluated hierarchically (Barill et al. 2018), so that open hulls
// in several parts, with holes, overlaps and sheets that dip under the skin still have an inside.
#pragma once
#include "core/fast_winding.h"
#include "core/mesh.h"
#include "field/winding_soup.h"

namespace hairfit {

class HairRegion {
 public:
  // `hull` and `scalp` in cm, cleaned (core/mesh_repair.h), the scalp facing out of the head.
  // A closed hull (no boundary loop, no non-manifold edge) encloses its inside by itself: the
  // scalp lies within it (a volume from `hairfit prepare` closes under the scalp with a floor).
  // `threads` (0 = all) builds the trees side by side; the region is the same for any count.
  HairRegion(const Mesh& hull, const Mesh& scalp, bool hull_closed, int threads = 1);

  // H(p): w_hull(p) for a closed hull; w_hull(p) − w_scalp(p) for an open one, which is 1 in the
  // shell an open hull and the scalp close between them where they share a hairline, 0 outside,
  // and in between where they do not meet (a hull hovering above the scalp, a gap, a hole).
  double winding(const Vec3& p) const;
  // H's hierarchical estimate at accuracy parameter `beta`, with a rigorous bound on its error
  // (the hull's and the scalp's bounds added).
  WindingEstimate estimate(const Vec3& p, double beta) const;
  // H's estimates at many nearby points at once (FastWindingNumber::estimate_box, the hull's and
  // the scalp's bounds added).
  void estimate_box(const std::vector<Vec3>& points, double beta, std::vector<WindingEstimate>& out) const;
  // Whether H(p) > ½, exactly as the direct sums decide it: the estimates with their error bounds
  // decide where H lies farther from ½ than the bound (certified_above, core/fast_winding.h), the
  // direct sums over every triangle elsewhere, i.e. on or right next to the hull and where H
  // itself is within about the bound of ½ (a card's own front). The trees are built with
  // β = kFirstBeta; the soup's references are estimated at β = kCloseBeta.
  bool inside_hull(const Vec3& p) const;
  static constexpr double kCloseBeta = 4.0;
  static constexpr double kFirstBeta = 1.5;
  bool hull_closed() const { return closed_; }

  // The region as the fields' robust sign takes it: the hull (the meshes this region was built
  // from, which must outlive the soup), with the scalp reversed for an open hull; estimated at
  // β = kCloseBeta (many points at once at the β asked), decided by inside_hull.
  WindingSoup soup(const Mesh& hull, const Mesh& scalp) const;

  const FastWindingNumber& hull_winding() const { return hull_; }
  const FastWindingNumber& scalp_winding() const { return scalp_; }

 private:
  FastWindingNumber hull_, scalp_;
  bool closed_;
};

// The head as a closed surface: the scalp (a disk facing out of the head) and a floor across its
// hairline, a fan from the hairline's centroid wound so that the two face outward together. Its
// inside is what the scalp's field counts as the head: bounded, so hair that hangs below the
// hairline past the ears and the neck is outside it, as it would be on the real head.
Mesh closed_head(const Mesh& scalp);

// Whether the winding number of `winding`'s mesh at p exceeds ½, exactly as the direct sum decides
// it (FastWindingNumber::above).
bool winding_above_half(const FastWindingNumber& winding, const Vec3& p);

// `mesh`'s own winding number as a soup: estimated by `winding` (built over `mesh`; both must
// outlive the soup) at β = HairRegion::kCloseBeta (many points at once at the β asked), decided
// by winding_above_half.
WindingSoup winding_soup(const Mesh& mesh, const FastWindingNumber& winding);

}  // namespace hairfit
