#include "pipeline/golden.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "pipeline/build_id.h"

namespace hairfit {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kGoldenFormat = "hairfit-golden/1";
constexpr const char* kGuidesHeader =
    "guide,converged,iterations,tip_x,tip_y,tip_z,force_x,force_y,force_z,moment_x,moment_y,moment_z";

std::string number(double x, int digits = 7) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

std::string figure_text(const Figure& f) {
  if (std::holds_alternative<bool>(f)) return std::get<bool>(f) ? "true" : "false";
  if (std::holds_alternative<std::int64_t>(f)) return std::to_string(std::get<std::int64_t>(f));
  if (std::holds_alternative<double>(f)) return number(std::get<double>(f), 10);
  return "\"" + std::get<std::string>(f) + "\"";
}

bool numeric(const Figure& f) { return std::holds_alternative<std::int64_t>(f) || std::holds_alternative<double>(f); }
double as_double(const Figure& f) {
  return std::holds_alternative<double>(f) ? std::get<double>(f) : static_cast<double>(std::get<std::int64_t>(f));
}

// Compares the figures of one stage; `exact` is the same-build rule (equal digests decide, the
// figures only explain by how much), otherwise each figure against its tolerance.
void compare_figures(const GoldenStage& golden, const GoldenStage& now, bool exact, StageComparison& out) {
  std::map<std::string, Figure> current(now.figures.begin(), now.figures.end());
  for (const auto& [key, was] : golden.figures) {
    const auto it = current.find(key);
    if (it == current.end()) {
      out.details.push_back(key + ": in the golden results (" + figure_text(was) + "), not in this run");
      out.differs = true;
      continue;
    }
    const Figure is = it->second;  // a copy: the entry is erased next
    current.erase(it);
    if (numeric(was) && numeric(is)) {
      const double a = as_double(was), b = as_double(is);
      if (a == b) continue;
      const FigureTolerance t = figure_tolerance(golden.name, key);
      const bool within = std::fabs(b - a) <= t.absolute + t.relative * std::fabs(a);
      std::string line = key + ": " + figure_text(was) + " → " + figure_text(is) + " (" + (b > a ? "+" : "") + number(b - a, 4);
      if (a != 0) line += ", " + std::string(b > a ? "+" : "") + number(100.0 * (b - a) / std::fabs(a), 3) + " %";
      line += exact ? ")" : std::string(within ? ", within" : ", beyond") + " tolerance " +
                                (t.absolute > 0 ? number(t.absolute, 3) : "") + (t.absolute > 0 && t.relative > 0 ? " + " : "") +
                                (t.relative > 0 ? number(100 * t.relative, 3) + " %" : (t.absolute > 0 ? "" : "0")) + ")";
      out.details.push_back(line);
      if (!exact && !within) out.differs = true;
    } else if (figure_text(was) != figure_text(is)) {
      out.details.push_back(key + ": " + figure_text(was) + " → " + figure_text(is));
      if (!exact) out.differs = true;
    }
  }
  for (const auto& [key, is] : current) {
    out.details.push_back(key + ": new in this run (" + figure_text(is) + ")");
    if (!exact) out.differs = true;
  }
}

void compare_guides(const std::vector<GoldenGuide>& golden, const std::vector<GoldenGuide>& now, bool exact,
                    StageComparison& out) {
  if (golden.size() != now.size()) {
    out.details.push_back("guide table: " + std::to_string(golden.size()) + " guides in the golden results, " +
                          std::to_string(now.size()) + " now");
    out.differs = true;
    return;
  }
  std::size_t moved = 0, beyond = 0, worst = 0, converged_changed = 0;
  double largest = 0.0;
  for (std::size_t i = 0; i < golden.size(); ++i) {
    const double d = (now[i].tip - golden[i].tip).norm();
    moved += d > 0;
    beyond += d > kGuideTipTolerance;
    converged_changed += now[i].converged != golden[i].converged;
    if (d > largest) largest = d, worst = i;
  }
  if (moved == 0 && converged_changed == 0) return;
  const double share_within = golden.empty() ? 1.0 : 1.0 - static_cast<double>(beyond) / golden.size();
  out.details.push_back("guide tips: " + std::to_string(moved) + " of " + std::to_string(golden.size()) +
                        " moved (to the table's 7 digits), " + std::to_string(beyond) + " by more than " +
                        number(kGuideTipTolerance) + " cm, the most " + number(largest, 3) + " cm (guide " +
                        std::to_string(worst) + "); " + std::to_string(converged_changed) + " changed convergence");
  if (!exact && share_within < kGuideTipShare) {
    out.details.push_back("guide tips: " + number(100 * share_within, 4) + " % within " + number(kGuideTipTolerance) +
                          " cm, tolerance " + number(100 * kGuideTipShare, 3) + " %");
    out.differs = true;
  }
}

std::vector<GoldenGuide> read_guides(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "cannot read the golden guides (write them with hairfit check --update)");
  std::string line;
  std::getline(in, line);
  if (line != kGuidesHeader) throw InputError(path.string() + ":1", "expected the header \"" + std::string(kGuidesHeader) + "\"");
  std::vector<GoldenGuide> guides;
  for (int row = 2; std::getline(in, line); ++row) {
    std::istringstream fields(line);
    std::vector<double> x;
    std::string cell;
    while (std::getline(fields, cell, ',')) {
      char* end = nullptr;
      x.push_back(std::strtod(cell.c_str(), &end));
      if (cell.empty() || *end) throw InputError(path.string() + ":" + std::to_string(row), "\"" + cell + "\" is not a number");
    }
    if (x.size() != 12 || x[0] != static_cast<double>(guides.size()))
      throw InputError(path.string() + ":" + std::to_string(row), "expected 12 values for guide " + std::to_string(guides.size()));
    GoldenGuide g;
    g.converged = x[1] != 0;
    g.iterations = static_cast<int>(x[2]);
    g.tip = Vec3(x[3], x[4], x[5]);
    g.force = Vec3(x[6], x[7], x[8]);
    g.root_moment = Vec3(x[9], x[10], x[11]);
    guides.push_back(g);
  }
  return guides;
}

}  // namespace

