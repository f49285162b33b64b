// The paper's scale end to end (issue 11): `hairfit run` of fixtures/paper-scale (3000 guides,
// 90 000 fibres, CDM) and fixtures/full-head (6000 guides, 150 000 fibres), each cold (--no-cache)
// N times in a child process. Prints, as Markdown, the median wall time per stage and in total,
// the CPU time (user + system), the cost evaluations per guide, the peak memory and the ratio to
// the paper's 90 s (Pentium IV, Sobottka et al. §4).
//   bench_paper_scale [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [SCENE ...]
// The machine is shared: CPU time is the steadier figure, wall time depends on the others' load
// (printed with the load average before and after).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli_runs.h"

using namespace hairfit::bench;

namespace {

constexpr double kPaperSeconds = 90.0;  // Sobottka et al. §4: 3000 guides, ~90 000 fibres, Pentium IV

void report_scene(const std::string& hairfit, const fs::path& scene, const fs::path& scratch, int runs, int threads) {
  std::printf("\n## %s\n\nload average before: %s\n\n", scene.string().c_str(), load_average().c_str());
  std::fflush(stdout);
  std::vector<RunRecord> records;
  for (int r = 0; r < runs; ++r) {
    records.push_back(run_hairfit(hairfit, scene, scratch / ("run" + std::to_string(r)), threads));
    std::fprintf(stderr, "  run %d/%d: %.2f s wall, %.2f s CPU\n", r + 1, runs, records.back().usage.wall,
                 records.back().usage.cpu());
  }
  const RunRecord& first = records.front();
  std::printf("%d runs, --threads %d; fibres %.0f, guides %.0f, effects as the scene declares\n\n", runs, threads,
              first.figure("strands", "fibres"), first.figure("guides", "guides"));
  // Cores busy: the stage's CPU time over its wall time, per run; of `threads`, how many worked.
  std::printf("| stage | median s | min s | max s | median CPU s | cores busy | peak memory MiB (max) |\n"
              "|---|---:|---:|---:|---:|---:|---:|\n");
  for (const StageRun& s : first.stages) {
    std::vector<double> seconds, cpu, busy;
    std::uint64_t peak = 0;
    for (const RunRecord& r : records) {
      const StageRun& run = *r.stage(s.name);
      seconds.push_back(run.seconds);
      cpu.push_back(run.cpu_seconds);
      busy.push_back(run.seconds > 0 ? run.cpu_seconds / run.seconds : 0.0);
      peak = std::max(peak, run.peak_memory_bytes);
    }
    std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %.0f |\n", s.name.c_str(), median(seconds),
                *std::min_element(seconds.begin(), seconds.end()), *std::max_element(seconds.begin(), seconds.end()),
                median(cpu), median(busy), mib(peak));
  }
  std::vector<double> wall, cpu, user, stage_sum, evaluations, iterations;
  std::uint64_t rss = 0;
  for (const RunRecord& r : records) {
    wall.push_back(r.usage.wall);
    cpu.push_back(r.usage.cpu());
    user.push_back(r.usage.user);
    double sum = 0.0;
    for (const StageRun& s : r.stages) sum += s.seconds;
    stage_sum.push_back(sum);
    evaluations.push_back(r.figure("guides", "mean_evaluations"));
    iterations.push_back(r.figure("guides", "mean_iterations"));
    rss = std::max(rss, r.usage.max_rss_bytes);
  }
  std::printf("\n| figure | median | min | max |\n|---|---:|---:|---:|\n");
  auto row = [](const char* name, const std::vector<double>& v, const char* format) {
    std::printf("| %s | ", name);
    std::printf(format, median(v));
    std::printf(" | ");
    std::printf(format, *std::min_element(v.begin(), v.end()));
    std::printf(" | ");
    std::printf(format, *std::max_element(v.begin(), v.end()));
    std::printf(" |\n");
  };
  row("process wall s (loaded machine)", wall, "%.2f");
  row("sum of stage s", stage_sum, "%.2f");
  row("process CPU s (user + system)", cpu, "%.2f");
  row("process user CPU s", user, "%.2f");
  row("cost evaluations per guide", evaluations, "%.1f");
  row("solver iterations per guide", iterations, "%.1f");
  std::uint64_t stage_peak = 0;
  for (const RunRecord& r : records)
    for (const StageRun& s : r.stages) stage_peak = std::max(stage_peak, s.peak_memory_bytes);
  std::printf("\npeak resident memory: process %.0f MiB (wait4), largest stage %.0f MiB (report.json)\n", mib(rss),
              mib(stage_peak));
  std::printf("paper's 90 s (one Pentium IV core) / median wall: %.1f×; / median CPU: %.1f×\n",
              kPaperSeconds / median(wall), kPaperSeconds / median(cpu));
  std::printf("load average after: %s\n", load_average().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  RunSettings run{5, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-paper-scale"};
  std::vector<fs::path> scenes;
  for (int i = 1; i < argc; ++i) {
    if (parse_run_option(argc, argv, i, run)) continue;
    if (std::string(argv[i]).rfind("--", 0) == 0) {
      std::fprintf(stderr, "usage: bench_paper_scale [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [SCENE ...]\n");
      return 2;
    }
    scenes.emplace_back(argv[i]);
  }
  if (run.runs < 1 || run.threads < 1) {
    std::fprintf(stderr, "bench_paper_scale: --runs and --threads must be ≥ 1\n");
    return 2;
  }
  if (scenes.empty())
    scenes = {fs::path(HAIRFIT_SOURCE_DIR) / "fixtures/paper-scale/scene.toml",
              fs::path(HAIRFIT_SOURCE_DIR) / "fixtures/full-head/scene.toml"};
  std::printf("# Paper scale end to end\n\nhairfit: %s\nsource at: %s\n", run.hairfit.c_str(), source_commit().c_str());
  try {
    for (const fs::path& scene : scenes) report_scene(run.hairfit, scene, run.scratch / scene.parent_path().filename(), run.runs, run.threads);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_paper_scale: %s\n", e.what());
    return 1;
  }
  return 0;
}
