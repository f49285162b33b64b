// Statistics on hand-made cases whose answers are counted by hand.
#include <doctest/doctest.h>

#include <cmath>

#include "density/accumulator.h"
#include "density/statistics.h"

using namespace hairfit;

namespace {

GridGeometry unit_grid(int nx, int ny, int nz) {
  GridGeometry g;
  g.origin = Vec3(0, 0, 0);
  g.voxel = 1.0;
  g.dims = Vec3i(nx, ny, nz);
  return g;
}

}  // namespace

TEST_CASE("segments-per-cell histogram counts distinct segments per crossed cell") {
  const GridGeometry g = unit_grid(6, 4, 4);
  // Fibre A: one segment along x through row (y, z) = (1, 1), cells x = 0..5.
  // Fibre B: two segments in the same row, split at x = 2.5: cells 0..2 and 2..5 → cell 2 twice.
  // Fibre C: one segment along y through column x = 4, z = 1: cells y = 0..3 (crosses the row at
  // cell (4, 1, 1)).
  const Curves fibres = make_curves({
      {Vec3(0.0, 1.5, 1.5), Vec3(6.0, 1.5, 1.5)},
      {Vec3(0.0, 1.2, 1.7), Vec3(2.5, 1.2, 1.7), Vec3(6.0, 1.2, 1.7)},
      {Vec3(4.5, 0.0, 1.5), Vec3(4.5, 4.0, 1.5)},
  });
  // Row cells: x=0,1: A,B1 → 2; x=2: A,B1,B2 → 3; x=3,5: A,B2 → 2; x=4: A,B2,C → 3.
  // Column cells other than (4,1,1): y = 0, 2, 3 → 1 each.
  const SegmentHistogram h = segment_histogram(g, fibres);
  REQUIRE(h.cells_with.size() == 4);
  CHECK(h.cells_with[1] == 3);
  CHECK(h.cells_with[2] == 4);
  CHECK(h.cells_with[3] == 2);
  CHECK(histogram_csv(h) == "segments_per_cell,cells\n1,3\n2,4\n3,2\n");
  CHECK(histogram_csv(segment_histogram(g, {})) == "segments_per_cell,cells\n");
}

TEST_CASE("coefficient of variation and empty share, with and without a region") {
  const GridGeometry g = unit_grid(4, 1, 1);
  DensityAccumulator acc(g);
  // Cells 0 and 1 get length 1 (value 1/√3), cells 2 gets 3 fibres (3/√3), cell 3 nothing.
  acc.add_fibre({Vec3(0, 0.5, 0.5), Vec3(2, 0.5, 0.5)});
  for (int r = 0; r < 3; ++r) acc.add_fibre({Vec3(2, 0.5, 0.5), Vec3(3, 0.5, 0.5)});
  const DensityGrid grid = acc.freeze();
  const double s = 1.0 / std::sqrt(3.0);
  const DensityStatistics all = density_statistics(grid);
  CHECK(all.region_cells == 4);
  CHECK(all.occupied_cells == 3);
  CHECK(all.empty_share == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(all.mean == doctest::Approx(5.0 / 3.0 * s).epsilon(1e-14));
  // Values {1, 1, 3}·s: mean 5/3, population std √(8/9)·... = √((4/9+4/9+16/9)/3) = √(24/27).
  CHECK(all.coefficient_of_variation == doctest::Approx(std::sqrt(24.0 / 27.0) / (5.0 / 3.0)).epsilon(1e-14));
  // Region: cells 1..3 only.
  const DensityStatistics part = density_statistics(grid, [](const Vec3& p) { return p.x() > 1.0; });
  CHECK(part.region_cells == 3);
  CHECK(part.occupied_cells == 2);
  CHECK(part.empty_share == doctest::Approx(1.0 / 3.0).epsilon(1e-15));
  CHECK(part.coefficient_of_variation == doctest::Approx(0.5).epsilon(1e-14));  // {1, 3}: std 1, mean 2
  const DensityStatistics none = density_statistics(grid, [](const Vec3&) { return false; });
  CHECK(none.region_cells == 0);
  CHECK(none.empty_share == 0.0);
  CHECK(none.coefficient_of_variation == 0.0);
}

TEST_CASE("centre slice: cell values of the middle layer, placed in the world, and as NRRD") {
  GridGeometry g;
  g.origin = Vec3(-1.0, 2.0, 0.5);
  g.voxel = 0.5;
  g.dims = Vec3i(5, 3, 4);
  DensityAccumulator acc(g);
  // Mark cell (i, j, k) with a value encoding (j, k): one fibre of length ℓ inside it, along x,
  // only in the middle x-layer i = 2.
  auto code = [](int j, int k) { return 0.01 * (1 + j + 3 * k); };
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = g.cell_centre(2, j, k);
      const double len = code(j, k) * g.cell_diagonal();
      acc.add_fibre({c - Vec3(0.5 * len, 0, 0), c + Vec3(0.5 * len, 0, 0)});
    }
  const DensityGrid grid = acc.freeze();
  // Sagittal: normal x (left–right), up +y: width runs along up × normal = y × x = −z.
  const DensitySlice s = centre_slice(grid, Vec3(1, 0, 0), Vec3(0, 1, 0));
  CHECK(s.width == 4);
  CHECK(s.height == 3);
  CHECK((s.u_step - Vec3(0, 0, -0.5)).norm() < 1e-15);
  CHECK((s.v_step - Vec3(0, 0.5, 0)).norm() < 1e-15);
  CHECK((s.origin - g.cell_centre(2, 0, 3)).norm() < 1e-12);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) CHECK(s.values[x + 4 * y] == doctest::Approx(code(y, 3 - x)).epsilon(1e-12));
  const NrrdVolume vol = slice_to_nrrd(s);
  CHECK(vol.sizes == Vec3i(1, 3, 4));
  CHECK((vol.origin - g.cell_centre(2, 0, 0)).norm() < 1e-12);
  CHECK((vol.spacing - Vec3(0.5, 0.5, 0.5)).norm() == 0.0);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j) CHECK(vol.data[j + 3 * k] == doctest::Approx(code(j, k)).epsilon(1e-6));
  // Even layer count along the normal: the mean of the two middle layers.
  const DensitySlice z = centre_slice(grid, Vec3(0, 0, 1), Vec3(0, 1, 0));
  CHECK(z.width == 5);
  CHECK(z.height == 3);
  CHECK(z.values[2 + 5 * 1] == doctest::Approx(0.5 * (code(1, 1) + code(1, 2))).epsilon(1e-12));
  CHECK_THROWS_AS(centre_slice(grid, Vec3(0, 0, 0), Vec3(0, 1, 0)), std::invalid_argument);
  CHECK_THROWS_AS(centre_slice(grid, Vec3(0, 1, 0), Vec3(0, 2, 0)), std::invalid_argument);
  CHECK_THROWS_AS(slice_to_nrrd(centre_slice(grid, Vec3(1, 1, 0), Vec3(0, 0, 1))), std::invalid_argument);
  const NrrdVolume whole = grid_to_nrrd(grid);
  CHECK(whole.sizes == g.dims);
  CHECK(whole.data.size() == size_t(g.count()));
}
