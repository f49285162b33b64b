// Deterministic parallel deposits: the grid is cut into z-slabs of whole cell layers; one thread
// owns a slab and writes only its cells, visiting the items in their given order, so every cell
// receives its contributions in the same order whatever the number of threads.
#pragma once
#include <algorithm>
#include <functional>
#include <vector>

#include "core/curves.h"
#include "density/grid.h"
#include "density/traversal.h"

namespace hairfit {

// Calls body(k_begin, k_end) for consecutive slabs covering [0, dims.z) on up to `threads`
// threads. The slab layout may depend on `threads`; results must not (see above).
void for_each_z_slab(const GridGeometry& grid, int threads, const std::function<void(int, int)>& body);

// The range [k_first, k_last] of cell layers the z-interval [z_lo, z_hi] (cm) touches, unclamped.
void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last);

// A fibre as the deposits read it: its points in place, wherever they are stored.
struct FibreSpan {
  const Vec3* points;
  std::size_t size;
};
std::vector<FibreSpan> fibre_spans(const std::vector<std::vector<Vec3>>& fibres);
std::vector<FibreSpan> fibre_spans(const Curves& fibres);

// The layers each fibre touches (z_layers of its z-range), found once on `threads` threads so that
// every slab skips the fibres that miss it with one test.
struct FibreLayers {
  int first, last;
};
std::vector<FibreLayers> fibre_layers(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, int threads);

// Calls visit(cell index, length) for every crossing (traverse_segment) of a fibre segment with a
// cell of layers [k_begin, k_end), fibre after fibre, segment after segment, from a to b: the
// fixed order in which a slab's owner adds to its cells.
template <class Visit>
void for_each_crossing_in_slab(const GridGeometry& grid, const std::vector<FibreSpan>& fibres,
                               const std::vector<FibreLayers>& layers, int k_begin, int k_end, Visit&& visit) {
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    const FibreSpan& fibre = fibres[f];
    // A fibre whose whole z-range misses the slab has no segment in it (z_layers is monotone);
    // one that lies well inside it needs no test per segment.
    if (fibre.size < 2 || layers[f].last + 1 < k_begin || layers[f].first - 1 >= k_end) continue;
    const bool inside = layers[f].first - 1 >= k_begin && layers[f].last + 1 < k_end;
    for (std::size_t s = 0; s + 1 < fibre.size; ++s) {
      const Vec3& a = fibre.points[s];
      const Vec3& b = fibre.points[s + 1];
      if (!inside) {
        int k_first, k_last;
        z_layers(grid, std::min(a.z(), b.z()), std::max(a.z(), b.z()), k_first, k_last);
        if (k_last + 1 < k_begin || k_first - 1 >= k_end) continue;  // one layer of slack: faces
      }
      // The walk's layer only moves one way (with b − a): once past the slab, it is done here.
      const bool up = b.z() > a.z();
      for_each_cell_crossing(grid, a, b, [&](const Vec3i& c, double length) {
        if (c.z() >= k_begin && c.z() < k_end) visit(grid.index(c.x(), c.y(), c.z()), length);
        else if (up ? c.z() >= k_end : c.z() < k_begin) return false;
        return true;
      });
    }
  }
}

}  // namespace hairfit
