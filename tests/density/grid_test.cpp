// Grid queries against closed forms: trilinear interpolation reproduces linear fields exactly;
// the central-difference gradient converges to the true gradient at second order; derivatives
// (gradient, Jacobian of the central gradient) agree with finite differences.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "density/accumulator.h"
#include "density/grid.h"

using namespace hairfit;

namespace {

// A grid whose cells hold f ≥ 0 at their centres, built through the public API only: a fibre of
// length ℓ lying inside one cell adds exactly ℓ / h√3 to it (CDM), so short fibres along x through
// each centre deposit f piece by piece.
template <class F>
DensityGrid grid_of(const GridGeometry& g, F f) {
  DensityAccumulator acc(g);
  std::vector<std::vector<Vec3>> fibres;
  const double diag = g.cell_diagonal();
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        double v = f(g.cell_centre(i, j, k));
        const Vec3 c = g.cell_centre(i, j, k);
        while (v > 0.0) {
          const double piece = std::min(v, 0.9 / std::sqrt(3.0));  // 0.9 h long at most: inside the cell
          const double len = piece * diag;
          fibres.push_back({c - Vec3(0.5 * len, 0, 0), c + Vec3(0.5 * len, 0, 0)});
          v -= piece;
        }
      }
  acc.add_fibres(make_curves(fibres), 1);
  return acc.freeze();
}

GridGeometry geometry(double h, int n) {
  GridGeometry g;
  g.origin = Vec3(-0.5 * n * h, -0.5 * n * h + 0.1, -0.5 * n * h - 0.2);
  g.voxel = h;
  g.dims = Vec3i(n, n, n);
  return g;
}

}  // namespace

TEST_CASE("make_grid_geometry covers the box, centred, and rejects bad input") {
  const GridGeometry g = make_grid_geometry(Vec3(-1, 0, 2), Vec3(2.1, 1, 2.3), 0.25);
  CHECK(g.dims == Vec3i(13, 4, 2));
  CHECK((g.origin.array() <= Vec3(-1, 0, 2).array()).all());
  CHECK((g.upper().array() >= Vec3(2.1, 1, 2.3).array()).all());
  CHECK((0.5 * (g.origin + g.upper()) - Vec3(0.55, 0.5, 2.15)).norm() < 1e-12);
  CHECK_THROWS_AS(make_grid_geometry(Vec3(0, 0, 0), Vec3(1, 1, 1), 0.0), InputError);
  CHECK_THROWS_AS(make_grid_geometry(Vec3(0, 0, 0), Vec3(1, 1, 1), NAN), InputError);
  CHECK_THROWS_AS(make_grid_geometry(Vec3(0, 0, 0), Vec3(1, -1, 1), 0.1), InputError);
  CHECK_THROWS_AS(make_grid_geometry(Vec3(0, 0, 0), Vec3(100, 100, 100), 0.001), InputError);
}

TEST_CASE("trilinear occupancy reproduces a positive linear field and its gradient exactly") {
  const GridGeometry g = geometry(0.25, 10);
  const Vec3 slope(0.3, -0.2, 0.5);
  auto f = [&](const Vec3& p) { return 2.0 + slope.dot(p); };
  const DensityGrid grid = grid_of(g, f);
  // Deposited values equal f at cell centres to round-off.
  CHECK(std::abs(grid.cell(4, 5, 6) - f(g.cell_centre(4, 5, 6))) < 1e-12);
  for (const Vec3& p : {Vec3(0.01, 0.13, -0.27), Vec3(-0.4, 0.3, 0.2), Vec3(0.55, -0.6, -0.5)}) {
    const DensityValueGradient vg = grid.value_and_gradient(p);
    CHECK(std::abs(vg.value - f(p)) < 1e-12);
    CHECK((vg.gradient - slope).norm() < 1e-11);
    CHECK((grid.central_gradient(p) - slope).norm() < 1e-11);
  }
  // Outside the grid every cell counts as 0.
  CHECK(grid.value(Vec3(100, 0, 0)) == 0.0);
  CHECK(grid.value_and_gradient(Vec3(NAN, 0, 0)).value == 0.0);
  CHECK(DensityGrid().value(Vec3(0, 0, 0)) == 0.0);
}

