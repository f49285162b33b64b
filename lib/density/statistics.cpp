#include "density/statistics.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/parallel.h"
#include "density/slabs.h"

namespace hairfit {

namespace {

SegmentHistogram histogram_of_spans(const GridGeometry& grid, const std::vector<FibreSpan>& fibres, int threads) {
  // Each segment visits a cell at most once (traverse_segment), so a per-cell count of visits is
  // the number of distinct segments crossing it. Integer counts: any order gives the same result.
  std::vector<int32_t> count(size_t(grid.count()), 0);
  const FibreLayers layers = fibre_layers(grid, fibres, threads);
  for_each_fibre_slab(grid, fibres, layers, threads, [&](int k_begin, int k_end) {
    for_each_crossing_in_slab(grid, fibres, layers, k_begin, k_end, [&](int64_t cell, double) { ++count[cell]; });
  });
  return histogram_of_counts(count);
}

}  // namespace

SegmentHistogram segment_histogram(const GridGeometry& grid, const Curves& fibres, int threads) {
  return histogram_of_spans(grid, fibre_spans(fibres), threads);
}

SegmentHistogram histogram_of_counts(const std::vector<int32_t>& segment_counts) {
  SegmentHistogram h;
  for (int32_t n : segment_counts) {
    if (n <= 0) continue;
    if (size_t(n) >= h.cells_with.size()) h.cells_with.resize(size_t(n) + 1, 0);
    ++h.cells_with[n];
  }
  return h;
}

std::string histogram_csv(const SegmentHistogram& histogram) {
  std::ostringstream out;
  out << "segments_per_cell,cells\n";
  for (size_t n = 1; n < histogram.cells_with.size(); ++n) out << n << ',' << histogram.cells_with[n] << '\n';
  return out.str();
}

DensityStatistics density_statistics(const DensityGrid& grid, const CellPredicate& inside, int threads) {
  const GridGeometry& g = grid.geometry();
  const std::vector<double>& v = grid.values();
  std::vector<char> in_region(v.size(), 1);
  if (inside) {  // one layer of cells per item: each writes only its own flags
    parallel_for(g.dims.z(), threads, [&](int k) {
      for (int j = 0; j < g.dims.y(); ++j)
        for (int i = 0; i < g.dims.x(); ++i) in_region[g.index(i, j, k)] = inside(g.cell_centre(i, j, k)) ? 1 : 0;
    });
  }
  return density_statistics(grid, in_region);
}

DensityStatistics density_statistics(const DensityGrid& grid, const std::vector<char>& in_region) {
  const std::vector<double>& v = grid.values();
  if (in_region.size() != v.size()) throw std::invalid_argument("density statistics: one region flag per cell");
  DensityStatistics s;
  double sum = 0.0;
  for (size_t c = 0; c < v.size(); ++c) {
    if (!in_region[c]) continue;
    ++s.region_cells;
    if (v[c] > 0.0) {
      ++s.occupied_cells;
      sum += v[c];
    }
  }
  if (s.region_cells > 0) s.empty_share = double(s.region_cells - s.occupied_cells) / double(s.region_cells);
  if (s.occupied_cells == 0) return s;
  s.mean = sum / double(s.occupied_cells);
  // Two passes (mean, then squared deviations): no cancellation for nearly uniform densities.
  double squares = 0.0;
  for (size_t c = 0; c < v.size(); ++c)
    if (in_region[c] && v[c] > 0.0) squares += (v[c] - s.mean) * (v[c] - s.mean);
  s.coefficient_of_variation = std::sqrt(squares / double(s.occupied_cells)) / s.mean;
  return s;
}

DensitySlice centre_slice(const DensityGrid& grid, const Vec3& normal, const Vec3& up) {
  const double nn = normal.norm();
  if (!(nn > 0.0) || !normal.allFinite() || !up.allFinite())
    throw std::invalid_argument("density slice: the normal must be a finite non-zero vector");
  const Vec3 n = normal / nn;
  const Vec3 v_raw = up - up.dot(n) * n;
  if (!(v_raw.norm() > 1e-9 * std::max(1.0, up.norm())))
    throw std::invalid_argument("density slice: `up` must not be parallel to the normal");
  const Vec3 v_axis = v_raw.normalized();
  const Vec3 u_axis = v_axis.cross(n);  // = up × normal, normalised

  const GridGeometry& g = grid.geometry();
  const double h = g.voxel;
  const Vec3 lo = g.origin, hi = g.upper(), centre = 0.5 * (lo + hi);
  double u_min = 0.0, u_max = 0.0, v_min = 0.0, v_max = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    const Vec3 r = corner - centre;
    u_min = std::min(u_min, r.dot(u_axis));
    u_max = std::max(u_max, r.dot(u_axis));
    v_min = std::min(v_min, r.dot(v_axis));
    v_max = std::max(v_max, r.dot(v_axis));
  }
  DensitySlice s;
  // Round-off must not add a column when the extent is a whole number of voxels.
  s.width = std::max(1, int(std::ceil((u_max - u_min) / h - 1e-9)));
  s.height = std::max(1, int(std::ceil((v_max - v_min) / h - 1e-9)));
  s.u_step = h * u_axis;
  s.v_step = h * v_axis;
  s.origin = centre + (u_min + 0.5 * h) * u_axis + (v_min + 0.5 * h) * v_axis;
  s.values.resize(size_t(s.width) * s.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      s.values[size_t(x) + size_t(s.width) * y] = grid.value(s.origin + double(x) * s.u_step + double(y) * s.v_step);
  return s;
}

namespace {

// The world axis a step runs along and its sign; throws unless the step is axis-aligned.
void step_axis(const Vec3& step, int& axis, bool& negative) {
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    if (step[k] != 0.0) {
      axis = k;
      ++count;
    }
  }
  if (count != 1) throw std::invalid_argument("density slice: NRRD needs a slice along world axes");
  negative = step[axis] < 0.0;
}

}  // namespace

