// Heavy rods (w = ρAgL³/EI up to 1e4) against independent answers: the planar heavy cantilever by
// Chebyshev collocation (heavy_references.h), its small-w limit (the linear beam) and its large-w
// limit (the hanging chain with its root boundary layer), and the observed convergence order.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "rod/rod.h"
#include "heavy_references.h"

using namespace hairfit;

namespace {

// A unit rod (L = 1, EI = 1) clamped horizontally along x, loaded by its weight w along −y.
SolvedRod heavy_cantilever(double weight, int segments, RodIntegrator integrator = RodIntegrator::rk4) {
  Rod rod;
  rod.length = 1.0;
  rod.stiffness = Vec3(1.0, 1.0, 1.0);
  rod.force_per_length = Vec3(0.0, -weight, 0.0);
  RodRoot root;
  root.frame.col(0) = Vec3(0.0, 1.0, 0.0);
  root.frame.col(1) = Vec3(0.0, 0.0, 1.0);
  root.frame.col(2) = Vec3(1.0, 0.0, 0.0);
  RodOptions options;
  options.segments = segments;
  options.integrator = integrator;
  options.tolerance = 1e-12;
  options.max_iterations = 2000;
  return solve_rod(rod, root, RodLoad{}, options);
}

}  // namespace

TEST_CASE("the collocation reference reproduces the linear beam and the chain's boundary layer") {
  // Linear beam: tip deflection qL⁴/(8EI), with a relative correction of order w².
  const test::HeavyTip light = test::heavy_cantilever_reference(1e-3);
  CHECK(light.y == doctest::Approx(-1e-3 / 8.0).epsilon(1e-5));
  // Hanging chain: beyond a layer of length ~ 1/√w the rod hangs straight down; the layer's
  // elastica tan(ψ/4) = tan(π/8)·exp(−√w·s) gives x → √2/√w and a drop short of L by (2 − √2)/√w.
  const double w = 1e4;
  const test::HeavyTip heavy = test::heavy_cantilever_reference(w);
  CHECK(heavy.x * std::sqrt(w) == doctest::Approx(std::sqrt(2.0)).epsilon(0.03));
  CHECK((1.0 + heavy.y) * std::sqrt(w) == doctest::Approx(2.0 - std::sqrt(2.0)).epsilon(0.05));
  // The reference converges spectrally: doubling its points moves the tip by < 1e-10.
  const test::HeavyTip finer = test::heavy_cantilever_reference(w, 96);
  CHECK(std::hypot(finer.x - heavy.x, finer.y - heavy.y) < 1e-10);
}

TEST_CASE("heavy cantilevers up to w = 1e4 match the collocation reference to 1e-6 L at 512 segments") {
  for (double w : {1.0, 1e2, 1e3, 1800.0, 1e4}) {
    CAPTURE(w);
    const test::HeavyTip reference = test::heavy_cantilever_reference(w);
    const SolvedRod fine = heavy_cantilever(w, 512);
    REQUIRE(fine.converged);
    const double error = std::hypot(fine.tip().x() - reference.x, fine.tip().y() - reference.y);
    // The defaults (64 segments) stay within 1e-3 L.
    const SolvedRod coarse = heavy_cantilever(w, 64);
    REQUIRE(coarse.converged);
    const double coarse_error = std::hypot(coarse.tip().x() - reference.x, coarse.tip().y() - reference.y);
    MESSAGE("w ", w, ": tip error ", error, " L at 512 segments, ", coarse_error, " L at 64");
    CHECK(error <= 1e-6);
    CHECK(coarse_error <= 1e-3);
    for (const Vec3& p : coarse.nodes) CHECK(p.allFinite());
  }
}

TEST_CASE("small weights give the linear beam, large weights the hanging chain") {
  const SolvedRod light = heavy_cantilever(1e-3, 64);
  CHECK(light.tip().y() == doctest::Approx(-1e-3 / 8.0).epsilon(1e-5));
  const double w = 1e4;
  const SolvedRod heavy = heavy_cantilever(w, 512);
  CHECK(heavy.tip().x() * std::sqrt(w) == doctest::Approx(std::sqrt(2.0)).epsilon(0.03));
  // Below the layer the rod hangs straight down: the tangent at s = 0.2 (20 layer lengths) is −y.
  CHECK(heavy.frames[512 / 5].col(2).y() < -0.9999);
}

TEST_CASE("the heavy cantilever converges at each integrator's order") {
  const double w = 1e3;
  const test::HeavyTip reference = test::heavy_cantilever_reference(w);
  for (RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
    CAPTURE(rod_integrator_name(integrator));
    double errors[3];
    for (int k = 0; k < 3; ++k) {
      const SolvedRod rod = heavy_cantilever(w, 128 << k, integrator);
      errors[k] = std::hypot(rod.tip().x() - reference.x, rod.tip().y() - reference.y);
    }
    const double order = rod_integrator_order(integrator);
    MESSAGE("errors ", errors[0], " ", errors[1], " ", errors[2]);
    for (int k = 0; k < 2; ++k) CHECK(std::log2(errors[k] / errors[k + 1]) == doctest::Approx(order).epsilon(0.15));
  }
}
