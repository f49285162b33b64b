// What accuracy costs (issue 11): each accuracy knob swept alone around the defaults on the
// spheroid fixture with the continuous density model on (so that density.voxel matters), every
// run measured against one high-accuracy reference run of the same scene:
//   rod        integrator rk2 | rk4 × segments 16 … 128       (reference rk4, 256)
//   fields     voxel 0.125 … 1 cm                              (reference 0.0625, band 1 cm)
//   guides     samples 4 … 64, tolerance 1e-2 … 1e-8,          (reference 64, 1e-10, 500)
//              max_iterations 10 … 200
//   density    voxel 0.125 … 1 cm                              (reference 0.125)
// Errors: guide shape (per guide the largest distance between corresponding nodes, at the same
// normalised arc length, of the run's guide and the reference's; mean and max over guides, cm),
// the share of guide nodes in the acceptable region judged by the reference's fields, and the
// field error (|run field − reference field| at the centres of the run's grid cells whose corners
// are all in the run's exact band and which lie in the reference's exact band; both fields).
// Time: the pipeline's stage seconds (wall, loaded machine) and the process CPU time (user +
// system) of each run, all stages, outputs not written. Runs in-process through run_pipeline().
//   bench_accuracy [--guides N] [--threads T] [--out DIR] [--quick] [--replot]
// (--quick: fewer values per knob; --replot: redraw accuracy.png from accuracy.csv only).
// Writes DIR/accuracy.csv, accuracy.md and accuracy.png (default bench/results).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cli_runs.h"
#include "core/parallel.h"
#include "guides/boundary.h"
#include "io/atomic_file.h"
#include "pipeline/pipeline.h"
#include "render/contact_sheet.h"
#include "render/plot.h"
#include "spec/scene.h"

using namespace hairfit;
using bench::fs::path;

namespace {

struct Run {
  PipelineResult result;
  double cpu = 0.0, user = 0.0;
  double stage_seconds(const std::string& name) const {
    for (const StageReport& s : result.report.stages)
      if (s.name == name) return s.seconds;
    return 0.0;
  }
  double total_seconds() const {
    double t = 0.0;
    for (const StageReport& s : result.report.stages) t += s.seconds;
    return t;
  }
  double figure(const std::string& stage, const std::string& key) const {
    for (const StageReport& s : result.report.stages)
      if (s.name == stage)
        for (const auto& [k, v] : s.figures)
          if (k == key) return std::holds_alternative<double>(v) ? std::get<double>(v) : double(std::get<std::int64_t>(v));
    return NAN;
  }
};

Run run(const Scene& scene, int threads) {
  const Inputs inputs = load_inputs(scene);
  RunOptions options;
  options.threads = threads;
  options.write_outputs = false;  // no cache either: every stage is computed
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  Run r;
  r.result = run_pipeline(scene, inputs, options);
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  auto seconds = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  r.user = seconds(after.ru_utime) - seconds(before.ru_utime);
  r.cpu = r.user + seconds(after.ru_stime) - seconds(before.ru_stime);
  return r;
}

// A node of a polyline at normalised arc length t ∈ [0, 1] (the rod is inextensible and its
// nodes are equally spaced in arc length, so node i of n segments sits at t = i/n).
Vec3 at_fraction(const std::vector<Vec3>& nodes, double t) {
  const double x = t * (nodes.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), nodes.size() - 2);
  const double f = x - i;
  return (1.0 - f) * nodes[i] + f * nodes[i + 1];
}

struct ShapeError {
  // Over guides, of the per-guide largest node distance, cm. The median and 90th percentile say
  // what most guides do; the mean and max are pulled up by guides that settle in another local
  // minimum of their objective than the reference's.
  double median = 0.0, p90 = 0.0, mean = 0.0, max = 0.0;
  double root_offset = 0.0;  // cm: largest root distance (0 when the guides correspond)
};

