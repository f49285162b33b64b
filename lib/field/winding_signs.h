// Whether a soup's winding number exceeds ½ at grid nodes, asking the winding number itself as
// rarely as its geometry allows. Internal to lib/field.
//
// Between two nodes a and b of a box, along a path of grid edges inside it,
//   w(b) = w(a) + J(a → b) + ∫ ∇w · dx,   |∫ ∇w · dx| ≤ G · |b − a|₁,
// where J is the exact sum of the jumps on the path's edges (grid_crossings.h) and G bounds |∇w|
// over the box (rim_bound.h). So one estimate of w at a reference node, with its rigorous error
// bound, decides every node of the box whose w(a) + J lies farther from ½ than that bound plus
// G·|b − a|₁. Boxes are split in eight where nodes stay undecided. A box of at most kEstimatedBox
// nodes a side, or of a few nodes, takes one estimate of all its nodes at once where the soup
// offers it (FastWindingNumber::estimate_box), and the certified test at each node that this does
// not decide. Away from rims G is small and one estimate settles thousands of nodes; on a closed,
// consistently oriented surface G is 0 and w is an integer off the surface.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/fast_winding.h"
#include "core/grid_geometry.h"
#include "field/grid_crossings.h"
#include "field/rim_bound.h"
#include "field/winding_soup.h"

namespace hairfit::field {

class GridWindingSigns {
 public:
  GridWindingSigns(const WindingSoup& soup, const GridGeometry& grid, int threads);

  // What a decision needed: estimates at references, estimates of boxes of nodes at once, and
  // nodes asked themselves.
  struct Counts {
    int64_t nodes = 0, references = 0, boxes = 0, asked = 0;
    Counts& operator+=(const Counts& o) {
      nodes += o.nodes, references += o.references, boxes += o.boxes, asked += o.asked;
      return *this;
    }
  };
  // inside[q] = (w > ½ at node nodes[q]), for nodes given by their grid index, ascending, each
  // with its distance to the surface (a lower bound will do: references are the nodes farthest
  // from the surface, never nearer than kClearance voxel, and nodes nearer than kSnapped voxel are
  // asked themselves, since there the snapped soup's jumps need not be the soup's).
  // Deterministic for any thread count.
  std::vector<std::uint8_t> decide(const std::vector<int64_t>& nodes, const std::vector<double>& distance, int threads,
                                   Counts* counts = nullptr) const;
  static constexpr double kClearance = 1e-3;  // voxels; the lattice's snapping is 2⁻¹⁷ voxel
  static constexpr double kSnapped = 1e-4;    // voxels, some ten times the snapping
  static constexpr int kTopBox = 32;          // nodes per side of the boxes decided side by side
  static constexpr int kAsk = 4;              // a box with this many undecided nodes or fewer asks them
  // Nodes per side of a box that takes one estimate of the box (soups with estimate_box) rather
  // than a reference and further splits.
  static constexpr int kEstimatedBox = 4;
  // A box's estimates take β = kBoxBeta, then twice that for the nodes they leave undecided, and
  // so on for kBoxPasses in all.
  static constexpr double kBoxBeta = 2.0;
  static constexpr int kBoxPasses = 4;

  const GridCrossings& crossings() const { return crossings_; }
  const RimBound& rims() const { return rims_; }
  const WindingSoup& soup() const { return soup_; }

 private:
  struct Box {
    Vec3i lo, hi;  // nodes lo … hi − 1
  };
  // Decides the requests `which` (indices into nodes) inside `box`.
  void decide_box(const Box& box, std::vector<int>& which, const std::vector<int64_t>& nodes,
                  const std::vector<double>& distance, std::vector<std::uint8_t>& inside, Counts& counts) const;

  const WindingSoup& soup_;
  GridGeometry grid_;
  GridCrossings crossings_;
  RimBound rims_;
};

// The robust inside of several soups: inside where any soup's winding number exceeds ½.
class RobustSigns {
 public:
  // `inside` must outlive this.
  RobustSigns(const RobustInside& inside, const GridGeometry& grid, int threads);
  // As GridWindingSigns::decide, for the union; each soup is asked only at the nodes that the
  // field and the soups before it leave outside. `counts` sums over the soups.
  std::vector<std::uint8_t> decide(const std::vector<int64_t>& nodes, const std::vector<double>& distance, int threads,
                                   GridWindingSigns::Counts* counts = nullptr) const;

  const DistanceField* negative_in() const { return negative_in_; }
  const std::vector<std::unique_ptr<GridWindingSigns>>& soups() const { return soups_; }

 private:
  const DistanceField* negative_in_;
  GridGeometry grid_;
  std::vector<std::unique_ptr<GridWindingSigns>> soups_;
};

}  // namespace hairfit::field
