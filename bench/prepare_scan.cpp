// `hairfit prepare` on the sculpted busts (lib/prepare/sculpted_bust.h) at the size of a real scan:
// the time of prepare_scan (weld, cut, scalp, checks; no file writing) by wall clock and by CPU
// over all threads, the method the scalp took, how smooth the scalp is under the hair (its mean
// curvature), and what the checks found. The plain and tilted
// busts are also prepared both ways (radial and level set), the two designs side by side.
//   cmake -S . -B build -DHAIRFIT_BENCH=ON && cmake --build build --target bench_prepare_scan
//   build/bench/bench_prepare_scan [spacing_cm = 0.23 (about 270 000 triangles)] [threads = 0: all] [bust: all]
//                                  [runs = 1] [folder: also write each bust's scan there, OBJ with colours]
// With several runs the times are their medians (this host's wall times vary by ±25 % from run
// to run), and the other columns come from the last run (every run gives the same result).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/obj_mesh.h"
#include "prepare/prepare.h"
#include "prepare/sculpted_bust.h"

using namespace hairfit;

namespace {

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x.size() % 2 ? x[x.size() / 2] : 0.5 * (x[x.size() / 2 - 1] + x[x.size() / 2]);
}

void run(BustStyle style, const BustScan& scan, const std::string& method, int threads, int runs) {
  PrepareOptions o;
  o.selection.kind = HairSelection::Kind::mask;
  o.selection.color = Vec3(kHairColor[0], kHairColor[1], kHairColor[2]);
  o.scalp_method = method;
  o.threads = threads;
  std::vector<double> walls, cpus;
  std::string outcome;
  Prepared p;
  for (int k = 0; k < runs; ++k) {
    const auto wall0 = std::chrono::steady_clock::now();
    const double cpu0 = cpu_seconds();
    try {
      p = prepare_scan(scan.mesh, scan.colors, o, bust_style_name(style));
      outcome = "passed";
    } catch (const InputError& e) {
      outcome = std::string("refused: ") + e.what();
      if (outcome.size() > 90) outcome = outcome.substr(0, 90) + "…";
    }
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    cpus.push_back(cpu_seconds() - cpu0);
  }
  const double wall = median(walls), cpu = median(cpus);
  std::printf("| %s | %zu | %s | %s | %.2f | %.2f | %zu | %zu | %.3f / %.3f | %s |\n", bust_style_name(style).c_str(),
              scan.mesh.triangles.size(), method.c_str(), p.scalp.method.empty() ? "–" : p.scalp.method.c_str(), wall, cpu,
              p.hull.mesh.triangles.size(), p.scalp.scalp.triangles.size(), p.checks.curvature_p95, p.checks.curvature_max,
              outcome.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const double spacing = argc > 1 ? std::atof(argv[1]) : 0.23;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 0;
  const std::string only = argc > 3 && std::string(argv[3]) != "all" ? argv[3] : "";
  const int runs = argc > 4 ? std::max(1, std::atoi(argv[4])) : 1;
  const std::string folder = argc > 5 ? argv[5] : "";
  std::printf("| bust | scan triangles | --scalp | made by | wall s | CPU s | hull triangles | scalp triangles | scalp |H| p95 / max (1/cm) | checks |\n");
  std::printf("| --- | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | --- |\n");
  for (BustStyle style : all_bust_styles()) {
    if (!only.empty() && bust_style_name(style) != only) continue;
    const BustScan scan = make_sculpted_bust(style, spacing);
    if (!folder.empty()) write_obj_mesh(folder + "/" + bust_style_name(style) + ".obj", scan.mesh, {}, scan.colors);
    run(style, scan, "auto", threads, runs);
    if (style == BustStyle::plain || style == BustStyle::tilted) {
      run(style, scan, "radial", threads, runs);
      run(style, scan, "level-set", threads, runs);
    }
  }
  return 0;
}