Golden make_golden(const PipelineResult& result) {
  Golden g;
  g.build = build_id();
  for (const StageReport& s : result.report.stages) g.stages.push_back(GoldenStage{s.name, s.digest, s.figures});
  if (result.values.guides)
    for (const Guide& guide : result.values.guides->items) {
      GoldenGuide row;
      row.converged = guide.converged;
      row.iterations = guide.iterations;
      row.tip = guide.shape.nodes.empty() ? guide.root : guide.shape.nodes.back();
      row.force = guide.force;
      row.root_moment = guide.root_moment;
      // As the table stores them, so that a run compares equal to its own golden results.
      auto stored = [](Vec3& v) {
        for (int k = 0; k < 3; ++k) v[k] = std::strtod(number(v[k]).c_str(), nullptr);
      };
      stored(row.tip);
      stored(row.force);
      stored(row.root_moment);
      g.guides.push_back(row);
    }
  return g;
}

void write_golden(const fs::path& folder, const Golden& golden) {
  Json root;
  root["format"] = kGoldenFormat;
  root["build"] = golden.build;
  Json stages = Json::object();
  for (const GoldenStage& s : golden.stages) {
    Json figures = Json::object();
    for (const auto& [key, value] : s.figures) std::visit([&, k = key](const auto& v) { figures[k] = v; }, value);
    stages[s.name] = {{"digest", s.digest}, {"figures", figures}};
  }
  root["stages"] = stages;
  write_text_file_atomically(folder / "golden.json", root.dump(2) + "\n");
  std::string csv = std::string(kGuidesHeader) + "\n";
  for (std::size_t i = 0; i < golden.guides.size(); ++i) {
    const GoldenGuide& g = golden.guides[i];
    csv += std::to_string(i) + "," + (g.converged ? "1" : "0") + "," + std::to_string(g.iterations);
    for (const Vec3* v : {&g.tip, &g.force, &g.root_moment})
      for (int k = 0; k < 3; ++k) csv += "," + number((*v)[k]);
    csv += "\n";
  }
  write_text_file_atomically(folder / "guides.csv", csv);
}

Golden read_golden(const fs::path& folder) {
  const fs::path path = folder / "golden.json";
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "no golden results here (write them with hairfit check SCENE --golden " +
                                               folder.string() + " --update)");
  Golden g;
  try {
    const Json root = Json::parse(in);
    if (root.at("format") != kGoldenFormat)
      throw InputError(path.string(), "format " + root.at("format").dump() + ", expected \"" + kGoldenFormat + "\"");
    g.build = root.at("build").get<std::string>();
    for (const auto& [name, stage] : root.at("stages").items()) {
      GoldenStage s{name, stage.at("digest").get<std::string>(), {}};
      for (const auto& [key, value] : stage.at("figures").items()) {
        if (value.is_boolean()) s.figures.emplace_back(key, value.get<bool>());
        else if (value.is_number_integer()) s.figures.emplace_back(key, value.get<std::int64_t>());
        else if (value.is_number()) s.figures.emplace_back(key, value.get<double>());
        else s.figures.emplace_back(key, value.get<std::string>());
      }
      g.stages.push_back(std::move(s));
    }
  } catch (const Json::exception& e) {
    throw InputError(path.string(), std::string("malformed golden results: ") + e.what());
  }
  g.guides = read_guides(folder / "guides.csv");
  return g;
}

