#include "guides/density_term.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "hair/guide_track.h"

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
  return DensityCeiling(term)(grid, threads);
}

double DensityCeiling::operator()(const DensityGrid& grid, int threads) {
  const GridGeometry& g = grid.geometry();
  const std::vector<double>& values = grid.values();
  if (term_.model == GuideDensityModel::binary) {
    double top = 0.0;
    for (double v : values) top = std::max(top, v);
    const double s = top > 0.0 ? surcharge_step(top, term_.threshold, term_.surcharge_width) : 0.0;
    return top * top + term_.surcharge * s * s;
  }
  // Every cell centre a trilinear blend can use: the grid and the ring of zero cells around it.
  // Central differences there reach two cells beyond the grid, so they read a copy padded with
  // two rings of zeros (no bounds checks). A row's maximum depends on its own cells and those of
  // its four neighbour rows; a row is rescanned when one of them changed since the last call.
  const int nx = g.dims.x() + 4, ny = g.dims.y() + 4, nz = g.dims.z() + 4;
  const bool fresh = nx != nx_ || ny != ny_ || nz != nz_ || g.voxel != voxel_;
  if (fresh) {
    nx_ = nx, ny_ = ny, nz_ = nz, voxel_ = g.voxel;
    padded_.assign(static_cast<std::size_t>(nx) * ny * nz, 0.0);
    row_top_.assign(static_cast<std::size_t>(ny) * nz, 0.0);
  }
  auto row = [&](int j, int k) { return static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k; };
  // Copy the changed rows in (bit for bit), one z layer per task; changed[k][j]: padded row (j, k)
  // differs from the last call (empty for the padding layers, which never change).
  std::vector<std::vector<char>> changed(nz);
  parallel_for(g.dims.z(), threads, [&](int k) {
    std::vector<char>& mark = changed[k + 2];
    mark.assign(ny, 0);
    for (int j = 0; j < g.dims.y(); ++j) {
      const double* from = values.data() + g.index(0, j, k);
      double* to = padded_.data() + 2 + static_cast<std::size_t>(nx) * row(j + 2, k + 2);
      if (!fresh && std::memcmp(from, to, sizeof(double) * g.dims.x()) == 0) continue;
      std::copy_n(from, g.dims.x(), to);
      mark[j + 2] = 1;
    }
  });
  const std::ptrdiff_t sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;
  const double h2 = 2.0 * g.voxel;
  parallel_for(nz - 2, threads, [&](int layer) {
    const int k = layer + 1;
    auto marked = [&](int kk, int j) { return !changed[kk].empty() && changed[kk][j]; };
    for (int j = 1; j < ny - 1; ++j) {
      if (!fresh && !marked(k, j) && !marked(k, j - 1) && !marked(k, j + 1) && !marked(k - 1, j) && !marked(k + 1, j))
        continue;
      double top = 0.0;
      const double* c = padded_.data() + 1 + sy * j + sz * k;
      for (int i = 1; i < nx - 1; ++i, ++c) {
        const Vec3 d((c[1] - c[-1]) / h2, (c[sy] - c[-sy]) / h2, (c[sz] - c[-sz]) / h2);
        top = std::max(top, d.squaredNorm());
      }
      row_top_[row(j, k)] = top;
    }
  });
  return term_.strength * *std::max_element(row_top_.begin(), row_top_.end());
}

void grow_guide_fibres(const std::vector<Vec3>& guide, const std::vector<int>& pores_of_guide,
                       const GuideDensityOptions& options, Vec3* fibres) {
  if (pores_of_guide.empty()) return;
  const GuideTrack track(guide);
  const double extent = wisp_extent(track, options.pores.positions, pores_of_guide);
  const std::size_t n = fibre_point_count(options.wisp);
  for (int i : pores_of_guide)
    grow_fibre(track, options.pores.positions[i], options.pores.lengths[i], extent, options.wisp, fibres + n * i);
}

void wisp_tube_lines(const std::vector<Vec3>& guide, const WispShape& wisp, Vec3* lines) {
  const GuideTrack track(guide);
  const int n = fibre_point_count(wisp);
  constexpr double kGoldenAngle = 2.399963229728653;  // π(3 − √5)
  std::size_t segment = 0;
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    Vec3 position, tangent, d1, d2;
    track.at(t * track.length(), position, tangent, d1, d2, segment);
    const double radius = wisp.root_radius + (wisp.tip_radius - wisp.root_radius) * t;
    for (int j = 0; j < kWispTubeLines; ++j) {
      const double rho = std::sqrt((j + 0.5) / kWispTubeLines), angle = j * kGoldenAngle;
      lines[std::size_t(j) * n + i] = position + radius * rho * (std::cos(angle) * d1 + std::sin(angle) * d2);
    }
  }
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
