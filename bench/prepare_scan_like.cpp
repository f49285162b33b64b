// `hairfit prepare` on the scan-like busts (lib/prepare/scan_like.h: far from the origin, coarse,
// tilted 30°, dressed, noisy): each written as an OBJ scan with its hair painted, prepared by the
// real command (reading the file, run's own checks on what it writes) and, with `run`, run at the
// scene's default keys; prints a table of what prepare did and, for the runs, report.json's
// strand figures.
//   cmake -S . -B build -DHAIRFIT_BENCH=ON && cmake --build build --target bench_prepare_scan_like hairfit
//   build/bench/bench_prepare_scan_like FOLDER [spacing_cm = 0.5] [case: all] [run]
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/cli_runs.h"
#include "io/obj_mesh.h"
#include "prepare/scan_like.h"

using namespace hairfit;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_prepare_scan_like FOLDER [spacing_cm = 0.5] [case: all] [run]\n");
    return 2;
  }
  const fs::path folder = argv[1];
  const double spacing = argc > 2 ? std::atof(argv[2]) : 0.5;
  const std::string only = argc > 3 && std::string(argv[3]) != "all" ? argv[3] : "";
  const bool run = argc > 4 && std::string(argv[4]) == "run";
  fs::create_directories(folder);
  std::printf("| case | scan triangles | prepare exit | CPU s | scalp | refined | run exit | CPU s | inside_fraction | scalp_crossings |\n");
  std::printf("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |\n");
  for (const ScanLikeCase& c : scan_like_cases(spacing)) {
    if (!only.empty() && c.name != only) continue;
    const BustScan scan = make_scan_like(c);
    const fs::path obj = folder / (c.name + ".obj"), out = folder / c.name;
    write_obj_mesh(obj, scan.mesh, {}, scan.colors);
    const bench::ProcessUsage prepared = bench::run_process(
        {HAIRFIT_BINARY, "prepare", obj.string(), "--out", out.string(), "--mask", "0.3,0.18,0.1", "--threads", "2"},
        folder / (c.name + "-prepare.log"));
    std::string method = "–", refined = "–";
    if (prepared.exit_code == 0) {
      const nlohmann::json record = nlohmann::json::parse(std::ifstream(out / "prepare.json"));
      method = record["scalp"]["method"].get<std::string>();
      refined = std::to_string(record["refined"]["splits"].get<int>());
    }
    std::string run_exit = "–", run_cpu = "–", inside = "–", crossings = "–";
    if (run && prepared.exit_code == 0) {
      const bench::ProcessUsage r = bench::run_process({HAIRFIT_BINARY, "run", (out / "scene.toml").string(), "--out",
                                                        (out / "run").string(), "--threads", "2", "--no-cache", "--quiet"},
                                                       folder / (c.name + "-run.log"));
      run_exit = std::to_string(r.exit_code);
      char text[32];
      std::snprintf(text, sizeof text, "%.1f", r.cpu());
      run_cpu = text;
      if (r.exit_code == 0) {
        const nlohmann::json report = nlohmann::json::parse(std::ifstream(out / "run" / "report.json"));
        const nlohmann::json& strands = report["stages"]["strands"];
        std::snprintf(text, sizeof text, "%.4f", strands["inside_fraction"].get<double>());
        inside = text;
        crossings = std::to_string(strands["scalp_crossings"].get<long long>());
      }
    }
    std::printf("| %s | %zu | %d | %.1f | %s | %s | %s | %s | %s | %s |\n", c.name.c_str(), scan.mesh.triangles.size(),
                prepared.exit_code, prepared.cpu(), method.c_str(), refined.c_str(), run_exit.c_str(), run_cpu.c_str(),
                inside.c_str(), crossings.c_str());
    std::fflush(stdout);
  }
  return 0;
}
