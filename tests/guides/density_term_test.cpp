// F4 (paper §3.5): residuals against independently computed integrals, jets against central
// finite differences, and no trace without a density model.
#include <doctest/doctest.h>

#include <algorithm>
#include <memory>
#include <cmath>
#include <cstdint>

#include "density/accumulator.h"
#include "guides/density_term.h"
#include "guides/objective.h"
#include "residual_differences.h"

using namespace hairfit;

namespace {

// A closed UV sphere of radius r about the origin, outward triangles.
Mesh ball(double r, int rings, int segments) {
  Mesh m;
  m.positions.emplace_back(0, r, 0);
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * j / segments;
      m.positions.emplace_back(r * std::sin(th) * std::cos(ph), r * std::cos(th), r * std::sin(th) * std::sin(ph));
    }
  m.positions.emplace_back(0, -r, 0);
  const int bottom = static_cast<int>(m.positions.size()) - 1;
  auto at = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    m.triangles.emplace_back(0, at(1, j), at(1, j + 1));
    m.triangles.emplace_back(bottom, at(rings - 1, j + 1), at(rings - 1, j));
    for (int i = 1; i + 1 < rings; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  for (Vec3i& t : m.triangles) {  // outward: the origin is inside
    const Vec3 n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    if (n.dot(m.positions[t[0]]) < 0) std::swap(t[1], t[2]);
  }
  return m;
}

struct World {
  DistanceField scalp = make_distance_field(ball(8.0, 16, 32), FieldSpec{0.5, 3, 20.0, 1.0, "scalp"}, 2);
  DistanceField volume = make_distance_field(ball(14.0, 16, 32), FieldSpec{0.5, 3, 20.0, 1.0, "volume"}, 2);
  // The fields share their samples, so the boundary's copies cost nothing.
  Boundary boundary() const {
    return Boundary{std::make_shared<const DistanceField>(scalp), std::make_shared<const DistanceField>(volume)};
  }
};
const World& world() {
  static const World w;
  return w;
}

// One guide rooted on top of the head, growing up and bending toward +x, following one straight
// pre-guide; K samples.
GuideTargets targets(int samples = 8) {
  GuideTargets t;
  t.root = Vec3(0, 8, 0);
  t.length = 10.0;
  t.rod.segments = 32;
  t.model = make_rod_model(hair_rod(t.length, HairMaterial{}), RodRoot{t.root, root_frame(Vec3(0, 1, 0), Vec3(1, 0, 0))});
  for (int k = 0; k <= samples; ++k) {
    t.sample_nodes.push_back(k * t.rod.segments / samples);
    t.sample_weights.push_back((k == 0 || k == samples ? 0.5 : 1.0) / samples);
  }
  GuideTargets::Neighbour nb;
  nb.weight = 1.0;
  for (int k = 0; k <= samples; ++k) {
    nb.tangents.push_back(Vec3(0, 1, 0));
    nb.darboux.push_back(Vec3::Zero());
  }
  t.neighbours.push_back(nb);
  static const Boundary boundary = world().boundary();  // outlives every GuideTargets made here
  t.boundary = &boundary;
  t.weights = GuideWeights{0.3, 0.2, 0.3, 0.2};
  return t;
}

// Fibres criss-crossing the space the guide sweeps, so the density has structure there.
DensityGrid cdm_grid(const GridGeometry& g) {
  DensityAccumulator acc(g);
  std::vector<std::vector<Vec3>> fibres;
  for (int i = 0; i < 40; ++i) {
    const double a = 0.37 * i, y = 8.0 + 0.3 * i;
    fibres.push_back({Vec3(-6 * std::cos(a), y, -6 * std::sin(a)), Vec3(6 * std::cos(a), y + 2.0, 6 * std::sin(a))});
  }
  acc.add_fibres(make_curves(fibres));
  return std::move(acc).freeze();
}
DensityGrid bom_grid(const GridGeometry& g) {
  DensityAccumulator acc(g);
  std::vector<Tube> tubes;
  for (int i = 0; i < 6; ++i) {
    const double y = 9.0 + 1.5 * i;
    tubes.push_back(guide_tube({Vec3(-6, y, -1), Vec3(0, y + 0.5, 0.3), Vec3(6, y, 1)}, 0.4, 0.7));
  }
  acc.occupy_all(tubes);
  return std::move(acc).freeze();
}

const GridGeometry& grid() {
  static const GridGeometry g = make_density_geometry(Vec3(-14, -14, -14), Vec3(14, 22, 14), 0.5, 1.0, 1.0);
  return g;
}

const double kEta[6] = {0.8, -0.4, 0.3, 0.2, 0.5, -0.3};

}  // namespace