TEST_CASE("central-difference gradient of a smooth field converges at second order") {
  auto f = [](const Vec3& p) { return 2.0 + std::sin(1.3 * p.x()) * std::cos(0.9 * p.y()) + 0.5 * std::sin(p.z() + 0.4); };
  auto grad = [](const Vec3& p) {
    return Vec3(1.3 * std::cos(1.3 * p.x()) * std::cos(0.9 * p.y()), -0.9 * std::sin(1.3 * p.x()) * std::sin(0.9 * p.y()),
                0.5 * std::cos(p.z() + 0.4));
  };
  // Samples at cell centres (where interpolation adds no error), in the interior.
  double previous = 0.0;
  for (int level = 0; level < 3; ++level) {
    const double h = 0.2 / (1 << level);
    const int n = int(std::lround(2.4 / h));
    const GridGeometry g = geometry(h, n);
    const DensityGrid grid = grid_of(g, f);
    double err = 0.0;
    for (const Vec3& p : {Vec3(0.1, 0.1, 0.0), Vec3(-0.3, 0.4, 0.3), Vec3(0.5, -0.2, -0.4)}) {
      const Vec3 q = (p - g.origin) / h;  // snap to the nearest cell centre
      const Vec3 c = g.cell_centre(int(q.x()), int(q.y()), int(q.z()));
      err = std::max(err, (grid.central_gradient(c) - grad(c)).norm());
    }
    if (level > 0) CHECK(previous / err > 3.5);  // halving h quarters the error
    previous = err;
  }
  CHECK(previous < 1e-3);
}

TEST_CASE("gradient and Jacobian agree with finite differences away from cell-centre planes") {
  const GridGeometry g = geometry(0.25, 12);
  auto f = [](const Vec3& p) { return 1.5 + std::sin(2.0 * p.x() + p.y()) * std::cos(1.5 * p.z()); };
  const DensityGrid grid = grid_of(g, f);
  const double e = 1e-6;
  for (const Vec3& p : {Vec3(0.07, 0.21, -0.33), Vec3(-0.61, 0.44, 0.19), Vec3(0.3, -0.08, 0.52)}) {
    const DensityValueGradient vg = grid.value_and_gradient(p);
    const DensityGradientJacobian gj = grid.central_gradient_and_jacobian(p);
    CHECK((gj.gradient - grid.central_gradient(p)).norm() == 0.0);
    for (int s = 0; s < 3; ++s) {
      const Vec3 dp = e * Vec3::Unit(s);
      CHECK(std::abs((grid.value(p + dp) - grid.value(p - dp)) / (2 * e) - vg.gradient[s]) < 1e-7);
      const Vec3 col = (grid.central_gradient(p + dp) - grid.central_gradient(p - dp)) / (2 * e);
      CHECK((col - gj.jacobian.col(s)).norm() < 1e-6);
    }
    // The paper's definition: central difference of the interpolant one voxel either side.
    const double h = g.voxel;
    for (int s = 0; s < 3; ++s) {
      const Vec3 dp = h * Vec3::Unit(s);
      CHECK(std::abs((grid.value(p + dp) - grid.value(p - dp)) / (2 * h) - gj.gradient[s]) < 1e-12);
    }
  }
}

TEST_CASE("from_values builds the grid of given cell values and refuses values that do not fill it") {
  const GridGeometry g = geometry(0.5, 4);
  std::vector<double> values(g.count());
  for (std::size_t n = 0; n < values.size(); ++n) values[n] = 0.25 * double(n % 7);
  const DensityGrid grid = DensityGrid::from_values(g, values);
  CHECK(grid.values() == values);
  CHECK(grid.cell(1, 2, 3) == values[g.index(1, 2, 3)]);
  CHECK(grid.value(g.cell_centre(2, 1, 0)) == values[g.index(2, 1, 0)]);  // at a centre, the cell's value
  CHECK(grid.cell(-1, 0, 0) == 0.0);
  CHECK_THROWS_AS(DensityGrid::from_values(g, std::vector<double>(values.size() - 1)), std::invalid_argument);
  GridGeometry flat = g;
  flat.voxel = -0.5;
  CHECK_THROWS_AS(DensityGrid::from_values(flat, values), std::invalid_argument);
  CHECK(DensityGrid::from_values(GridGeometry{}, {}).values().empty());
}