FigureTolerance figure_tolerance(const std::string& stage, const std::string& figure) {
  // Figures that count borderline items (a sample on the band's edge, a guide stopping at the
  // cap) or average iterative solver work may move a little between builds; positions and
  // counts of what was placed by exact rules may not.
  static const std::map<std::string, FigureTolerance> table{
      {"fields.band_voxels", {0, 1e-3}},
      {"fields.memory_bytes", {0, 1e-3}},
      {"roots.min_spacing_cm", {0, 1e-6}},
      {"roots.mean_spacing_cm", {0, 1e-6}},
      {"preguides.reached_depth", {1, 0.01}},
      {"preguides.flagged", {1, 0.01}},
      {"preguides.mean_newton_steps", {0, 0.05}},
      {"preguides.shared_newton_steps", {0, 0.05}},
      {"guides.failures", {1, 0.02}},
      {"guides.mean_iterations", {0, 0.05}},
      {"guides.max_iterations", {10, 0}},
      {"guides.mean_evaluations", {0, 0.05}},
      {"guides.inside_fraction", {0.005, 0}},
      {"guides.inside_head_fraction", {0.005, 0}},
      {"guides.outside_volume_fraction", {0.005, 0}},
      {"guides.outside_tip_fraction", {0.005, 0}},
      {"guides.guides_ending_outside", {1, 0.02}},
      {"guides.guides_held", {1, 0.02}},
      {"guides.max_point_force", {0, 0.05}},
      {"preguides.weight_not_followed", {1, 0.01}},
      {"preguides.flagged_tip_outside", {1, 0.01}},
      {"preguides.hanging", {1, 0.02}},
      {"fields.hairline_thickness_cm", {0, 1e-6}},
      {"roots.hang_weight_mean", {0.005, 0}},
      {"roots.hair_length_mean_cm", {0, 0.01}},
      {"guides.mean_direction_mismatch", {0, 0.05}},
      {"guides.followed_direction_mismatch", {0, 0.05}},
      {"guides.mean_f4", {0, 0.05}},
      {"strands.points", {0, 0.002}},
      {"strands.cut", {1, 0.02}},
      {"strands.cut_at_scalp", {1, 0.02}},
      {"strands.inside_fraction", {0.005, 0}},
      {"preguides.inside_fraction", {0.005, 0}},
      {"preguides.flow_crossing", {0.005, 0}},
      {"guides.flow_crossing", {0.005, 0}},
      {"guides.flow_median_degrees", {0.5, 0}},
      {"strands.cut_share", {0.005, 0}},
      {"strands.coverage", {0.005, 0}},
      {"density.region_cells", {0, 1e-3}},
      {"density.occupied_cells", {0, 0.01}},
      {"density.mean_density", {0, 0.01}},
      {"density.coefficient_of_variation", {0, 0.02}},
      {"density.empty_share", {0.005, 0}},
      {"density.max_segments_per_cell", {2, 0}},
  };
  const auto it = table.find(stage + "." + figure);
  if (it != table.end()) return it->second;
  return FigureTolerance{0, 1e-9};  // everything else: the same to rounding (exact for counts)
}

const StageComparison* GoldenComparison::first_difference() const {
  for (const StageComparison& s : stages)
    if (s.differs) return &s;
  return nullptr;
}

GoldenComparison compare_golden(const Golden& golden, const Golden& now) {
  GoldenComparison c;
  c.same_build = golden.build == now.build;
  std::vector<std::string> names;
  for (const GoldenStage& s : now.stages) names.push_back(s.name);
  for (const GoldenStage& s : golden.stages)
    if (std::find(names.begin(), names.end(), s.name) == names.end()) names.push_back(s.name);
  auto find = [](const Golden& g, const std::string& name) -> const GoldenStage* {
    for (const GoldenStage& s : g.stages)
      if (s.name == name) return &s;
    return nullptr;
  };
  for (const std::string& name : names) {
    StageComparison s;
    s.name = name;
    const GoldenStage* was = find(golden, name);
    const GoldenStage* is = find(now, name);
    if (!was || !is) {
      s.differs = true;
      s.details.push_back(was ? "in the golden results, but this run has no such stage"
                              : "this run has it, the golden results do not");
    } else {
      if (c.same_build && was->digest != is->digest) {
        s.differs = true;
        s.details.push_back("digest " + is->digest + ", golden " + was->digest);
      }
      compare_figures(*was, *is, c.same_build, s);
      if (name == "guides") compare_guides(golden.guides, now.guides, c.same_build, s);
    }
    c.stages.push_back(std::move(s));
  }
  return c;
}

}  // namespace hairfit