NrrdVolume slice_to_nrrd(const DensitySlice& slice) {
  int au = 0, av = 0;
  bool nu = false, nv = false;
  step_axis(slice.u_step, au, nu);
  step_axis(slice.v_step, av, nv);
  if (au == av) throw std::invalid_argument("density slice: u and v run along the same axis");
  const int an = 3 - au - av;
  NrrdVolume vol;
  vol.sizes[au] = slice.width;
  vol.sizes[av] = slice.height;
  vol.sizes[an] = 1;
  vol.spacing[au] = std::abs(slice.u_step[au]);
  vol.spacing[av] = std::abs(slice.v_step[av]);
  vol.spacing[an] = vol.spacing[au];
  // NRRD indices grow along +axis: a negative step is stored mirrored, from its far end.
  vol.origin = slice.origin;
  if (nu) vol.origin += double(slice.width - 1) * slice.u_step;
  if (nv) vol.origin += double(slice.height - 1) * slice.v_step;
  vol.data.assign(size_t(slice.width) * slice.height, 0.0f);
  const int64_t stride[3] = {1, vol.sizes.x(), int64_t(vol.sizes.x()) * vol.sizes.y()};
  for (int y = 0; y < slice.height; ++y) {
    for (int x = 0; x < slice.width; ++x) {
      const int64_t iu = nu ? slice.width - 1 - x : x, iv = nv ? slice.height - 1 - y : y;
      vol.data[size_t(iu * stride[au] + iv * stride[av])] = float(slice.values[size_t(x) + size_t(slice.width) * y]);
    }
  }
  return vol;
}

NrrdVolume grid_to_nrrd(const DensityGrid& grid) {
  const GridGeometry& g = grid.geometry();
  NrrdVolume vol;
  vol.sizes = g.dims;
  vol.origin = g.cell_centre(0, 0, 0);
  vol.spacing = Vec3::Constant(g.voxel);
  vol.data.assign(grid.values().begin(), grid.values().end());
  return vol;
}

}  // namespace hairfit
