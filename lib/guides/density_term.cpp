#include "guides/density_term.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "strands/guide_track.h"

namespace hairfit {

GridGeometry make_density_geometry(const Vec3& lower, const Vec3& upper, double voxel, double margin,
                                   double max_memory_gib) {
  const Vec3 grow = Vec3::Constant(margin);
  return make_grid_geometry(lower - grow, upper + grow, voxel, max_memory_gib);
}

double surcharge_step(double occupancy, double threshold, double width) {
  const double x = std::clamp((occupancy - threshold) / width + 0.5, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double density_ceiling(const DensityGrid& grid, const DensityTermOptions& term, int threads) {
  const GridGeometry& g = grid.geometry();
  const std::vector<double>& values = grid.values();
  if (term.model == GuideDensityModel::binary) {
    double top = 0.0;
    for (double v : values) top = std::max(top, v);
    const double s = top > 0.0 ? surcharge_step(top, term.threshold, term.surcharge_width) : 0.0;
    return top * top + term.surcharge * s * s;
  }
  // Every cell centre a trilinear blend can use: the grid and the ring of zero cells around it.
  // Central differences there reach two cells beyond the grid, so they read a copy padded with
  // two rings of zeros (no bounds checks), one z layer per task: this runs once per batch over
  // the whole grid. The largest of the layers' maxima is the same for any thread count.
  const int nx = g.dims.x() + 4, ny = g.dims.y() + 4, nz = g.dims.z() + 4;
  std::vector<double> padded(static_cast<std::size_t>(nx) * ny * nz, 0.0);
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      std::copy_n(values.begin() + g.index(0, j, k), g.dims.x(),
                  padded.begin() + (2 + static_cast<std::size_t>(nx) * ((j + 2) + static_cast<std::size_t>(ny) * (k + 2))));
  const std::ptrdiff_t sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;
  const double h2 = 2.0 * g.voxel;
  std::vector<double> layer_top(nz, 0.0);
  parallel_for(nz - 2, threads, [&](int layer) {
    const int k = layer + 1;
    double top = 0.0;
    for (int j = 1; j < ny - 1; ++j) {
      const double* c = padded.data() + 1 + sy * j + sz * k;
      for (int i = 1; i < nx - 1; ++i, ++c) {
        const Vec3 d((c[1] - c[-1]) / h2, (c[sy] - c[-sy]) / h2, (c[sz] - c[-sz]) / h2);
        top = std::max(top, d.squaredNorm());
      }
    }
    layer_top[k] = top;
  });
  return term.strength * *std::max_element(layer_top.begin(), layer_top.end());
}

std::vector<std::vector<Vec3>> guide_deposit_fibres(const std::vector<Vec3>& guide, const std::vector<int>& pores_of_guide,
                                                    const GuideDensityOptions& options) {
  if (pores_of_guide.empty()) return {guide};
  // The wisp extent exactly as make_strands measures it: the largest distance of the cluster's
  // pores from the guide root in the plane of the root frame.
  const GuideTrack track(guide);
  Vec3 g0, t0, d1, d2;
  track.at(0.0, g0, t0, d1, d2);
  double extent = 0.0;
  for (int i : pores_of_guide) {
    const Vec3 delta = options.pores.positions[i] - g0;
    extent = std::max(extent, std::hypot(delta.dot(d1), delta.dot(d2)));
  }
  std::vector<std::vector<Vec3>> fibres;
  fibres.reserve(pores_of_guide.size());
  for (int i : pores_of_guide)
    fibres.push_back(make_fibre(track, options.pores.positions[i], options.pores.lengths[i], extent, options.strands));
  return fibres;
}

Tube guide_tube(const std::vector<Vec3>& guide, double root_radius, double tip_radius) {
  Tube tube;
  tube.points = guide;
  std::vector<double> s(guide.size(), 0.0);
  for (std::size_t i = 1; i < guide.size(); ++i) s[i] = s[i - 1] + (guide[i] - guide[i - 1]).norm();
  const double total = s.empty() || s.back() <= 0.0 ? 1.0 : s.back();
  for (double si : s) tube.radii.push_back(root_radius + (tip_radius - root_radius) * si / total);
  return tube;
}

}  // namespace hairfit
