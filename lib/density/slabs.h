// Deterministic parallel deposits: the grid is cut into z-slabs of whole cell layers; one thread
// owns a slab and writes only its cells, visiting the items in their given order, so every cell
// receives its contributions in the same order whatever the number of threads.
#pragma once
#include <functional>

#include "density/grid.h"

namespace hairfit {

// Calls body(k_begin, k_end) for consecutive slabs covering [0, dims.z) on up to `threads`
// threads. The slab layout may depend on `threads`; results must not (see above).
void for_each_z_slab(const GridGeometry& grid, int threads, const std::function<void(int, int)>& body);

// The range [k_first, k_last] of cell layers the z-interval [z_lo, z_hi] (cm) touches, unclamped.
void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last);

}  // namespace hairfit