ShapeError shape_error(const Guides& run, const Guides& reference) {
  if (run.size() != reference.size())
    throw std::runtime_error("guide counts differ: " + std::to_string(run.size()) + " vs " +
                             std::to_string(reference.size()));
  ShapeError e;
  std::vector<double> per_guide;
  for (int g = 0; g < run.size(); ++g) {
    const std::vector<Vec3>& a = run.items[g].shape.nodes;
    const std::vector<Vec3>& b = reference.items[g].shape.nodes;
    double worst = 0.0;
    // Both node sets, each against the other curve at the same arc length.
    for (std::size_t i = 0; i < a.size(); ++i)
      worst = std::max(worst, (a[i] - at_fraction(b, double(i) / (a.size() - 1))).norm());
    for (std::size_t i = 0; i < b.size(); ++i)
      worst = std::max(worst, (b[i] - at_fraction(a, double(i) / (b.size() - 1))).norm());
    per_guide.push_back(worst);
    e.mean += worst / run.size();
    e.max = std::max(e.max, worst);
    e.root_offset = std::max(e.root_offset, (run.items[g].root - reference.items[g].root).norm());
  }
  std::sort(per_guide.begin(), per_guide.end());
  if (!per_guide.empty()) {
    e.median = per_guide[per_guide.size() / 2];
    e.p90 = per_guide[per_guide.size() * 9 / 10];
  }
  return e;
}

double inside_fraction(const Guides& guides, const Boundary& boundary) {
  std::size_t inside = 0, nodes = 0;
  for (const Guide& g : guides.items)
    for (const Vec3& p : g.shape.nodes) {
      inside += boundary.acceptable(p);
      ++nodes;
    }
  return nodes ? double(inside) / nodes : 0.0;
}

struct FieldError {
  double mean = 0.0, max = 0.0;
  std::int64_t samples = 0;
};

