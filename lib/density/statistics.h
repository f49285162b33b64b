// What users look at in a density result (paper §3.5, Fig. 5 and 6; docs/design.md §6): the histogram of
// segments per cell, the coefficient of variation of occupied cells, the share of the acceptable
// region left empty, and a planar slice for NRRD files and pictures.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/curves.h"
#include "core/types.h"
#include "density/grid.h"
#include "io/nrrd.h"

namespace hairfit {

// Fig. 5: cells_with[n] = number of cells crossed (positive length, traverse_segment) by exactly n
// distinct segments of the fibres (polylines, cm), for n ≥ 1; cells_with[0] is unused (0). The
// vector ends at the largest n present. Identical for any `threads`.
struct SegmentHistogram {
  std::vector<int64_t> cells_with;
};
SegmentHistogram segment_histogram(const GridGeometry& grid, const Curves& fibres, int threads = 1);
// The histogram of per-cell segment counts (DensityAccumulator::add_fibres counts them while it
// deposits, so a stage that does both traverses the segments once).
SegmentHistogram histogram_of_counts(const std::vector<int32_t>& segment_counts);
// "segments_per_cell,cells\n" then one row per n ≥ 1 (rows with 0 cells included, so the
// abscissa is contiguous), '\n' line ends.
std::string histogram_csv(const SegmentHistogram& histogram);

// Which cells belong to the region the statistics describe (e.g. the acceptable region: inside
// the hair volume and outside the head), asked at each cell centre (cm). Empty = every cell.
using CellPredicate = std::function<bool(const Vec3&)>;

struct DensityStatistics {
  int64_t region_cells = 0;      // cells whose centre is in the region
  int64_t occupied_cells = 0;    // region cells with value > 0
  double mean = 0.0;             // mean value over occupied region cells
  double coefficient_of_variation = 0.0;  // population standard deviation / mean, occupied region cells
  double empty_share = 0.0;      // (region − occupied) / region cells; 0 for an empty region
};
// Summed in index order (deterministic). A region without occupied cells gives mean = cv = 0.
// `inside` is asked on up to `threads` threads at once (it must be safe for that).
DensityStatistics density_statistics(const DensityGrid& grid, const CellPredicate& inside = {}, int threads = 1);
// The same for a region given cell by cell: in_region[c] != 0 (index order, one per cell).
DensityStatistics density_statistics(const DensityGrid& grid, const std::vector<char>& in_region);

// A planar slice: values[u + width·v] sampled (trilinearly) at origin + u·u_step + v·v_step.
struct DensitySlice {
  int width = 0, height = 0;
  Vec3 origin = Vec3::Zero();  // cm: world position of sample (0, 0)
  Vec3 u_step = Vec3::Zero();  // cm between neighbouring samples along the width
  Vec3 v_step = Vec3::Zero();  // cm between neighbouring samples along the height
  std::vector<double> values;
};

// The plane through the grid's centre perpendicular to `normal` (e.g. the left–right axis for the
// centre sagittal slice of Fig. 6), sampled every voxel. Height runs along `up` projected into
// the plane, width along up × normal: seen from the +normal side, u runs to the right and v up.
// When normal is a grid axis and `up` another, samples fall on cell
// centres of the grid's middle layer (the mean of the two middle layers for an even count) and
// the slice covers the grid exactly. Throws std::invalid_argument when normal is zero or up is
// parallel to it.
DensitySlice centre_slice(const DensityGrid& grid, const Vec3& normal, const Vec3& up);

// The slice as a one-sample-thick NRRD volume, placed where it lies in the world. Requires
// u_step and v_step along two different world axes (std::invalid_argument otherwise).
NrrdVolume slice_to_nrrd(const DensitySlice& slice);
// The whole grid as NRRD (samples at cell centres).
NrrdVolume grid_to_nrrd(const DensityGrid& grid);

}  // namespace hairfit