TEST_CASE("F4 adds no residual and is zero without a density model") {
  const GuideTargets t = targets();
  const std::vector<double> r = guide_residuals(t, kEta);
  CHECK(r.size() == t.sample_nodes.size() * (6 * t.neighbours.size() + 2));
  CHECK(evaluate_guide_terms(t, kEta).f4 == 0.0);

  // With an empty grid the residuals exist but are zero, and the other terms are unchanged.
  DensityAccumulator empty(grid());
  const DensityGrid zero = std::move(empty).freeze();
  for (GuideDensityModel model : {GuideDensityModel::continuous, GuideDensityModel::binary}) {
    GuideTargets d = targets();
    d.density = zero;
    d.density_term.model = model;
    const std::vector<double> rd = guide_residuals(d, kEta);
    const std::size_t per = model == GuideDensityModel::continuous ? 2 : 3;  // + the outside residual
    REQUIRE(rd.size() == r.size() + per * t.sample_nodes.size());
    for (std::size_t i = 0; i < r.size(); ++i) CHECK(rd[i] == r[i]);
    for (std::size_t i = r.size(); i < rd.size(); ++i) CHECK(rd[i] == 0.0);
    CHECK(evaluate_guide_terms(d, kEta).f4 == 0.0);
  }
}

TEST_CASE("F4 equals the paper's integrals by the trapezoidal rule on the guide's samples") {
  const DensityGrid cdm = cdm_grid(grid()), bom = bom_grid(grid());
  GuideTargets t = targets();
  const FibreShape shape = fibre_shape(t.model, t.root, t.length, t.rod, Vec3(kEta[0], kEta[1], kEta[2]),
                                       Vec3(kEta[3], kEta[4], kEta[5]));
  // CDM: c_ρ Σ Δs ⟨∇Φρ, t⟩², gradient from the grid's own central differences.
  t.density = cdm;
  t.density_term.model = GuideDensityModel::continuous;
  t.density_term.strength = 2.5;
  double expect = 0.0;
  for (std::size_t k = 0; k < t.sample_nodes.size(); ++k) {
    const int n = t.sample_nodes[k];
    const double slope = cdm.central_gradient(shape.nodes[n]).dot(shape.tangents[n]);
    expect += 2.5 * t.sample_weights[k] * slope * slope;
  }
  CHECK(expect > 1e-4);  // the fixture gives the term something to measure
  CHECK(evaluate_guide_terms(t, kEta).f4 == doctest::Approx(expect).epsilon(1e-9));

  // BOM: Σ Δs (o² + c_BOM·S(o)²).
  t.density = bom;
  t.density_term.model = GuideDensityModel::binary;
  t.density_term.surcharge = 7.0;
  expect = 0.0;
  double surcharged = 0.0;
  for (std::size_t k = 0; k < t.sample_nodes.size(); ++k) {
    const double o = bom.value(shape.nodes[t.sample_nodes[k]]);
    const double s = surcharge_step(o, t.density_term.threshold, t.density_term.surcharge_width);
    expect += t.sample_weights[k] * (o * o + 7.0 * s * s);
    surcharged += s;
  }
  CHECK(surcharged > 0.0);  // the guide crosses occupied cells
  CHECK(evaluate_guide_terms(t, kEta).f4 == doctest::Approx(expect).epsilon(1e-9));
  // The weighted total includes w4·F4.
  const GuideTerms terms = evaluate_guide_terms(t, kEta);
  const GuideWeights& w = t.weights;
  CHECK(terms.total == doctest::Approx(w.direction * terms.f1 + w.similarity * terms.f2 + w.boundary * terms.f3 +
                                       w.density * terms.f4).epsilon(1e-12));
  // w4 = 0: F4 is still reported, unweighted.
  t.weights = GuideWeights{0.4, 0.2, 0.4, 0.0};
  CHECK(evaluate_guide_terms(t, kEta).f4 == doctest::Approx(expect).epsilon(1e-9));
}

