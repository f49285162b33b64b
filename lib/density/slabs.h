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

// The range [k_first, k_last] of cell layers the z-interval [z_lo, z_hi] (cm) touches, unclamped
// (but kept within [−1, dims.z + 1]); z_layer(z) is one end.
void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last);
int z_layer(const GridGeometry& grid, double z);

// A fibre as the deposits read it: its points in place, wherever they are stored (a Curves, or
// the guides' shapes beside fibres grown into one buffer, as the density batches deposit them).
struct FibreSpan {
  const Vec3* points;
  std::size_t size;
  double weight = 1.0;  // how many fibres it stands for: each crossing deposits weight × its length
};
std::vector<FibreSpan> fibre_spans(const Curves& fibres);

// The layers the fibres touch (z_layers), found once on `threads` threads: each point's, and each
// fibre's range of them, so that a slab skips a fibre that misses it with one test and a segment
// with two (a segment's range is its end points', z_layers being monotone).
struct FibreLayers {
  std::vector<int> first, last;    // per fibre (first > last for an empty fibre)
  std::vector<std::size_t> begin;  // per fibre: where its points' layers start in `point`
  std::vector<int> point;          // per point, fibre after fibre
};
FibreLayers fibre_layers(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, int threads);

// for_each_z_slab for fibres: two slabs per thread, cut where each holds about the same number of
// fibre segments (spread over each fibre's layers). A segment that crosses a cut is walked by
// both slabs, so few cuts where the fibres are, and no more than the threads need, save work;
// the layout never changes results.
void for_each_fibre_slab(const GridGeometry& grid, const std::vector<FibreSpan>& fibres,
                         const FibreLayers& layers, int threads, const std::function<void(int, int)>& body);

// Calls visit(cell index, length) for every crossing (traverse_segment) of a fibre segment with a
// cell of layers [k_begin, k_end), fibre after fibre, segment after segment, from a to b: the
// fixed order in which a slab's owner adds to its cells.
template <class Visit>
void for_each_crossing_in_slab(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, const FibreLayers& layers,
                               int k_begin, int k_end, Visit&& visit) {
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    const FibreSpan& fibre = fibres[f];
    // A fibre whose whole z-range misses the slab has no segment in it; one that lies well inside
    // it needs no test per segment.
    if (fibre.size < 2 || layers.last[f] + 1 < k_begin || layers.first[f] - 1 >= k_end) continue;
    const bool inside = layers.first[f] - 1 >= k_begin && layers.last[f] + 1 < k_end;
    const int* point_layer = layers.point.data() + layers.begin[f];
    for (std::size_t s = 0; s + 1 < fibre.size; ++s) {
      if (!inside) {
        const int k_first = std::min(point_layer[s], point_layer[s + 1]), k_last = std::max(point_layer[s], point_layer[s + 1]);
        if (k_last + 1 < k_begin || k_first - 1 >= k_end) continue;  // one layer of slack: faces
      }
      for_each_cell_crossing(
          grid, fibre.points[s], fibre.points[s + 1],
          [&](const Vec3i& c, double length) { visit(grid.index(c.x(), c.y(), c.z()), fibre.weight * length); }, k_begin, k_end);
    }
  }
}

}  // namespace hairfit
