#include "density/accumulator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "density/slabs.h"

namespace hairfit {

namespace {

void check_fibre(const FibreSpan& fibre, size_t item) {
  for (size_t p = 0; p < fibre.size; ++p) {
    if (!fibre.points[p].allFinite()) {
      std::ostringstream m;
      m << "density: fibre " << item << " point " << p << " is not finite";
      throw std::invalid_argument(m.str());
    }
  }
}

// Adds the CDM contributions of the fibres to the cells with k in [k_begin, k_end), in order,
// and counts the crossing segments per cell when `counts` is given.
void deposit_fibres(const GridGeometry& grid, std::vector<double>& values, std::int32_t* counts,
                    const std::vector<FibreSpan>& fibres, const FibreLayers& layers, int k_begin, int k_end) {
  const double diagonal = grid.cell_diagonal();
  if (counts)
    for_each_crossing_in_slab(grid, fibres, layers, k_begin, k_end, [&](std::int64_t cell, double length) {
      values[cell] += length / diagonal;
      ++counts[cell];
    });
  else
    for_each_crossing_in_slab(grid, fibres, layers, k_begin, k_end,
                              [&](std::int64_t cell, double length) { values[cell] += length / diagonal; });
}

void occupy_tubes(const GridGeometry& grid, std::vector<double>& values, const std::vector<Tube>& tubes,
                  OccupancyShape shape, int k_begin, int k_end) {
  for (const Tube& tube : tubes) {
    for (size_t s = 0; s + 1 < tube.points.size(); ++s) {
      const Frustum f{tube.points[s], tube.points[s + 1], tube.radii[s], tube.radii[s + 1]};
      const double r = std::max(f.radius_a, f.radius_b);
      int k_first, k_last;
      z_layers(grid, std::min(f.a.z(), f.b.z()) - r, std::max(f.a.z(), f.b.z()) + r, k_first, k_last);
      if (k_last + 1 < k_begin || k_first - 1 >= k_end) continue;
      // A cell already occupied (by this tube, an earlier one or an earlier batch) stays 1.
      for (const Vec3i& c : frustum_cells_unsettled(grid, f, shape, values, k_begin, k_end))
        values[grid.index(c.x(), c.y(), c.z())] = 1.0;
    }
  }
}

void check_tube(const Tube& tube, size_t item) {
  if (tube.points.size() != tube.radii.size()) {
    std::ostringstream m;
    m << "density: tube " << item << " has " << tube.points.size() << " points but " << tube.radii.size()
      << " radii; give one radius per point";
    throw std::invalid_argument(m.str());
  }
  for (size_t p = 0; p < tube.points.size(); ++p) {
    if (!tube.points[p].allFinite() || !std::isfinite(tube.radii[p]) || tube.radii[p] < 0.0) {
      std::ostringstream m;
      m << "density: tube " << item << " point " << p << " is not finite or has a negative radius";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace

DensityAccumulator::DensityAccumulator(const GridGeometry& grid)
    : geometry_(grid), values_(std::make_shared<std::vector<double>>(size_t(grid.count()), 0.0)) {}

DensityAccumulator::DensityAccumulator(const DensityGrid& start)
    : geometry_(start.geometry()), values_(std::make_shared<std::vector<double>>(start.values())) {}

double DensityAccumulator::cell(int i, int j, int k) const {
  return geometry_.contains(i, j, k) ? (*values_)[geometry_.index(i, j, k)] : 0.0;
}

void DensityAccumulator::add_fibre(const std::vector<Vec3>& fibre) {
  // A one-element batch, so the single and the batch path are the same code.
  add_fibres(std::vector<FibreSpan>{FibreSpan{fibre.data(), fibre.size()}}, 1, nullptr);
}

void DensityAccumulator::add_fibres(const Curves& fibres, int threads, std::vector<std::int32_t>* segment_counts) {
  add_fibres(fibre_spans(fibres), threads, segment_counts);
}

void DensityAccumulator::add_fibres(const std::vector<FibreSpan>& fibres, int threads,
                                    std::vector<std::int32_t>* segment_counts) {
  for (size_t f = 0; f < fibres.size(); ++f) check_fibre(fibres[f], f);
  const FibreLayers layers = fibre_layers(geometry_, fibres, threads);
  std::vector<double>& values = writable_values();
  std::int32_t* counts = nullptr;
  if (segment_counts) {
    segment_counts->assign(size_t(geometry_.count()), 0);
    counts = segment_counts->data();
  }
  for_each_fibre_slab(geometry_, fibres, layers, threads, [&](int k_begin, int k_end) {
    deposit_fibres(geometry_, values, counts, fibres, layers, k_begin, k_end);
  });
}

void DensityAccumulator::occupy(const Tube& tube, OccupancyShape shape) {
  check_tube(tube, 0);
  occupy_tubes(geometry_, writable_values(), {tube}, shape, 0, geometry_.dims.z());
}

void DensityAccumulator::occupy_all(const std::vector<Tube>& tubes, int threads, OccupancyShape shape) {
  for (size_t t = 0; t < tubes.size(); ++t) check_tube(tubes[t], t);
  std::vector<double>& values = writable_values();
  for_each_z_slab(geometry_, threads,
                  [&](int k_begin, int k_end) { occupy_tubes(geometry_, values, tubes, shape, k_begin, k_end); });
}

DensityGrid DensityAccumulator::freeze() const& { return DensityGrid(geometry_, values_); }

std::vector<double>& DensityAccumulator::writable_values() {
  if (values_.use_count() > 1) values_ = std::make_shared<std::vector<double>>(*values_);  // a frozen grid shares them
  return *values_;
}

DensityGrid DensityAccumulator::freeze() && {
  DensityGrid grid(geometry_, std::shared_ptr<const std::vector<double>>(std::move(values_)));
  values_ = std::make_shared<std::vector<double>>();  // left empty but valid
  geometry_.dims = Vec3i::Zero();
  return grid;
}

}  // namespace hairfit
