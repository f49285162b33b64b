// The mutable builder of a density grid (transient → persistent, STYLE.md): deposit fibres (CDM)
// or tubes (BOM) in a fixed order, then freeze() into an immutable DensityGrid. An accumulator is
// a local of one function and never shared between threads; its batch methods parallelise
// internally and are bit-identical for any thread count.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.h"
#include "core/curves.h"
#include "density/grid.h"
#include "density/slabs.h"
#include "density/voxelise.h"

namespace hairfit {

class DensityAccumulator {
 public:
  // All cells 0.
  explicit DensityAccumulator(const GridGeometry& grid);
  // Continue from an existing grid (copies its values).
  explicit DensityAccumulator(const DensityGrid& start);

  const GridGeometry& geometry() const { return geometry_; }
  double cell(int i, int j, int k) const;  // 0 outside the grid

  // CDM (paper §3.5): for every segment of the polyline (cm), every cell it crosses gains
  // (length of the segment inside the cell) / (cell diagonal h√3) — dimensionless. Parts outside
  // the grid are clipped (traverse_segment). Throws std::invalid_argument for a non-finite point.
  void add_fibre(const std::vector<Vec3>& fibre);
  // The same for every fibre, in the given order: the result is bit-identical to calling
  // add_fibre on each in turn, for any `threads` (each thread owns a z-slab of cells and adds, in
  // the fibres' order, only to its own cells, so every cell sums in the same order).
  // With `segment_counts`, also sets it to the number of distinct segments of these fibres that
  // cross each cell (index order), counted in the same traversal (histogram_of_counts turns it
  // into segment_histogram's result).
  // The fibres are read in place.
  void add_fibres(const Curves& fibres, int threads = 1, std::vector<std::int32_t>* segment_counts = nullptr);
  // The same for fibres wherever they lie.
  void add_fibres(const std::vector<FibreSpan>& fibres, int threads = 1,
                  std::vector<std::int32_t>* segment_counts = nullptr);

  // BOM (paper §3.5): every cell the tube occupies (frustum_cells per segment) becomes 1.
  void occupy(const Tube& tube, OccupancyShape shape = OccupancyShape::frustum);
  // The same for every tube; order-independent and identical for any `threads`.
  void occupy_all(const std::vector<Tube>& tubes, int threads = 1,
                  OccupancyShape shape = OccupancyShape::frustum);

  // The immutable grid of the values so far. The const version shares the buffer and the
  // accumulator stays usable: its next deposit copies the buffer (8 bytes a cell, e.g. 14 MB for
  // 120³ cells) if a grid frozen from it is still alive, and writes in place if none is. The
  // rvalue version (std::move(acc).freeze()) hands the buffer over.
  DensityGrid freeze() const&;
  DensityGrid freeze() &&;

 private:
  // The values, about to be written: copied first while a frozen grid shares them.
  std::vector<double>& writable_values();

  GridGeometry geometry_;
  std::shared_ptr<std::vector<double>> values_;
};

}  // namespace hairfit
