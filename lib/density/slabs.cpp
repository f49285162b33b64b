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

int z_layer(const GridGeometry& grid, double z) {
  const double k = std::floor((z - grid.origin.z()) / grid.voxel);
  // Clamp in double before the cast so far-away coordinates cannot overflow an int.
  return int(std::min(std::max(k, -1.0), double(grid.dims.z()) + 1.0));
}

void z_layers(const GridGeometry& grid, double z_lo, double z_hi, int& k_first, int& k_last) {
  k_first = z_layer(grid, z_lo);
  k_last = z_layer(grid, z_hi);
}

std::vector<FibreSpan> fibre_spans(const Curves& fibres) {
  std::vector<FibreSpan> spans(fibres.count());
  for (std::size_t f = 0; f < spans.size(); ++f) spans[f] = {fibres.points.data() + fibres.offsets[f], fibres.size(f)};
  return spans;
}

void for_each_fibre_slab(const GridGeometry& grid, const std::vector<FibreSpan>& fibres,
                         const FibreLayers& layers, int threads, const std::function<void(int, int)>& body) {
  const int count = grid.dims.z();
  if (count <= 0) return;
  threads = std::max(1, threads);
  const int slabs = std::min(count, threads == 1 ? 1 : 2 * threads);
  if (slabs == 1) {
    body(0, count);
    return;
  }
  // Work per layer: each fibre's segments spread evenly over the layers it touches.
  std::vector<double> change(count + 1, 0.0);
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    if (fibres[f].size < 2) continue;
    const int first = std::clamp(layers.first[f], 0, count - 1), last = std::clamp(layers.last[f], 0, count - 1);
    const double per_layer = double(fibres[f].size - 1) / (last - first + 1);
    change[first] += per_layer;
    change[last + 1] -= per_layer;
  }
  std::vector<double> cumulative(count + 1, 0.0);  // work below layer k
  double level = 0.0;
  for (int k = 0; k < count; ++k) {
    level += change[k];
    cumulative[k + 1] = cumulative[k] + level;
  }
  // Cuts at the layers where the cumulative work reaches s/slabs of the total (each slab at least
  // one layer).
  std::vector<int> cuts{0};
  for (int s = 1; s < slabs; ++s) {
    const double target = cumulative[count] * s / slabs;
    int k = static_cast<int>(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
    k = std::clamp(k, cuts.back() + 1, count - (slabs - s));
    cuts.push_back(k);
  }
  cuts.push_back(count);
  parallel_for(slabs, threads, [&](int s) { body(cuts[s], cuts[s + 1]); });
}

FibreLayers fibre_layers(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, int threads) {
  FibreLayers layers;
  layers.first.assign(fibres.size(), 0);
  layers.last.assign(fibres.size(), -1);
  layers.begin.resize(fibres.size() + 1, 0);
  for (std::size_t f = 0; f < fibres.size(); ++f) layers.begin[f + 1] = layers.begin[f] + fibres[f].size;
  layers.point.resize(layers.begin.back());
  parallel_for(static_cast<int>(fibres.size()), threads, [&](int f) {
    const FibreSpan& fibre = fibres[f];
    int* point = layers.point.data() + layers.begin[f];
    for (std::size_t p = 0; p < fibre.size; ++p) {
      const int k = z_layer(grid, fibre.points[p].z());
      point[p] = k;
      layers.first[f] = p == 0 ? k : std::min(layers.first[f], k);
      layers.last[f] = p == 0 ? k : std::max(layers.last[f], k);
    }
  });
  return layers;
}

}  // namespace hairfit
