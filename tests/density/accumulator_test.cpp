// Deposits: the CDM mass equals the fibre length inside the grid over the cell diagonal; batch and
// one-by-one deposits agree; 1, 2 and 4 threads give byte-identical grids; frozen grids never
// change.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/random.h"
#include "density/accumulator.h"
#include "density/statistics.h"

using namespace hairfit;

namespace {

GridGeometry bench_like_grid() {
  return make_grid_geometry(Vec3(-4, -4, -4), Vec3(4, 4, 4), 0.25);
}

// Wavy polylines, some leaving the grid, some on grid planes.
std::vector<std::vector<Vec3>> random_fibres(int count, int segments, std::uint64_t seed) {
  std::vector<std::vector<Vec3>> fibres;
  for (int f = 0; f < count; ++f) {
    Random rng(seed, RandomStage::test, f);
    std::vector<Vec3> fibre;
    Vec3 p(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
    if (f % 9 == 0) p = Vec3(0.25 * std::round(4 * p.x()), 0.25 * std::round(4 * p.y()), p.z());  // on a grid line
    Vec3 dir = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    for (int s = 0; s <= segments; ++s) {
      fibre.push_back(p);
      if (f % 9 != 0) dir = (dir + 0.3 * Vec3(rng.normal(), rng.normal(), rng.normal())).normalized();
      p += (f % 9 == 0 ? Vec3(0, 0, 0.3) : Vec3(0.3 * dir));
    }
    fibres.push_back(fibre);
  }
  return fibres;
}

std::vector<Tube> random_tubes(int count, int segments, std::uint64_t seed) {
  std::vector<Tube> tubes;
  for (const auto& fibre : random_fibres(count, segments, seed)) {
    Tube t{fibre, {}};
    Random rng(seed + 1, RandomStage::test, tubes.size());
    for (size_t i = 0; i < fibre.size(); ++i) t.radii.push_back(rng.uniform(0.3, 0.6));
    tubes.push_back(t);
  }
  return tubes;
}

bool bytes_equal(const DensityGrid& a, const DensityGrid& b) {
  return a.values().size() == b.values().size() &&
         std::memcmp(a.values().data(), b.values().data(), a.values().size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("CDM mass: every fibre adds its in-grid length over the cell diagonal") {
  const GridGeometry g = bench_like_grid();
  DensityAccumulator acc(g);
  const std::vector<Vec3> fibre = {Vec3(-5, 0.1, 0.2), Vec3(-1, 0.7, -0.3), Vec3(1.5, 1.5, 1.5), Vec3(1.5, 1.5, 1.5),
                                   Vec3(1.5001, 1.5, 1.5)};
  acc.add_fibre(fibre);
  const DensityGrid grid = acc.freeze();
  double mass = 0.0;
  for (double v : grid.values()) mass += v;
  // Clipped first segment: x from −4 (the grid face) to −1 along a straight line.
  const Vec3 d = fibre[1] - fibre[0];
  const double inside = d.norm() * (fibre[1].x() - g.origin.x()) / d.x() + (fibre[2] - fibre[1]).norm() + 1e-4;
  CHECK(std::abs(mass * g.cell_diagonal() - inside) < 1e-12 * inside);
  CHECK_THROWS_AS(acc.add_fibre({Vec3(0, 0, 0), Vec3(NAN, 0, 0)}), std::invalid_argument);
}

TEST_CASE("deposits are byte-identical for 1, 2 and 4 threads and match one-by-one deposits") {
  const GridGeometry g = bench_like_grid();
  SUBCASE("CDM") {
    const auto fibres = random_fibres(400, 40, 31);
    DensityAccumulator serial(g);
    for (const auto& f : fibres) serial.add_fibre(f);
    const DensityGrid reference = serial.freeze();
    for (int threads : {1, 2, 3, 4}) {
      DensityAccumulator acc(g);
      // Two batches, as the guide loop deposits them.
      acc.add_fibres(make_curves(std::vector<std::vector<Vec3>>(fibres.begin(), fibres.begin() + 150)), threads);
      acc.add_fibres(make_curves(std::vector<std::vector<Vec3>>(fibres.begin() + 150, fibres.end())), threads);
      CHECK_MESSAGE(bytes_equal(acc.freeze(), reference), threads << " threads");
    }
    // Not a vacuous comparison: many cells sum several contributions.
    CHECK(segment_histogram(g, make_curves(fibres)).cells_with.size() > 4);
  }
  SUBCASE("BOM") {
    const auto tubes = random_tubes(60, 20, 32);
    DensityAccumulator serial(g);
    for (const auto& t : tubes) serial.occupy(t);
    const DensityGrid reference = serial.freeze();
    for (int threads : {1, 2, 4}) {
      DensityAccumulator acc(g);
      acc.occupy_all(tubes, threads);
      CHECK(bytes_equal(acc.freeze(), reference));
    }
    // Equal to the union of tube_cells.
    std::vector<char> expected(size_t(g.count()), 0);
    for (const auto& t : tubes)
      for (int64_t c : tube_cells(g, t, OccupancyShape::frustum)) expected[c] = 1;
    size_t mismatches = 0;
    for (size_t c = 0; c < expected.size(); ++c) mismatches += (reference.values()[c] == 1.0) != (expected[c] == 1);
    CHECK(mismatches == 0);
  }
  SUBCASE("histogram") {
    const Curves fibres = make_curves(random_fibres(300, 30, 33));
    const SegmentHistogram one = segment_histogram(g, fibres, 1);
    CHECK(segment_histogram(g, fibres, 2).cells_with == one.cells_with);
    CHECK(segment_histogram(g, fibres, 4).cells_with == one.cells_with);
    // Counted while depositing: the same histogram and the same deposit as done separately.
    DensityAccumulator plain(g);
    plain.add_fibres(fibres, 1);
    for (int threads : {1, 3}) {
      DensityAccumulator acc(g);
      std::vector<std::int32_t> counts{7};  // replaced, not added to
      acc.add_fibres(fibres, threads, &counts);
      CHECK(histogram_of_counts(counts).cells_with == one.cells_with);
      CHECK(bytes_equal(acc.freeze(), plain.freeze()));
    }
    // The same fibres one by one: the same deposit.
    DensityAccumulator one_by_one(g);
    for (std::size_t f = 0; f < fibres.count(); ++f)
      one_by_one.add_fibre(std::vector<Vec3>(fibres.points.begin() + fibres.offsets[f], fibres.points.begin() + fibres.offsets[f + 1]));
    CHECK(bytes_equal(one_by_one.freeze(), plain.freeze()));
  }
  SUBCASE("statistics over a region") {
    DensityAccumulator acc(g);
    acc.add_fibres(make_curves(random_fibres(300, 30, 34)), 2);
    const DensityGrid grid = acc.freeze();
    const CellPredicate region = [](const Vec3& p) { return p.x() + 0.5 * p.z() < 0.3; };
    const DensityStatistics one = density_statistics(grid, region, 1);
    CHECK(one.region_cells > 0);
    CHECK(one.region_cells < g.count());
    for (int threads : {2, 4}) {
      const DensityStatistics s = density_statistics(grid, region, threads);
      CHECK(s.region_cells == one.region_cells);
      CHECK(s.occupied_cells == one.occupied_cells);
      CHECK(s.mean == one.mean);
      CHECK(s.coefficient_of_variation == one.coefficient_of_variation);
    }
  }
}

TEST_CASE("a frozen grid never changes; an accumulator can continue from a grid") {
  const GridGeometry g = bench_like_grid();
  DensityAccumulator acc(g);
  acc.add_fibre({Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.1, 0.1)});
  const DensityGrid first = acc.freeze();
  const double before = first.cell(16, 16, 16);
  CHECK(before > 0.0);
  acc.add_fibre({Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.1, 0.1)});
  CHECK(first.cell(16, 16, 16) == before);
  CHECK(acc.cell(16, 16, 16) == 2.0 * before);
  DensityAccumulator again(first);
  again.add_fibre({Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.1, 0.1)});
  const DensityGrid moved = std::move(again).freeze();
  CHECK(moved.cell(16, 16, 16) == acc.cell(16, 16, 16));
  CHECK(first.cell(16, 16, 16) == before);
}

TEST_CASE("freezing shares the accumulator's buffer: a deposit copies it only while a frozen grid is alive") {
  const GridGeometry g = bench_like_grid();
  DensityAccumulator acc(g);
  const std::vector<Vec3> fibre{Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.1, 0.1)};
  acc.add_fibre(fibre);
  const double* buffer;
  {
    const DensityGrid frozen = acc.freeze();
    buffer = frozen.values().data();
    CHECK(acc.freeze().values().data() == buffer);  // no copy on freezing
    acc.add_fibre(fibre);                            // copies: `frozen` must not change
    CHECK(frozen.cell(16, 16, 16) * 2.0 == acc.cell(16, 16, 16));
    CHECK(acc.freeze().values().data() != buffer);
  }
  const double* current = acc.freeze().values().data();
  acc.add_fibre(fibre);  // no grid frozen from it is alive: written in place
  const DensityGrid after = acc.freeze();
  CHECK(after.values().data() == current);
  DensityAccumulator plain(g);  // the same three deposits, never frozen in between
  for (int k = 0; k < 3; ++k) plain.add_fibre(fibre);
  CHECK(after.values() == plain.freeze().values());
}
