// What rod accuracy costs: integrator × segments → tip error against the exact references
// (elliptic-integral cantilever, exact helix), µs per forward integration in double, µs per jet
// evaluation (Jet<double, 6>: the guides' six load parameters), µs per shooting solve.
// Writes bench/results/rod.csv and bench/results/rod.png (error against time, log–log) and prints
// the table as Markdown.  Usage: bench_rod [OUT_DIR]   (default: <source>/bench/results)
//
// Profiling driver: bench_rod --calls double|jet6 rk2|rk4 SEGMENTS CALLS runs only CALLS forward
// integrations of the timed workload inside run_calls (no timing, no files), for
//   valgrind --tool=callgrind --toggle-collect='*run_calls*' ./bench_rod --calls jet6 rk4 64 100
// whose instruction count ÷ CALLS is reproducible on a loaded machine, unlike wall time.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "io/atomic_file.h"
#include "io/png_image.h"
#include "render/plot.h"
#include "rod/rod.h"
#include "rod/rod_jet.h"
#include "tests/rod/rod_references.h"

using namespace hairfit;

namespace {

// Median over 5 runs of the time per call, each run repeating `body` for at least ~20 ms.
template <typename Body>
double microseconds_per_call(Body body) {
  using Clock = std::chrono::steady_clock;
  int repeats = 1;
  for (;;) {
    const auto start = Clock::now();
    for (int i = 0; i < repeats; ++i) body();
    if (Clock::now() - start > std::chrono::milliseconds(20)) break;
    repeats *= 2;
  }
  std::vector<double> runs;
  for (int run = 0; run < 5; ++run) {
    const auto start = Clock::now();
    for (int i = 0; i < repeats; ++i) body();
    runs.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count() / repeats);
  }
  std::sort(runs.begin(), runs.end());
  return runs[2];
}

struct Row {
  const char* integrator;
  int segments;
  double cantilever_error;  // |tip − elliptic| / L, P·L²/EI = 5, shooting
  double helix_error;       // |tip − exact| / L + max |R − R_exact|, oblique couple, 2 turns
  double forward_us;        // one forward integration, double, nodes + frames written
  double jet_us;            // the same with Jet<double, 6>
  double shooting_us;       // one cold shooting solve of the cantilever
  int shooting_iterations;
};

volatile double sink = 0.0;  // keeps the timed work observable

// The forward-integration workload: a loaded, anisotropic rod with gravity (GJ/EI = 0.46).
RodModel workload_model() {
  RodModel model;
  model.compliance = Vec3(1.0, 0.8, 1.0 / 0.46);
  model.force_per_length = Vec3(0.0, 0.0, -3.0);
  return model;
}
const double kEta[6] = {2.0, -1.0, 0.5, 0.3, 1.2, -0.4};  // η̃ = (f_L, m(0)), dimensionless

// `calls` forward integrations writing nodes and frames; not inlined so callgrind can count it.
template <typename T>
__attribute__((noinline)) void run_calls(const RodModel& model, RodIntegrator integrator, int segments, int calls) {
  std::vector<T> nodes(3 * (segments + 1)), frames(9 * (segments + 1));
  T eta[6], end[3];
  for (int i = 0; i < 6; ++i) eta[i] = T(kEta[i]);
  if constexpr (!std::is_same_v<T, double>)
    for (int i = 0; i < 6; ++i) eta[i].v[i] = 1.0;
  for (int c = 0; c < calls; ++c) {
    integrate_rod<T>(model, integrator, segments, eta, eta + 3, end,
                     RodTrace<T>{nodes.data(), frames.data(), nullptr, nullptr});
    if constexpr (std::is_same_v<T, double>)
      sink = sink + end[0];
    else
      sink = sink + end[0].a + end[0].v[5];
  }
}

