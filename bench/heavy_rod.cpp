// Accuracy against time for heavy rods (issue: long hair): the planar heavy cantilever of weight
// w = ρAgL³/EI from 100 to 1e4 (40 cm of real hair is ≈ 1800) solved by multiple shooting at
// 32 … 512 segments, its tip against the Chebyshev collocation reference of the tests
// (tests/rod/heavy_references.h), and the CPU time of one solve from rest (load continuation)
// and of one re-solve warm-started from a solution at a 1 % different load, as the guide
// optimiser does it. Also a rod resting on a support (contact), against its own 1024-segment
// solution. Prints a Markdown table.
//   cmake -S . -B build -DHAIRFIT_BENCH=ON && cmake --build build --target bench_heavy_rod
//   build/bench/bench_heavy_rod
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>

#include "rod/rod_shooting.h"
#include "tests/rod/heavy_references.h"
#include "tests/rod/ramp_plane.h"

using namespace hairfit;

namespace {

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

RodModel cantilever(double weight) {
  RodModel model;
  model.root_frame.col(0) = Vec3(0.0, 1.0, 0.0);
  model.root_frame.col(1) = Vec3(0.0, 0.0, 1.0);
  model.root_frame.col(2) = Vec3(1.0, 0.0, 0.0);
  model.force_per_length = Vec3(0.0, -weight, 0.0);
  return model;
}

Vec3 tip_of(const RodModel& model, const ShootingOptions& options, const ShootingResult& s) {
  std::vector<double> nodes(3 * (options.segments + 1));
  trace_pieces(model, options.integrator, options.segments, s, RodTrace<double>{nodes.data(), nullptr, nullptr, nullptr});
  return Eigen::Map<const Vec3>(&nodes[3 * options.segments]);
}

// Per solve: from rest, and warm-started at a 1 % larger terminal force, averaged over `repeat`.
struct Timing {
  double from_rest = 0.0, warm = 0.0;
  int pieces = 0;
  Vec3 tip = Vec3::Zero();
};

Timing time_solves(const RodModel& model, int segments, const Vec3& force) {
  ShootingOptions options;
  options.segments = segments;
  options.max_iterations = 2000;
  Timing t;
  const int repeat = 5;
  ShootingResult s;
  double start = cpu_seconds();
  for (int r = 0; r < repeat; ++r) s = shoot_root_moment(model, force, Vec3::Zero(), Vec3::Zero(), options);
  t.from_rest = (cpu_seconds() - start) / repeat;
  t.pieces = static_cast<int>(s.breaks.size()) - 1;
  t.tip = tip_of(model, options, s);
  ShootingOptions warm = options;
  warm.restart_from_rest = false;
  start = cpu_seconds();
  for (int r = 0; r < repeat; ++r) shoot_root_moment(model, 1.01 * force + Vec3(0.0, 0.0, 0.01), Vec3::Zero(), s, warm);
  t.warm = (cpu_seconds() - start) / repeat;
  return t;
}

}  // namespace

int main() {
  std::printf("| w | segments | pieces | tip error (L) | CPU per solve from rest (ms) | CPU per warm re-solve (ms) |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  for (double w : {100.0, 1000.0, 1800.0, 10000.0}) {
    const test::HeavyTip reference = test::heavy_cantilever_reference(w);
    for (int segments : {32, 64, 128, 256, 512}) {
      const Timing t = time_solves(cantilever(w), segments, Vec3(0.0, 0.0, 1.0));
      // The reference has no terminal force; the timed solves carry a small one (0, 0, 1) so the
      // warm re-solve has a load to move. The error is measured without it.
      ShootingOptions options;
      options.segments = segments;
      options.max_iterations = 2000;
      const ShootingResult plain = shoot_root_moment(cantilever(w), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), options);
      const Vec3 tip = tip_of(cantilever(w), options, plain);
      const double error = std::hypot(tip.x() - reference.x, tip.y() - reference.y);
      std::printf("| %g | %d | %d | %.2e | %.2f | %.3f |\n", w, segments, t.pieces, error, 1e3 * t.from_rest,
                  1e3 * t.warm);
    }
  }
  std::printf("\nOn a support (w = 1800, k = 4e5 at its 1/20 layer, from 0.3 rad above level; error against 1024 segments):\n\n");
  std::printf("| segments | pieces | tip error (L) | CPU per solve from rest (ms) | CPU per warm re-solve (ms) |\n");
  std::printf("| --- | --- | --- | --- | --- |\n");
  RodModel supported = cantilever(1800.0);
  supported.root_frame = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix() * supported.root_frame;
  supported.support = std::make_shared<test::RampPlane>(-0.05, 4e5, 0.05);
  const Vec3 reference = time_solves(supported, 1024, Vec3(0.0, 0.0, 1.0)).tip;
  for (int segments : {32, 64, 128, 256, 512}) {
    const Timing t = time_solves(supported, segments, Vec3(0.0, 0.0, 1.0));
    std::printf("| %d | %d | %.2e | %.2f | %.3f |\n", segments, t.pieces, (t.tip - reference).norm(), 1e3 * t.from_rest,
                1e3 * t.warm);
  }
  return 0;
}
