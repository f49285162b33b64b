#include "density/slabs.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace hairfit {

void for_each_z_slab(const GridGeometry& grid, int threads, const std::function<void(int, int)>& body) {
  const int layers = grid.dims.z();
  if (layers <= 0) return;
  threads = std::max(1, threads);
  // A few slabs per thread balance hair that is denser in some layers than others.
  const int slabs = std::min(layers, threads == 1 ? 1 : 4 * threads);
  parallel_for(slabs, threads, [&](int s) {
    const int k_begin = int(int64_t(layers) * s / slabs), k_end = int(int64_t(layers) * (s + 1) / slabs);
    if (k_end > k_begin) body(k_begin, k_end);
  });
}

void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last) {
  const double a = std::floor((z_lo - grid.origin.z()) / grid.voxel);
  const double b = std::floor((z_hi - grid.origin.z()) / grid.voxel);
  // Clamp in double before the cast so far-away coordinates cannot overflow an int.
  const double lim = double(grid.dims.z()) + 1.0;
  k_first = int(std::min(std::max(a, -1.0), lim));
  k_last = int(std::min(std::max(b, -1.0), lim));
}

}  // namespace hairfit
