// How time and memory grow with the work (issue 11): `hairfit run` of variants of a base scene
// (default fixtures/paper-scale: CDM on), fibres 10 000 → 150 000 at the base's guides, and guides
// 500 → 6000 at the base's fibres. Each variant is written into a scratch folder with absolute
// paths; fibres are set through hair.density, which the roots stage multiplies by the scalp's
// area and the density map: the base's roots figure `expected_roots` per unit of hair.density
// gives the density for any fibre count.
//   bench_scaling [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [--out DIR] [--scene BASE] [--replot]
// Writes DIR/scaling.csv and DIR/scaling.png (default bench/results) and prints a Markdown table.
// Each point is the median of N runs (default 1). The machine is shared: CPU time is the steadier
// figure; wall time depends on the others' load.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_runs.h"
#include "io/atomic_file.h"
#include "render/contact_sheet.h"
#include "render/plot.h"

using namespace hairfit;
using namespace hairfit::bench;

namespace {

struct Point {
  std::string series;  // "fibres" or "guides"
  double fibres = 0, guides = 0;
  double wall = 0, cpu = 0, peak_mib = 0;
  double guides_s = 0, strands_s = 0, density_s = 0, evaluations = 0;
  std::string load;
};

Point measure(const std::string& hairfit, const fs::path& scene, const fs::path& out, int runs, int threads) {
  std::vector<double> wall, cpu, guides_s, strands_s, density_s;
  Point p;
  p.load = load_average();
  double peak = 0;
  for (int r = 0; r < runs; ++r) {
    const RunRecord rec = run_hairfit(hairfit, scene, out, threads);
    wall.push_back(rec.usage.wall);
    cpu.push_back(rec.usage.cpu());
    peak = std::max(peak, mib(rec.usage.max_rss_bytes));
    guides_s.push_back(rec.stage("guides")->seconds);
    strands_s.push_back(rec.stage("strands")->seconds);
    density_s.push_back(rec.stage("density") ? rec.stage("density")->seconds : 0.0);
    p.fibres = rec.figure("strands", "fibres");
    p.guides = rec.figure("guides", "guides");
    p.evaluations = rec.figure("guides", "mean_evaluations");
  }
  p.wall = median(wall);
  p.cpu = median(cpu);
  p.peak_mib = peak;
  p.guides_s = median(guides_s);
  p.strands_s = median(strands_s);
  p.density_s = median(density_s);
  return p;
}

// The least-squares line a + b·x through the points: on it, growth is linear.
Series fitted_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = x.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx), a = (sy - b * sx) / n;
  const double lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
  return {"least-squares line", {lo, hi}, {a + b * lo, a + b * hi}, 7, false, true};
}

// Time (CPU and wall) and peak memory against the count that varies (fibres in thousands).
std::vector<Image> panels(const std::vector<Point>& points, const std::string& series, const std::string& label) {
  auto column = [&](double Point::*field, double scale = 1.0) {
    std::vector<double> v;
    for (const Point& p : points)
      if (p.series == series) v.push_back(p.*field * scale);
    return v;
  };
  const std::vector<double> x = series == "fibres" ? column(&Point::fibres, 1e-3) : column(&Point::guides);
  const std::vector<double> cpu = column(&Point::cpu), wall = column(&Point::wall);
  LinePlot time;
  time.title = "Time against " + label;
  time.x_label = label;
  time.y_label = "seconds";
  time.series = {{"process CPU (user + system)", x, cpu, 0},
                 {"process wall (loaded machine)", x, wall, 1},
                 {"guides stage wall", x, column(&Point::guides_s), 2},
                 {"strands stage wall", x, column(&Point::strands_s), 3},
                 fitted_line(x, cpu),
                 // invisible: room above the data for the legend (top right)
                 {"", {x.front()}, {1.6 * *std::max_element(wall.begin(), wall.end())}, 0, false, false}};
  LinePlot memory;
  memory.title = "Peak memory against " + label;
  memory.x_label = label;
  memory.y_label = "MiB (peak resident)";
  const std::vector<double> peak = column(&Point::peak_mib);
  memory.series = {{"process peak", x, peak, 4},
                   fitted_line(x, peak),
                   {"", {x.front()}, {1.4 * *std::max_element(peak.begin(), peak.end())}, 0, false, false},
                   {"", {x.front()}, {0.0}, 0, false, false}};
  return {render_line_plot(time, 720, 460), render_line_plot(memory, 720, 460)};
}

// The points of an earlier scaling.csv, for --replot.
std::vector<Point> read_points(const fs::path& csv) {
  std::vector<Point> points;
  for (const std::vector<std::string>& f : read_csv(csv, 11))
    points.push_back({f[0], std::stod(f[1]), std::stod(f[2]), std::stod(f[3]), std::stod(f[4]), std::stod(f[5]),
                      std::stod(f[6]), std::stod(f[7]), std::stod(f[8]), std::stod(f[9]), f[10]});
  return points;
}

