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

std::vector<FibreSpan> fibre_spans(const std::vector<std::vector<Vec3>>& fibres) {
  std::vector<FibreSpan> spans(fibres.size());
  for (std::size_t f = 0; f < fibres.size(); ++f) spans[f] = {fibres[f].data(), fibres[f].size()};
  return spans;
}

std::vector<FibreSpan> fibre_spans(const Curves& fibres) {
  std::vector<FibreSpan> spans(fibres.count());
  for (std::size_t f = 0; f < spans.size(); ++f) spans[f] = {fibres.points.data() + fibres.offsets[f], fibres.size(f)};
  return spans;
}

std::vector<FibreLayers> fibre_layers(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, int threads) {
  std::vector<FibreLayers> layers(fibres.size(), FibreLayers{0, -1});
  parallel_for(static_cast<int>(fibres.size()), threads, [&](int f) {
    const FibreSpan& fibre = fibres[f];
    if (fibre.size == 0) return;
    double z_lo = fibre.points[0].z(), z_hi = z_lo;
    for (std::size_t p = 1; p < fibre.size; ++p) z_lo = std::min(z_lo, fibre.points[p].z()), z_hi = std::max(z_hi, fibre.points[p].z());
    z_layers(grid, z_lo, z_hi, layers[f].first, layers[f].last);
  });
  return layers;
}

}  // namespace hairfit
