// The paper's scale end to end (issue 11): `hairfit run` of fixtures/paper-scale (3000 guides,
// 90 000 fibres, CDM) and fixtures/full-head (6000 guides, 150 000 fibres), each cold (--no-cache)
// N times in a child process. Prints, as Markdown, the median wall time per stage and in total,
// the CPU time (user + system), the cost evaluations per guide, the peak memory and the ratio to
// the paper's 90 s (Pentium IV, Sobottka et al. §4).
//   bench_paper_scale [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [--against PATH] [SCENE ...]
// The machine is shared: CPU time is the steadier figure, wall time depends on the others' load
// (printed with the load average before and after).
// --against OTHER compares two builds in one run instead: OTHER and --hairfit alternate in ABBA
// order (on this machine the second of two back-to-back runs tends to be the faster one, so
// each build takes each place equally often), and the medians and their ratios are printed.
#include <array>
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

// Medians of one build's runs: process wall and CPU, and each stage's wall and CPU seconds.
struct Medians {
  double wall = 0.0, cpu = 0.0;
  std::vector<std::pair<std::string, std::array<double, 2>>> stages;  // (name, {wall, cpu})
};

Medians medians_of(const std::vector<RunRecord>& records) {
  Medians m;
  std::vector<double> wall, cpu;
  for (const RunRecord& r : records) {
    wall.push_back(r.usage.wall);
    cpu.push_back(r.usage.cpu());
  }
  m.wall = median(wall);
  m.cpu = median(cpu);
  for (const StageRun& s : records.front().stages) {
    std::vector<double> stage_wall, stage_cpu;
    for (const RunRecord& r : records) {
      stage_wall.push_back(r.stage(s.name)->seconds);
      stage_cpu.push_back(r.stage(s.name)->cpu_seconds);
    }
    m.stages.push_back({s.name, {median(stage_wall), median(stage_cpu)}});
  }
  return m;
}

void compare_builds(const std::string& hairfit, const std::string& other, const fs::path& scene, const fs::path& scratch,
                    int runs, int threads) {
  std::printf("\n## %s: A/B\n\nA (--against): %s\nB: %s\nload average before: %s\n\n", scene.string().c_str(),
              other.c_str(), hairfit.c_str(), load_average().c_str());
  std::fflush(stdout);
  std::vector<RunRecord> a, b;
  for (int r = 0; r < runs; ++r) {
    // ABBA: A then B in even rounds, B then A in odd ones.
    for (int k = 0; k < 2; ++k) {
      const bool run_a = (k == 0) == (r % 2 == 0);
      (run_a ? a : b).push_back(run_hairfit(run_a ? other : hairfit, scene, scratch / (run_a ? "a" : "b"), threads));
      std::fprintf(stderr, "  round %d/%d %s: %.2f s wall, %.2f s CPU\n", r + 1, runs, run_a ? "A" : "B",
                   (run_a ? a : b).back().usage.wall, (run_a ? a : b).back().usage.cpu());
    }
  }
  const Medians ma = medians_of(a), mb = medians_of(b);
  std::printf("%d runs each, --threads %d, medians\n\n| | A s | B s | B / A |\n|---|---:|---:|---:|\n", runs, threads);
  auto row = [](const std::string& name, double x, double y) {  // 0: not reported (an older build)
    if (x > 0 && y > 0) std::printf("| %s | %.3f | %.3f | %.3f |\n", name.c_str(), x, y, y / x);
    else {
      char left[32] = "–", right[32] = "–";
      if (x > 0) std::snprintf(left, sizeof left, "%.3f", x);
      if (y > 0) std::snprintf(right, sizeof right, "%.3f", y);
      std::printf("| %s | %s | %s | – |\n", name.c_str(), left, right);
    }
  };
  row("process wall", ma.wall, mb.wall);
  row("process CPU", ma.cpu, mb.cpu);
  for (std::size_t k = 0; k < ma.stages.size() && k < mb.stages.size(); ++k) {
    row(ma.stages[k].first + " wall", ma.stages[k].second[0], mb.stages[k].second[0]);
    row(ma.stages[k].first + " CPU", ma.stages[k].second[1], mb.stages[k].second[1]);
  }
  std::printf("\nload average after: %s\n", load_average().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  RunSettings run{5, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-paper-scale"};
  std::vector<fs::path> scenes;
  std::string against;
  for (int i = 1; i < argc; ++i) {
    if (parse_run_option(argc, argv, i, run)) continue;
    if (std::string(argv[i]) == "--against" && i + 1 < argc) {
      against = argv[++i];
      continue;
    }
    if (std::string(argv[i]).rfind("--", 0) == 0) {
      std::fprintf(stderr,
                   "usage: bench_paper_scale [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [--against PATH] "
                   "[SCENE ...]\n");
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
    for (const fs::path& scene : scenes) {
      const fs::path scratch = run.scratch / scene.parent_path().filename();
      if (against.empty()) report_scene(run.hairfit, scene, scratch, run.runs, run.threads);
      else compare_builds(run.hairfit, against, scene, scratch, run.runs, run.threads);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_paper_scale: %s\n", e.what());
    return 1;
  }
  return 0;
}