void write_plot(const std::vector<Point>& points, const fs::path& file) {
  auto count = [&](const std::string& series, double Point::*other) {
    for (const Point& p : points)
      if (p.series == series) return std::to_string(static_cast<long>(p.*other));
    return std::string("?");
  };
  std::vector<Image> images = panels(points, "fibres", "thousand fibres (" + count("fibres", &Point::guides) + " guides)");
  for (Image& i : panels(points, "guides", "guides (" + count("guides", &Point::fibres) + " fibres)"))
    images.push_back(std::move(i));
  write_png(file, contact_sheet(images, {}, 2, {1.0f, 1.0f, 1.0f}));
}

}  // namespace

int main(int argc, char** argv) {
  RunSettings run{1, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-scaling"};
  bool replot = false;
  fs::path out = fs::path(HAIRFIT_SOURCE_DIR) / "bench/results";
  fs::path base = fs::path(HAIRFIT_SOURCE_DIR) / "fixtures/paper-scale/scene.toml";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (parse_run_option(argc, argv, i, run)) continue;
    if (a == "--out" && has_value) out = argv[++i];
    else if (a == "--scene" && has_value) base = argv[++i];
    else if (a == "--replot") replot = true;
    else {
      std::fprintf(stderr, "usage: bench_scaling [--runs N] [--threads T] [--hairfit PATH] [--scratch DIR] [--out DIR] "
                           "[--scene BASE] [--replot]\n");
      return 2;
    }
  }
  try {
    if (replot) {  // only redraw DIR/scaling.png from DIR/scaling.csv
      write_plot(read_points(out / "scaling.csv"), out / "scaling.png");
      return 0;
    }
    // The base scene's own figures: its guides, and roots per unit of hair.density.
    std::printf("# Scaling\n\nhairfit: %s\nsource at: %s\nbase: %s, %d run(s) per point, --threads %d\n\n",
                run.hairfit.c_str(), source_commit().c_str(), base.string().c_str(), run.runs, run.threads);
    const RunRecord probe = [&] {
      const fs::path dir = run.scratch / "probe";
      write_scene_variant(base, {}, dir / "scene.toml");
      fs::remove_all(dir / "out");
      fs::create_directories(dir / "out");
      RunRecord r;
      r.usage = run_process({run.hairfit, "run", (dir / "scene.toml").string(), "--out", (dir / "out").string(), "--until",
                             "roots", "--no-cache", "--quiet"},
                            dir / "out/run.log");
      if (r.usage.exit_code != 0) throw std::runtime_error("probe run failed; see " + (dir / "out/run.log").string());
      r.stages = read_report(dir / "out/report.json");
      return r;
    }();
    const double base_guides = probe.figure("roots", "guides");
    const double base_fibres = probe.figure("roots", "roots");
    const double roots_per_density = probe.figure("roots", "expected_roots") / toml::parse_file(base.string())
                                                                                   .at_path("hair.density")
                                                                                   .value_or(200.0);
    std::vector<std::pair<std::string, Overrides>> variants;
    for (double fibres : {10000.0, 25000.0, 50000.0, 90000.0, 120000.0, 150000.0})
      variants.push_back({"fibres", {{"hair.density", fibres / roots_per_density}, {"roots.guides", std::int64_t(base_guides)}}});
    for (std::int64_t guides : {500, 1000, 2000, 3000, 4500, 6000})
      variants.push_back({"guides", {{"hair.density", base_fibres / roots_per_density}, {"roots.guides", guides}}});

    std::vector<Point> points;
    std::string csv = "series,fibres,guides,wall_s,cpu_s,peak_mib,guides_stage_s,strands_stage_s,density_stage_s,"
                      "mean_evaluations,load_average\n";
    std::printf("| varied | fibres | guides | CPU s | wall s (loaded) | peak MiB | guides s | strands s | density s | "
                "evaluations/guide | load |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const fs::path dir = run.scratch / ("point" + std::to_string(v));
      write_scene_variant(base, variants[v].second, dir / "scene.toml");
      Point p = measure(run.hairfit, dir / "scene.toml", dir / "out", run.runs, run.threads);
      p.series = variants[v].first;
      std::printf("| %s | %.0f | %.0f | %.2f | %.2f | %.0f | %.2f | %.2f | %.2f | %.1f | %s |\n", p.series.c_str(),
                  p.fibres, p.guides, p.cpu, p.wall, p.peak_mib, p.guides_s, p.strands_s, p.density_s, p.evaluations,
                  p.load.c_str());
      std::fflush(stdout);
      char line[512];
      std::snprintf(line, sizeof line, "%s,%.0f,%.0f,%.3f,%.3f,%.1f,%.3f,%.3f,%.3f,%.2f,%s\n", p.series.c_str(), p.fibres,
                    p.guides, p.wall, p.cpu, p.peak_mib, p.guides_s, p.strands_s, p.density_s, p.evaluations,
                    p.load.c_str());
      csv += line;
      points.push_back(p);
    }
    write_text_file_atomically(out / "scaling.csv", csv);
    write_plot(points, out / "scaling.png");
    std::printf("\nwrote %s and %s\n", (out / "scaling.csv").string().c_str(), (out / "scaling.png").string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scaling: %s\n", e.what());
    return 1;
  }
  return 0;
}