// |run − reference| at the centres of the run grid's cells that are exact on both sides.
void add_field_error(const DistanceField& run, const DistanceField& reference, FieldError& e, double& sum) {
  const Vec3i n = run.dims();
  const double h = run.voxel(), reach = reference.band_width() - std::sqrt(3.0) * reference.voxel();
  for (int k = 0; k + 1 < n.z(); ++k)
    for (int j = 0; j + 1 < n.y(); ++j)
      for (int i = 0; i + 1 < n.x(); ++i) {
        bool exact = true;
        for (int c = 0; c < 8 && exact; ++c) exact = run.in_band(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        if (!exact) continue;
        const Vec3 p = run.origin() + h * Vec3(i + 0.5, j + 0.5, k + 0.5);
        const double d_ref = reference.value(p);
        if (std::abs(d_ref) > reach) continue;
        const double d = std::abs(run.value(p) - d_ref);
        sum += d;
        e.max = std::max(e.max, d);
        ++e.samples;
      }
}

FieldError field_error(const StageValues& run, const StageValues& reference) {
  FieldError e;
  double sum = 0.0;
  add_field_error(*run.scalp_distance, *reference.scalp_distance, e, sum);
  add_field_error(*run.volume_field, *reference.volume_field, e, sum);
  e.mean = e.samples ? sum / e.samples : 0.0;
  return e;
}

struct Setting {
  std::string knob;   // the series
  std::string value;  // as written in the scene
  std::function<void(Scene&)> apply;
  bool is_default = false;
  bool density_model = false;  // run with the continuous density model (else none)
};

struct Row {
  Setting setting;
  double seconds = 0, guides_seconds = 0, cpu = 0, user = 0;
  ShapeError shape;
  double inside = 0, strands_inside = 0, iterations = 0, evaluations = 0, failures = 0;
  FieldError field;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

const char* const kCdm = "density.voxel (CDM)";
const char* const kStall = "density.stall_iterations (CDM)";

// The presets docs/results/accuracy.md recommends, from the one-knob rows: preview takes the knobs that save
// time for little error (fewer rod segments, samples and iterations, a looser tolerance) and
// keeps the voxels (the fields stage costs a few tenths of a second; coarser grids double the
// error); final buys accuracy where it is cheap (samples, tolerance, iterations). "default" is
// the shipped defaults.
void apply_recommended_preset(Scene& s, const std::string& preset) {
  if (preset == "preview") {
    s.rod.segments = 32;
    s.guides.samples = 8;
    s.guides.tolerance = 1e-3;
    s.guides.max_iterations = 30;
  } else if (preset == "final") {
    s.guides.samples = 64;
    s.guides.tolerance = 1e-8;
    s.guides.max_iterations = 200;
  }
}

// The presets as the scene format defines them now (spec: scene_presets()), whatever their values.
void apply_spec_preset(Scene& s, const std::string& preset) {
  for (const ScenePreset& p : scene_presets()) {
    if (p.name != preset) continue;
    for (const auto& [key, value] : p.values) {
      if (key == "rod.segments") s.rod.segments = int(value);
      else if (key == "fields.voxel") s.fields.voxel = value;
      else if (key == "guides.samples") s.guides.samples = int(value);
      else if (key == "guides.tolerance") s.guides.tolerance = value;
      else if (key == "guides.max_iterations") s.guides.max_iterations = int(value);
      else if (key == "density.voxel") s.density.voxel = value;
      else throw std::runtime_error("bench_accuracy does not know the preset key " + key);
    }
    return;
  }
  throw std::runtime_error("the scene format has no preset " + preset);
}

std::vector<Setting> settings(bool quick) {
  std::vector<Setting> s;
  s.push_back({"default", "defaults", [](Scene&) {}, true});
  for (const char* integrator : {"rk2", "rk4"})
    for (int segments : quick ? std::vector<int>{16, 32} : std::vector<int>{16, 32, 64, 128}) {
      if (std::string(integrator) == "rk4" && segments == 64) continue;  // the default
      s.push_back({std::string("rod ") + integrator, std::to_string(segments), [=](Scene& sc) {
                     sc.rod.integrator = integrator;
                     sc.rod.segments = segments;
                   }});
    }
  for (double v : {0.125, 0.5, 1.0})
    s.push_back({"fields.voxel", number(v), [=](Scene& sc) { sc.fields.voxel = v; }});
  for (int v : quick ? std::vector<int>{4, 32} : std::vector<int>{4, 8, 32, 64})
    s.push_back({"guides.samples", std::to_string(v), [=](Scene& sc) { sc.guides.samples = v; }});
  for (double v : {1e-2, 1e-3, 1e-4, 1e-8})
    s.push_back({"guides.tolerance", number(v), [=](Scene& sc) { sc.guides.tolerance = v; }});
  for (int v : quick ? std::vector<int>{10, 200} : std::vector<int>{10, 25, 50, 200})
    s.push_back({"guides.max_iterations", std::to_string(v), [=](Scene& sc) { sc.guides.max_iterations = v; }});
  for (const char* preset : {"preview", "final"}) {
    s.push_back({"recommended preset", preset, [=](Scene& sc) { apply_recommended_preset(sc, preset); }});
    s.push_back({"spec preset", preset, [=](Scene& sc) { apply_spec_preset(sc, preset); }});
  }
  s.push_back({"default (CDM)", "defaults", [](Scene&) {}, true, true});
  for (double v : {0.125, 0.5, 1.0})
    s.push_back({kCdm, number(v), [=](Scene& sc) { sc.density.voxel = v; }, false, true});
  for (int v : {0, 1, 5})  // 0: off
    s.push_back({kStall, std::to_string(v), [=](Scene& sc) { sc.density.stall_iterations = v; }, false, true});
  return s;
}

// The value of the knob a series varies in the default scene, "" when the default run is not on
// the series (rk2), so the default run sits on every other series at its place.
std::string default_value(const std::string& knob, const Scene& s) {
  if (knob == "rod rk2" || knob == "rod rk4") return s.rod.integrator == knob.substr(4) ? std::to_string(s.rod.segments) : "";
  if (knob == "fields.voxel") return number(s.fields.voxel);
  if (knob == "guides.samples") return std::to_string(s.guides.samples);
  if (knob == "guides.tolerance") return number(s.guides.tolerance);
  if (knob == "guides.max_iterations") return std::to_string(s.guides.max_iterations);
  if (knob == kCdm) return number(s.density.voxel);
  if (knob == kStall) return std::to_string(s.density.stall_iterations);
  if (knob.find("preset") != std::string::npos) return "default";
  return "";
}

// Orders a knob's values from coarse to fine: smaller voxels and tolerances are finer, more
// segments, samples and iterations are.
double fineness(const std::string& knob, const std::string& value) {
  if (knob.find("preset") != std::string::npos) return value == "preview" ? 0.0 : value == "default" ? 1.0 : 2.0;
  const double v = std::stod(value);
  if (knob == kStall) return v == 0.0 ? 1e9 : v;  // 0 turns the stall test off: the finest
  return knob.find("voxel") != std::string::npos || knob.find("tolerance") != std::string::npos ? -v : v;
}

Scene reference_of(Scene s) {
  s.rod.integrator = "rk4";
  s.rod.segments = 256;
  s.fields.voxel = 0.0625;
  s.fields.band = 16;  // 1 cm of exact distances, as the default 4 × 0.25 cm
  s.guides.samples = 64;
  s.guides.tolerance = 1e-10;
  s.guides.max_iterations = 500;
  s.density.voxel = 0.125;
  s.density.stall_iterations = 0;  // every density solve to the tolerance
  return s;
}

void with_cdm(Scene& s) {
  s.effects.density = DensityModel::continuous;
  s.guides.weights = {0.35, 0.2, 0.35, 0.1};  // as bench/results/density_guides.md
}

// Pareto plot: one series per knob through its values, coarse to fine, with the default run on
// each series. Without the density model only: with it, every guide's shape depends on all
// earlier batches, and the errors measure that sensitivity more than the knob (see the table).
void write_pareto_plot(const std::vector<Row>& rows, const Scene& scene, const path& file) {
  std::vector<std::string> knobs;
  for (const Row& r : rows)
    if (!r.setting.is_default && !r.setting.density_model &&
        std::find(knobs.begin(), knobs.end(), r.setting.knob) == knobs.end())
      knobs.push_back(r.setting.knob);
  std::vector<Image> images;
  for (const bool median : {true, false}) {
    LinePlot plot;
    plot.title = std::string(median ? "Median" : "90th percentile") + " guide error, no density model";
    plot.x_label = "CPU seconds, whole pipeline (user + system)";
    plot.y_label = std::string(median ? "median" : "90th percentile") + " guide error vs reference, cm";
    plot.log_y = true;
    double highest = 0.0;
    for (std::size_t k = 0; k < knobs.size(); ++k) {
      std::vector<std::pair<double, const Row*>> points;  // coarse to fine
      for (const Row& r : rows) {
        if (r.setting.density_model) continue;
        const std::string value = r.setting.is_default ? default_value(knobs[k], scene) : r.setting.value;
        if (r.setting.knob == knobs[k] || (r.setting.is_default && !value.empty()))
          points.push_back({fineness(knobs[k], value), &r});
      }
      std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      Series series{knobs[k], {}, {}, int(k)};
      for (const auto& [fine, r] : points) {
        series.x.push_back(r->cpu);
        series.y.push_back(median ? r->shape.median : r->shape.p90);
        highest = std::max(highest, series.y.back());
      }
      plot.series.push_back(series);
    }
    // An invisible point a decade and a half above the data keeps the legend (top right) clear of it.
    plot.series.push_back({"", {plot.series.front().x.front()}, {highest * 30.0}, 0, false, false});
    images.push_back(render_line_plot(plot, 760, 540));
  }
  write_png(file, side_by_side(images));
}

// The rows of an earlier accuracy.csv (enough of them for the plot), for --replot.
std::vector<Row> read_rows(const path& csv) {
  std::vector<Row> rows;
  for (const std::vector<std::string>& f : bench::read_csv(csv, 20)) {
    Row r;
    r.setting.knob = f[0];
    r.setting.value = f[1];
    r.setting.density_model = f[2] == "continuous";
    r.setting.is_default = f[3] == "1";
    r.cpu = std::stod(f[6]);
    r.shape.median = std::stod(f[8]);
    r.shape.p90 = std::stod(f[9]);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  int guides = 600, threads = 2;
  bool quick = false, replot = false;
  path out = path(HAIRFIT_SOURCE_DIR) / "bench/results";
  const path base = path(HAIRFIT_SOURCE_DIR) / "fixtures/spheroid/scene.toml";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--guides" && has_value) guides = std::atoi(argv[++i]);
    else if (a == "--threads" && has_value) threads = std::atoi(argv[++i]);
    else if (a == "--out" && has_value) out = argv[++i];
    else if (a == "--quick") quick = true;
    else if (a == "--replot") replot = true;
    else {
      std::fprintf(stderr, "usage: bench_accuracy [--guides N] [--threads T] [--out DIR] [--quick] [--replot]\n");
      return 2;
    }
  }
  try {
    Scene scene = parse_scene(base);
    scene.roots.guides = guides;
    if (replot) {  // only redraw DIR/accuracy.png from DIR/accuracy.csv
      write_pareto_plot(read_rows(out / "accuracy.csv"), scene, out / "accuracy.png");
      return 0;
    }
    Scene cdm_scene = scene;
    with_cdm(cdm_scene);

    // One reference per density model, computed when a setting first needs it.
    std::map<bool, Run> references;
    auto reference = [&](bool density_model) -> const Run& {
      auto found = references.find(density_model);
      if (found != references.end()) return found->second;
      std::fprintf(stderr, "reference run%s (load %s)...\n", density_model ? " with CDM" : "",
                   bench::load_average().c_str());
      const Run& r = references.emplace(density_model, run(reference_of(density_model ? cdm_scene : scene), threads))
                         .first->second;
      std::fprintf(stderr, "  %.1f s, %.1f s CPU\n", r.total_seconds(), r.cpu);
      return r;
    };
    auto judge = [&](bool density_model) {
      const StageValues& v = reference(density_model).result.values;
      return Boundary{v.scalp_field, v.volume_field};
    };

    std::vector<Row> rows;
    for (const Setting& setting : settings(quick)) {
      Scene s = setting.density_model ? cdm_scene : scene;
      setting.apply(s);
      const Run& ref = reference(setting.density_model);
      const Run r = run(s, threads);
      Row row;
      row.setting = setting;
      row.seconds = r.total_seconds();
      row.guides_seconds = r.stage_seconds("guides");
      row.cpu = r.cpu;
      row.user = r.user;
      row.shape = shape_error(*r.result.values.guides, *ref.result.values.guides);
      if (row.shape.root_offset > 1e-9)
        throw std::runtime_error(setting.knob + " = " + setting.value + " moved the guide roots by " +
                                 number(row.shape.root_offset) + " cm: guides do not correspond");
      row.inside = inside_fraction(*r.result.values.guides, judge(setting.density_model));
      row.strands_inside = r.figure("strands", "inside_fraction");
      row.iterations = r.figure("guides", "mean_iterations");
      row.evaluations = r.figure("guides", "mean_evaluations");
      row.failures = r.figure("guides", "failures");
      row.field = field_error(r.result.values, ref.result.values);
      std::fprintf(stderr, "  %-22s %-8s %6.1f s %6.1f s CPU  error median %.4f mean %.4f max %.3f cm  inside %.4f  "
                           "field %.4f cm (load %s)\n",
                   setting.knob.c_str(), setting.value.c_str(), row.seconds, row.cpu, row.shape.median, row.shape.mean,
                   row.shape.max, row.inside, row.field.mean, bench::load_average().c_str());
      rows.push_back(row);
    }

    // A setting is on the Pareto front when no other of the same density model is at once
    // cheaper (CPU) and more accurate (median guide error).
    auto dominated = [&](const Row& r) {
      for (const Row& o : rows)
        if (o.setting.density_model == r.setting.density_model && o.cpu < r.cpu && o.shape.median < r.shape.median)
          return true;
      return false;
    };
    std::string csv = "knob,value,density_model,default,total_s,guides_s,cpu_s,user_s,guide_error_median_cm,"
                      "guide_error_p90_cm,guide_error_mean_cm,guide_error_max_cm,inside_fraction,"
                      "strands_inside_fraction,mean_iterations,mean_evaluations,failures,field_error_mean_cm,"
                      "field_error_max_cm,pareto\n";
    std::string md = "# What accuracy costs\n\n";
    md += "`build-bench/bench/bench_accuracy --guides " + std::to_string(guides) + " --threads " +
          std::to_string(threads) + "`, source at " + bench::source_commit() +
          ". Spheroid fixture (`fixtures/spheroid/scene.toml`) with " + std::to_string(guides) +
          " guides (roots.guides), every other key as shipped, one knob changed per row. The (CDM) rows "
          "run with the continuous density model on (weights 0.35/0.2/0.35/0.1) and are "
          "measured against a reference with it; the others without a density model.\n\n";
    md += "Reference: rk4 with 256 segments, fields.voxel 0.0625 (band 16 voxels = 1 cm), guides.samples 64, "
          "tolerance 1e-10, max_iterations 500, density.voxel 0.125, density.stall_iterations 0 (off).";
    for (const auto& [model, r] : references) {
      const Boundary b{r.result.values.scalp_field, r.result.values.volume_field};
      md += std::string(model ? " With CDM: " : " Without: ") + number(r.total_seconds()) + " s wall, " +
            number(r.cpu) + " s CPU, inside fraction " + number(inside_fraction(*r.result.values.guides, b)) +
            ", not converged " + number(r.figure("guides", "failures")) + ".";
    }
    md += "\n\nGuide error: per guide the largest distance between corresponding nodes (same normalised arc length) "
          "of the run's and the reference's guide, cm; median, 90th percentile and max over guides. Inside: share "
          "of guide nodes in the acceptable region judged by the reference's fields. Field error: |run − "
          "reference| at the run grid's cell centres within the exact band of both, both fields, mean / max cm. "
          "Time: the sum of the stage times (wall clock; the 2-core machine was loaded by others' builds, so it "
          "varies) and the process CPU time (user + system, steadier). ★: on the Pareto front of CPU time against "
          "median guide error (within the same density model).\n\n";
    md += "| knob | value | wall s (loaded) | CPU s | guide error median / p90 / max cm | inside | field error mean / "
          "max cm | iterations | not converged | |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const Row& r : rows) {
      const bool front = !dominated(r);
      char line[1024];
      std::snprintf(line, sizeof line,
                    "%s,%s,%s,%d,%.3f,%.3f,%.3f,%.3f,%.6g,%.6g,%.6g,%.6g,%.6f,%.6f,%.3f,%.3f,%.0f,%.6g,%.6g,%d\n",
                    r.setting.knob.c_str(), r.setting.value.c_str(), r.setting.density_model ? "continuous" : "none",
                    int(r.setting.is_default), r.seconds, r.guides_seconds, r.cpu, r.user, r.shape.median, r.shape.p90,
                    r.shape.mean, r.shape.max, r.inside, r.strands_inside, r.iterations, r.evaluations, r.failures,
                    r.field.mean, r.field.max, int(front));
      csv += line;
      std::snprintf(line, sizeof line,
                    "| %s | %s | %.1f | %.1f | %.4f / %.3f / %.2f | %.4f | %.4f / %.3f | %.1f | %.0f | %s |\n",
                    r.setting.knob.c_str(), r.setting.value.c_str(), r.seconds, r.cpu, r.shape.median, r.shape.p90,
                    r.shape.max, r.inside, r.field.mean, r.field.max, r.iterations, r.failures, front ? "★" : "");
      md += line;
    }
    write_text_file_atomically(out / "accuracy.csv", csv);
    write_text_file_atomically(out / "accuracy.md", md);

    write_pareto_plot(rows, scene, out / "accuracy.png");
    std::printf("%s\nwrote %s, accuracy.md, accuracy.png\n", md.c_str(), (out / "accuracy.csv").string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_accuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
