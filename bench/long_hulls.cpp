// Hair from the hull (issue 47) at default hair keys: every long or shell hull the project has,
// each with only the two meshes, the directions, 600 guides and 50 hairs/cm² (a user's first
// scene), one cold `hairfit run` each; then the straight hull again with effects.gravity, for the
// cost of weight. Prints the measures as Markdown, one row per hull.
//   bench_long_hulls [--threads T] [--hairfit PATH] [--scratch DIR]
// Coverage is the strands stage's own (the hull's area within 0.75 cm of a strand point, on
// 20 000 area-weighted samples); docs/results/long-hair.md checks it independently.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runs.h"

using namespace hairfit::bench;

namespace {

struct Hull {
  std::string name, scalp, volume, units;
};

// The scene a new user writes: the two meshes and the directions; nothing about the hair.
void write_default_scene(const Hull& h, bool gravity, const fs::path& out) {
  std::ofstream s(out);
  s << "format = \"hairfit-scene/1\"\nseed = 1\n[units]\nlength = \"" << h.units
    << "\"\ndown = [0, -1, 0]\nfront = [0, 0, 1]\n[inputs]\nscalp = \"" << h.scalp << "\"\nvolume = \"" << h.volume
    << "\"\n[hair]\ndensity = 50\n[roots]\nguides = 600\n";
  if (gravity) s << "[effects]\ngravity = true\n";
}

}  // namespace

int main(int argc, char** argv) {
  RunSettings run{1, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-long-hulls"};
  for (int i = 1; i < argc; ++i) {
    if (parse_run_option(argc, argv, i, run)) continue;
    std::fprintf(stderr, "usage: bench_long_hulls [--threads T] [--hairfit PATH] [--scratch DIR]\n");
    return 2;
  }
  const std::string fixtures = std::string(HAIRFIT_SOURCE_DIR) + "/fixtures/";
  const std::string makehuman = std::string(HAIRFIT_SOURCE_DIR) + "/../shared/data/makehuman/";
  std::vector<Hull> hulls = {
      {"straight (closed, to the shoulders)", fixtures + "meshes/scalp.obj", fixtures + "meshes/straight_volume.obj", "cm"}};
  for (const char* name : {"short04_full", "short01_full", "bob01_full", "braid01_full", "ponytail01_full", "ponytail01_shell"}) {
    // The shipped fixtures' copies where there are some; the rest from ../shared.
    const std::string shipped = fixtures + "makehuman/hair_" + name + ".obj";
    hulls.push_back({name, fixtures + "makehuman/scalp.obj",
                     fs::exists(shipped) ? shipped : makehuman + "hair_" + name + ".obj", "dm"});
  }
  std::printf("# Long hulls at default hair keys\n\nhairfit: %s\nsource at: %s\n--threads %d; load average before: %s\n\n",
              run.hairfit.c_str(), source_commit().c_str(), run.threads, load_average().c_str());
  std::printf("| hull | hanging | mean length cm | coverage | guides inside | strands inside | pre-guides at depth "
              "| evaluations / guide | guides ending outside | flow crossing | guide CPU s |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  double weightless_cpu = 0.0;
  try {
    for (std::size_t k = 0; k <= hulls.size(); ++k) {
      const bool gravity = k == hulls.size();
      const Hull& h = gravity ? hulls[0] : hulls[k];
      if (!fs::exists(h.volume)) {
        std::printf("| %s | missing: %s | | | | | | | | | |\n", h.name.c_str(), h.volume.c_str());
        continue;
      }
      const std::string tag = "hull-" + std::to_string(k);
      const fs::path scene = run.scratch / (tag + ".toml");
      fs::create_directories(run.scratch);
      write_default_scene(h, gravity, scene);
      const RunRecord r = run_hairfit(run.hairfit, scene, run.scratch / tag, run.threads);
      const double cpu = r.stage("guides") ? r.stage("guides")->cpu_seconds : 0.0;
      if (k == 0) weightless_cpu = cpu;
      std::printf("| %s%s | %.2f | %.1f | %.3f | %.4f | %.4f | %.2f | %.1f | %.0f | %.3f | %.2f |\n", h.name.c_str(),
                  gravity ? ", gravity" : "", r.figure("roots", "hang_weight_mean"),
                  r.figure("roots", "hair_length_mean_cm"), r.figure("strands", "coverage"),
                  r.figure("guides", "inside_fraction"), r.figure("strands", "inside_fraction"),
                  r.figure("preguides", "reached_depth") / r.figure("preguides", "preguides"),
                  r.figure("guides", "mean_evaluations"), r.figure("guides", "guides_ending_outside"),
                  r.figure("guides", "flow_crossing"), cpu);
      if (gravity && weightless_cpu > 0.0)
        std::printf("\nguide stage with gravity / weightless on the straight hull: %.1f×\n", cpu / weightless_cpu);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_long_hulls: %s\n", e.what());
    return 1;
  }
  std::printf("\ntarget: coverage ≥ 0.90, guides and strands inside ≥ 0.99, pre-guides at depth ≥ 0.90, "
              "≤ 30 evaluations a guide, gravity ≤ 3× weightless\nload average after: %s\n", load_average().c_str());
  return 0;
}