TEST_CASE("the density ceiling is the largest F4 integrand anywhere on the grid") {
  const DensityGrid cdm = cdm_grid(grid()), bom = bom_grid(grid());
  DensityTermOptions term;
  term.model = GuideDensityModel::binary;
  term.surcharge = 7.0;
  // BOM: the grid is 0/1, so the largest integrand is 1² + c_BOM·S(1)² = 1 + 7.
  CHECK(density_ceiling(bom, term) == doctest::Approx(8.0).epsilon(1e-15));
  CHECK(density_ceiling(DensityGrid(), term) == 0.0);
  // CDM: c_ρ·|∇Φρ|² bounds c_ρ⟨∇Φρ, t⟩² for unit t, and |∇Φρ|² at random points never exceeds
  // the ceiling, which some cell centre (or a zero cell of the ring just outside) attains.
  term.model = GuideDensityModel::continuous;
  term.strength = 2.5;
  const double ceiling = density_ceiling(cdm, term);
  CHECK(ceiling > 0.0);
  const GridGeometry& g = cdm.geometry();
  double at_centres = 0.0;
  for (int k = -1; k <= g.dims.z(); ++k)
    for (int j = -1; j <= g.dims.y(); ++j)
      for (int i = -1; i <= g.dims.x(); ++i)
        at_centres = std::max(at_centres, 2.5 * cdm.central_gradient(g.cell_centre(i, j, k)).squaredNorm());
  CHECK(ceiling == doctest::Approx(at_centres).epsilon(1e-12));
  std::uint64_t state = 12345;
  auto uniform = [&state]() {  // a fixed LCG: the test is deterministic
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  double sampled = 0.0;
  for (int n = 0; n < 200000; ++n) {
    const Vec3 p = g.origin + (g.upper() - g.origin).cwiseProduct(Vec3(uniform(), uniform(), uniform()));
    sampled = std::max(sampled, 2.5 * cdm.central_gradient(p).squaredNorm());
  }
  CHECK(sampled <= ceiling * (1 + 1e-12));
  CHECK(sampled > 0.25 * ceiling);  // the samples do reach the dense part (the peak is at one centre)
}

TEST_CASE("the density ceiling of a grid that changes in places equals a full scan, bit for bit") {
  const GridGeometry g = grid();
  DensityTermOptions term;
  term.strength = 1.5;
  std::uint64_t state = 99;
  auto uniform = [&state]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  auto point = [&]() -> Vec3 { return g.origin + (g.upper() - g.origin).cwiseProduct(Vec3(uniform(), uniform(), uniform())); };
  for (int threads : {1, 3}) {
    CAPTURE(threads);
    DensityCeiling tracked(term);
    DensityAccumulator acc(cdm_grid(g));
    for (int step = 0; step < 12; ++step) {
      CAPTURE(step);
      if (step % 4 == 3) {
        acc = DensityAccumulator(g);  // a sparser grid: the ceiling falls
        acc.add_fibre({point(), point()});
      } else {
        // Short fibres here and there, and one through the corner cells of the grid.
        for (int n = 0; n < 3; ++n) {
          const Vec3 p = point();
          acc.add_fibre({p, p + 0.6 * Vec3(uniform(), uniform(), uniform())});
        }
        acc.add_fibre({g.origin, g.origin + 0.5 * g.voxel * Vec3::Ones(), g.upper()});
      }
      const DensityGrid now = acc.freeze();
      CHECK(tracked(now, threads) == density_ceiling(now, term, 1));
    }
    // A grid of the same dimensions at another voxel size is scanned afresh.
    GridGeometry finer = g;
    finer.voxel *= 0.5;
    DensityAccumulator other(finer);
    other.add_fibre({finer.origin, finer.upper()});
    const DensityGrid fine = std::move(other).freeze();
    CHECK(tracked(fine, threads) == density_ceiling(fine, term, 1));
  }
}

TEST_CASE("outside the acceptable region a sample pays the density ceiling on top of F4") {
  const DensityGrid cdm = cdm_grid(grid()), bom = bom_grid(grid());
  // A guide that leaves the volume (the ball of radius 14): nearly straight up from y = 8, 10 long.
  const double eta[6] = {0.0, 0.05, 0.0, 0.0, 0.0, -0.05};
  for (GuideDensityModel model : {GuideDensityModel::continuous, GuideDensityModel::binary}) {
    CAPTURE(static_cast<int>(model));
    GuideTargets t = targets(16);
    t.density = model == GuideDensityModel::continuous ? cdm : bom;
    t.density_term.model = model;
    const double base = evaluate_guide_terms(t, eta).f4;
    t.density_ceiling = 3.0;
    const double with_outside = evaluate_guide_terms(t, eta).f4;
    // Independently: Σ Δs·3·(H(u_S) + H(u_V))², H the smoothstep from 0 at a surface to 1 one
    // density voxel beyond it.
    const FibreShape shape = fibre_shape(t.model, t.root, t.length, t.rod, Vec3(eta[0], eta[1], eta[2]), Vec3(eta[3], eta[4], eta[5]));
    const double h = grid().voxel;
    auto step = [h](double u) {
      const double x = std::clamp(u / h, 0.0, 1.0);
      return x * x * (3 - 2 * x);
    };
    double expect = 0.0;
    int beyond = 0;
    for (std::size_t k = 0; k < t.sample_nodes.size(); ++k) {
      const Vec3& p = shape.nodes[t.sample_nodes[k]];
      const double H = step(t.boundary->beyond_scalp(p)) + step(t.boundary->beyond_volume(p));
      expect += t.sample_weights[k] * 3.0 * H * H;
      beyond += t.boundary->beyond_volume(p) > h;
    }
    CHECK(beyond >= 2);  // the fixture puts samples well beyond the volume
    CHECK(with_outside - base == doctest::Approx(expect).epsilon(1e-9));
  }
}

TEST_CASE("F4 jets match central finite differences of the double residuals") {
  const DensityGrid cdm = cdm_grid(grid()), bom = bom_grid(grid());
  for (GuideDensityModel model : {GuideDensityModel::continuous, GuideDensityModel::binary}) {
    CAPTURE(static_cast<int>(model));
    GuideTargets t = targets();
    t.density = model == GuideDensityModel::continuous ? cdm : bom;
    t.density_term.model = model;
    t.density_term.surcharge_width = 0.5;  // a wide ramp: more samples on it
    t.density_ceiling = 2.0;               // and the outside residual, for the samples beyond the volume
    const std::size_t first = t.sample_nodes.size() * (6 * t.neighbours.size() + 2);
    std::vector<double> jacobian;
    const std::vector<double> r = guide_residuals(t, kEta, &jacobian);
    const std::vector<double> differences = hairfit::testing::residual_differences(t, kEta, 1e-6);
    int compared = 0, nonzero = 0;
    for (int j = 0; j < 6; ++j) {
      for (std::size_t i = first; i < r.size(); ++i) {
        const double fd = differences[6 * i + j], ad = jacobian[6 * i + j];
        // Trilinear interpolants have kinks on cell-centre planes; a sample within h of one
        // would make the difference quotient meaningless, and then rp/rm straddle it.
        CHECK(ad == doctest::Approx(fd).epsilon(1e-5).scale(1.0));
        ++compared;
        nonzero += std::fabs(ad) > 1e-6;
      }
    }
    CHECK(compared > 0);
    CHECK(nonzero > 6);  // the derivatives are not trivially zero
  }
}

TEST_CASE("a solve stopped at a stall is the capped solve of the same length, and no worse than its start") {
  const DensityGrid cdm = cdm_grid(grid());
  GuideTargets t = targets();
  t.density = cdm;
  const GuideSolve full = optimise_guide(t, kEta, 100, 1e-12);
  REQUIRE(full.iterations > 3);
  // Every iteration lowers the cost by less than all of it: the first window of one iteration stalls.
  const GuideSolve one = optimise_guide(t, kEta, 100, 1e-12, StallTest{1, 1.0});
  CHECK(one.termination == "STALL");
  CHECK(one.converged);
  CHECK(one.iterations == 1);
  // A looser stall stops somewhere in between; Levenberg–Marquardt is deterministic, so the stopped
  // solve is exactly the solve capped at the same number of iterations.
  const GuideSolve stalled = optimise_guide(t, kEta, 100, 1e-12, StallTest{2, 1e-2});
  REQUIRE(stalled.termination == "STALL");
  CHECK(stalled.iterations < full.iterations);
  const GuideSolve capped = optimise_guide(t, kEta, stalled.iterations, 1e-12);
  for (int i = 0; i < 6; ++i) CHECK(stalled.eta[i] == capped.eta[i]);
  CHECK(stalled.final_cost <= stalled.initial_cost);
  CHECK(stalled.final_cost >= full.final_cost);
  // Off (0 iterations), the stall test changes nothing.
  const GuideSolve off = optimise_guide(t, kEta, 100, 1e-12, StallTest{0, 1.0});
  CHECK(off.iterations == full.iterations);
  for (int i = 0; i < 6; ++i) CHECK(off.eta[i] == full.eta[i]);
}

TEST_CASE("a solve by multiple shooting given no stall test stops at the scheme's stall; one given a test keeps it") {
  GuideTargets t = targets();
  t.density.reset();
  t.weights = GuideWeights{0.4, 0.2, 0.4, 0.0};
  t.model.force_per_length = Vec3(0.0, -300.0, 0.0);  // a 10 cm rod of w = 300: multiple shooting
  REQUIRE(rod_scheme(t.model) == RodScheme::multiple_shooting);
  const double start[6] = {2.0, -1.0, 0.5, 0.0, 0.0, 0.0};
  const GuideSolve plain = optimise_guide(t, start, 200, 1e-14);
  const GuideSolve stated = optimise_guide(t, start, 200, 1e-14, StallTest{30, 1e-2});
  CHECK(plain.scheme == RodScheme::multiple_shooting);
  CHECK(plain.termination == "STALL");  // this rod crawls: the stall ends it (after 40 iterations)
  CHECK(plain.termination == stated.termination);
  CHECK(plain.iterations == stated.iterations);
  for (int i = 0; i < 6; ++i) CHECK(plain.eta[i] == stated.eta[i]);
  // A window longer than the iteration cap never stalls: the solve runs on to its tolerance or cap.
  const GuideSolve unstalled = optimise_guide(t, start, 200, 1e-14, StallTest{1000, 1e-2});
  CHECK(unstalled.termination != "STALL");
  CHECK(unstalled.iterations > plain.iterations);
  CHECK(unstalled.final_cost <= plain.final_cost);
  CHECK(std::isfinite(plain.final_cost));
}

TEST_CASE("a wisp's tube lines: a sunflower over the wisp's cross-section, together its fibres' length") {
  // A straight guide along z, 10 cm, wisp radius 0.5 cm root to tip: each line runs parallel to the
  // guide at ρ_j · 0.5 cm from it, so K lines weighted n/K deposit n · 10 cm of fibre in all.
  std::vector<Vec3> guide;
  for (int k = 0; k <= 20; ++k) guide.emplace_back(0.0, 0.0, 0.5 * k);
  WispShape wisp;
  wisp.points = 16;
  wisp.root_radius = wisp.tip_radius = 0.5;
  const int n = fibre_point_count(wisp);
  std::vector<Vec3> lines(std::size_t(kWispTubeLines) * n);
  wisp_tube_lines(guide, wisp, lines.data());
  for (int j = 0; j < kWispTubeLines; ++j) {
    CAPTURE(j);
    const double rho = std::sqrt((j + 0.5) / kWispTubeLines);
    for (int i = 0; i < n; ++i) {
      const Vec3& p = lines[std::size_t(j) * n + i];
      CHECK(std::hypot(p.x(), p.y()) == doctest::Approx(0.5 * rho).epsilon(1e-12));
      CHECK(p.z() == doctest::Approx(10.0 * i / (n - 1)).epsilon(1e-12));
    }
  }
  // Evenly over the disk: the lines' centroid is near the axis (a sunflower's first moment is
  // small), and each ring of equal area holds its share of them.
  Vec3 centroid = Vec3::Zero();
  for (int j = 0; j < kWispTubeLines; ++j) centroid += lines[std::size_t(j) * n];
  CHECK((centroid / kWispTubeLines).norm() < 0.1 * 0.5);
  int inner = 0;
  for (int j = 0; j < kWispTubeLines; ++j) inner += lines[std::size_t(j) * n].head<2>().norm() < 0.5 * std::sqrt(0.5);
  CHECK(inner == kWispTubeLines / 2);
  const double fibres = 30.0;
  DensityAccumulator accumulator(make_grid_geometry(Vec3(-2, -2, -1), Vec3(2, 2, 11), 0.25));
  std::vector<FibreSpan> spans;
  for (int j = 0; j < kWispTubeLines; ++j)
    spans.push_back({lines.data() + std::size_t(j) * n, std::size_t(n), fibres / kWispTubeLines});
  accumulator.add_fibres(spans, 1);
  const DensityGrid grid = accumulator.freeze();
  double total = 0.0;
  for (double v : grid.values()) total += v;
  CHECK(total * grid.geometry().cell_diagonal() == doctest::Approx(fibres * 10.0).epsilon(1e-12));
}