int profile_main(int argc, char** argv) {
  if (argc != 6 || (std::strcmp(argv[2], "double") != 0 && std::strcmp(argv[2], "jet6") != 0)) {
    std::fprintf(stderr, "usage: bench_rod --calls double|jet6 rk2|rk4 SEGMENTS CALLS\n");
    return 2;
  }
  const RodIntegrator integrator = parse_rod_integrator(argv[3]);
  const int segments = std::atoi(argv[4]), calls = std::atoi(argv[5]);
  if (segments < 1 || calls < 1) {
    std::fprintf(stderr, "SEGMENTS and CALLS must be positive\n");
    return 2;
  }
  if (std::strcmp(argv[2], "double") == 0)
    run_calls<double>(workload_model(), integrator, segments, calls);
  else
    run_calls<RodJet6>(workload_model(), integrator, segments, calls);
  std::printf("%s %s %d segments: %d calls, checksum %.17g\n", argv[2], argv[3], segments, calls, sink);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--calls") == 0) return profile_main(argc, argv);
  const std::filesystem::path out_dir =
      argc > 1 ? std::filesystem::path(argv[1]) : std::filesystem::path(HAIRFIT_SOURCE_DIR) / "bench" / "results";
  const double alpha = 5.0;
  const test::CantileverTip elliptic = test::cantilever_tip(alpha, true);
  const Vec3 couple = Vec3(1.0, 0.5, 1.0).normalized() * (2.0 * 2.0 * test::kPi);  // 2 turns, EI = 1
  const double gj = 0.46;
  const test::HelixState helix = test::exact_helix(couple, 1.0, gj, Mat3::Identity(), 1.0);

  const RodModel model = workload_model();
  const double* eta = kEta;

  std::vector<Row> rows;
  for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4})
    for (int segments = 8; segments <= 512; segments *= 2) {
      Row row{rod_integrator_name(integrator), segments, 0, 0, 0, 0, 0, 0};
      RodOptions options;
      options.integrator = integrator;
      options.segments = segments;
      options.tolerance = 1e-13;
      RodLoad load;
      load.terminal_force = Vec3(alpha, 0.0, 0.0);
      const SolvedRod cantilever = solve_rod(Rod{}, RodRoot{}, load, options);
      row.cantilever_error = (cantilever.tip() - Vec3(elliptic.x, 0.0, elliptic.z)).norm();
      row.shooting_iterations = cantilever.iterations;

      Rod twisted;
      twisted.stiffness = Vec3(1.0, 1.0, gj);
      RodLoad pure;
      pure.root_moment = couple;
      RodOptions forward = options;
      forward.solver = RodSolver::initial_value;
      const SolvedRod h = solve_rod(twisted, RodRoot{}, pure, forward);
      row.helix_error = (h.tip() - helix.position).norm() + (h.tip_frame() - helix.frame).cwiseAbs().maxCoeff();

      std::vector<double> nodes(3 * (segments + 1)), frames(9 * (segments + 1));
      double end[3];
      row.forward_us = microseconds_per_call([&] {
        integrate_rod<double>(model, integrator, segments, eta, eta + 3, end,
                              RodTrace<double>{nodes.data(), frames.data(), nullptr, nullptr});
        sink = sink + end[0];
      });
      std::vector<RodJet6> jet_nodes(3 * (segments + 1)), jet_frames(9 * (segments + 1));
      RodJet6 parameters[6], jet_end[3];
      for (int i = 0; i < 6; ++i) parameters[i] = RodJet6(eta[i], i);
      row.jet_us = microseconds_per_call([&] {
        integrate_rod<RodJet6>(model, integrator, segments, parameters, parameters + 3, jet_end,
                               RodTrace<RodJet6>{jet_nodes.data(), jet_frames.data(), nullptr, nullptr});
        sink = sink + jet_end[0].a;
      });
      row.shooting_us = microseconds_per_call([&] { sink = sink + solve_rod(Rod{}, RodRoot{}, load, options).tip().x(); });
      rows.push_back(row);
    }

  std::string csv =
      "integrator,segments,cantilever_tip_error,helix_error,forward_us,jet6_us,shooting_us,shooting_iterations\n";
  std::printf("| integrator | segments | cantilever tip error / L | helix error | forward µs (double) | "
              "forward µs (Jet6) | shooting µs (iterations) |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%d,%.3e,%.3e,%.3f,%.3f,%.2f,%d\n", r.integrator, r.segments,
                  r.cantilever_error, r.helix_error, r.forward_us, r.jet_us, r.shooting_us, r.shooting_iterations);
    csv += line;
    std::printf("| %s | %d | %.2e | %.2e | %.2f | %.2f | %.1f (%d) |\n", r.integrator, r.segments, r.cantilever_error,
                r.helix_error, r.forward_us, r.jet_us, r.shooting_us, r.shooting_iterations);
  }
  write_text_file_atomically(out_dir / "rod.csv", csv);

  LinePlot plot;
  plot.title = "Rod: tip error vs time, 8 to 512 segments";
  plot.x_label = "microseconds per forward integration (double)";
  plot.y_label = "tip error / L";
  plot.log_x = plot.log_y = true;
  int colour = 0;
  for (const char* integrator : {"rk2", "rk4"})
    for (const bool cantilever : {true, false}) {
      Series s;
      s.name = std::string(integrator) + (cantilever ? ", cantilever PL^2/EI = 5" : ", helix 2 turns (tip + frame)");
      s.color_id = colour++;
      for (const Row& r : rows) {
        if (std::string(r.integrator) != integrator) continue;
        s.x.push_back(r.forward_us);
        s.y.push_back(cantilever ? r.cantilever_error : r.helix_error);
      }
      plot.series.push_back(s);
    }
  write_png(out_dir / "rod.png", render_line_plot(plot, 900, 560));
  std::printf("\nwrote %s and %s\n", (out_dir / "rod.csv").string().c_str(), (out_dir / "rod.png").string().c_str());
  return 0;
}
