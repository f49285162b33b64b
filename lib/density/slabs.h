// Deterministic parallel deposits: the grid is cut into z-slabs of whole cell layers; one thread
// owns a slab and writes only its cells, visiting the items in their given order, so every cell
// receives its contributions in the same order whatever the number of threads.
#pragma once
#include <algorithm>
#include <functional>
#include <vector>

#include "density/grid.h"
#include "density/traversal.h"

namespace hairfit {

// Calls body(k_begin, k_end) for consecutive slabs covering [0, dims.z) on up to `threads`
// threads. The slab layout may depend on `threads`; results must not (see above).
void for_each_z_slab(const GridGeometry& grid, int threads, const std::function<void(int, int)>& body);

// The range [k_first, k_last] of cell layers the z-interval [z_lo, z_hi] (cm) touches, unclamped.
void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last);

// Calls visit(cell index, length) for every crossing (traverse_segment) of a fibre segment with a
// cell of layers [k_begin, k_end), fibre after fibre, segment after segment, from a to b: the
// fixed order in which a slab's owner adds to its cells.
template <class Visit>
void for_each_crossing_in_slab(const GridGeometry& grid, const std::vector<std::vector<Vec3>>& fibres, int k_begin,
                               int k_end, Visit&& visit) {
  std::vector<CellCrossing> crossings;
  for (const std::vector<Vec3>& fibre : fibres) {
    if (fibre.size() < 2) continue;
    // A fibre whose whole z-range misses the slab has no segment in it (z_layers is monotone):
    // one test instead of one per segment.
    double z_lo = fibre[0].z(), z_hi = z_lo;
    for (const Vec3& p : fibre) z_lo = std::min(z_lo, p.z()), z_hi = std::max(z_hi, p.z());
    int fibre_first, fibre_last;
    z_layers(grid, z_lo, z_hi, fibre_first, fibre_last);
    if (fibre_last + 1 < k_begin || fibre_first - 1 >= k_end) continue;
    for (size_t s = 0; s + 1 < fibre.size(); ++s) {
      const Vec3& a = fibre[s];
      const Vec3& b = fibre[s + 1];
      int k_first, k_last;
      z_layers(grid, std::min(a.z(), b.z()), std::max(a.z(), b.z()), k_first, k_last);
      if (k_last + 1 < k_begin || k_first - 1 >= k_end) continue;  // one layer of slack: faces
      traverse_segment(grid, a, b, crossings);
      for (const CellCrossing& c : crossings)
        if (c.cell.z() >= k_begin && c.cell.z() < k_end) visit(grid.index(c.cell.x(), c.cell.y(), c.cell.z()), c.length);
    }
  }
}

}  // namespace hairfit
