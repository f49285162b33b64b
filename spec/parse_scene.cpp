// Scene text → Scene value. The only file that includes toml++.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "spec/scene.h"
#include "spec/scene_keys.h"

namespace hairfit {

namespace fs = std::filesystem;

double SceneUnits::to_cm() const {
  if (length == "mm") return 0.1;
  if (length == "dm") return 10.0;
  if (length == "m") return 100.0;
  if (length == "in") return 2.54;
  return 1.0;
}

bool SceneEffects::uses_map(const std::string& name) const {
  return std::find(maps.begin(), maps.end(), name) != maps.end();
}

std::vector<std::string> SceneEffects::names() const {
  std::vector<std::string> out;
  if (gravity) out.push_back("gravity");
  if (contact) out.push_back("contact");
  if (density == DensityModel::binary) out.push_back("density:binary");
  if (density == DensityModel::continuous) out.push_back("density:continuous");
  for (const std::string& m : maps) out.push_back("map:" + m);
  if (cutting) out.push_back("cutting");
  if (winding) out.push_back("winding");
  return out;
}

Diagnostic Scene::at(const std::string& key, const std::string& message) const {
  const auto it = locations.find(key);
  Diagnostic d{{file.string(), 0, 0}, message, {}};
  if (it != locations.end()) d.where = it->second;
  // The source line is re-read on demand so a Scene stays small.
  if (d.where.line > 0) {
    std::ifstream in(file);
    std::string line;
    for (int i = 0; i < d.where.line && std::getline(in, line); ++i) {}
    d.source_line = line;
  }
  return d;
}

namespace {

// strands.contain for hair from the shell (cm): an excursion deeper than this is left to cutting.
constexpr double kShellContain = 1.0;
// The guides of hair that suits its shell (apply_shell_defaults).
constexpr double kShellPointForces = 3;
constexpr double kShellSamples = 32;
constexpr double kShellOutsidePenalty = 10.0;  // cm
constexpr double kShellBoundaryWidth = 0.3;    // cm
// The growth field's smoothing for hair from the shell (cm).
constexpr double kShellFlowSmoothing = 8.0;

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string last_part(const std::string& dotted) {
  const std::size_t dot = dotted.rfind('.');
  return dot == std::string::npos ? dotted : dotted.substr(dot + 1);
}

std::string parent_part(const std::string& dotted) {
  const std::size_t dot = dotted.rfind('.');
  return dot == std::string::npos ? std::string() : dotted.substr(0, dot);
}

class SceneParser {
 public:
  SceneParser(const std::string& text, const fs::path& file) : file_(file) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
    for (const SceneKey& k : scene_keys()) {
      names_.insert(k.name);
      for (std::string p = parent_part(k.name); !p.empty(); p = parent_part(p)) tables_.insert(p);
    }
  }

  Scene parse(const std::string& text) {
    scene_.file = file_;
    toml::table root;
    try {
      root = toml::parse(text, file_.string());
    } catch (const toml::parse_error& e) {
      const auto& begin = e.source().begin;
      error({static_cast<int>(begin.line), static_cast<int>(begin.column)},
            "TOML syntax error: " + std::string(e.description()));
      throw InputError(diagnostics_);
    }
    visit(root, "");
    for (const SceneKey& k : scene_keys())
      if (k.required && !scene_.locations.count(k.name))
        error({0, 0}, "required key " + k.name + " is missing" +
                          (k.name == "format" ? " (add format = \"" + std::string(kSceneFormat) + "\" at the top)" : ""));
    if (diagnostics_.empty()) apply_preset();
    if (diagnostics_.empty()) apply_shell_defaults();
    if (diagnostics_.empty()) check_consistency();
    if (!diagnostics_.empty()) throw InputError(diagnostics_);
    if (scene_.output.dir.empty()) scene_.output.dir = file_.parent_path() / "out";
    return scene_;
  }

 private:
  struct Where {
    int line, column;
  };

  void error(Where w, const std::string& message) {
    Diagnostic d{{file_.string(), w.line, w.column}, message, {}};
    if (w.line > 0 && w.line <= static_cast<int>(lines_.size())) d.source_line = lines_[w.line - 1];
    diagnostics_.push_back(std::move(d));
  }

  static Where where(const toml::source_region& r) {
    return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
  }

  void visit(const toml::table& table, const std::string& prefix) {
    for (const auto& [key, node] : table) {
      const std::string name = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
      if (names_.count(name)) {
        scene_.locations[name] = {file_.string(), where(node.source()).line, where(node.source()).column};
        read_value(*find_scene_key(name), node);
      } else if (tables_.count(name) && node.is_table()) {
        visit(*node.as_table(), name);
      } else if (tables_.count(name)) {
        error(where(key.source()), "[" + name + "] must be a table of keys, not a single value");
      } else {
        error(where(key.source()), unknown_key_message(name));
      }
    }
  }

  std::string unknown_key_message(const std::string& name) const {
    const std::string parent = parent_part(name), leaf = last_part(name);
    std::string where_text = parent.empty() ? "at the top level" : "in [" + parent + "]";
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, leaf.size() / 3) + 1;
    // A near miss in the same table, then the same word in another table.
    for (const std::string& known : names_) {
      if (parent_part(known) != parent) continue;
      const std::size_t d = edit_distance(leaf, last_part(known));
      if (d < best_distance) best_distance = d, best = known;
    }
    for (const std::string& known : tables_)
      if (parent_part(known) == parent && edit_distance(leaf, last_part(known)) < best_distance)
        best_distance = edit_distance(leaf, last_part(known)), best = known;
    std::vector<std::string> candidates;
    if (!best.empty()) candidates.push_back(best);
    else
      for (const std::string& known : names_)
        if (last_part(known) == leaf) candidates.push_back(known);
    std::string message = "unknown key \"" + leaf + "\" " + where_text;
    for (std::size_t i = 0; i < candidates.size(); ++i)
      message += (i == 0 ? " (did you mean \"" : i + 1 == candidates.size() ? "\" or \"" : "\", \"") + candidates[i];
    if (!candidates.empty()) message += "\"?)";
    else message += "; spec/reference.md lists every key";
    return message;
  }

  // The preset's values for every knob the file does not set itself (an explicit key wins).
  void apply_preset() {
    for (const ScenePreset& p : scene_presets())
      if (p.name == scene_.preset)
        for (const auto& [key, value] : p.values)
          if (!scene_.locations.count(key)) imply(key, {value}, {}, "preset \"" + p.name + "\"");
  }

  // Sets a key the file leaves unset by a rule, and remembers the rule for the resolved scene.
  void imply(const std::string& key, const std::vector<double>& numbers, const std::vector<std::string>& texts,
             const std::string& rule) {
    find_scene_key(key)->store(scene_, numbers, texts);
    scene_.implied[key] = rule;
  }
  void shell_default(const std::string& key, const std::vector<double>& numbers,
                     const std::vector<std::string>& texts = {}) {
    imply(key, numbers, texts, "shell default");
  }

  // Hair that suits its shell: with neither hair.length nor hair.tilt given (nor their maps), the
  // run derives them from the shell, and what the file leaves unset of the thin-shell machinery
  // takes the values made for it: growth toward the thicker layer along one smooth field steered
  // by the hull's relief, pre-guides and guides kept in the layer, the guides' looser stop.
  void apply_shell_defaults() {
    bool given = scene_.effects.uses_map("length") || scene_.effects.uses_map("tilt");
    for (const char* key : kShellTriggerKeys) given = given || scene_.locations.count(key);
    if (given) return;
    scene_.hair.from_shell = true;
    for (const auto& [key, value] : {std::pair<const char*, const char*>{"hair.tilt_toward", "thicker"},
                                     {"hair.flow", "relief"},
                                     {"preguides.immersion", "layer"},
                                     {"guides.boundary", "layer"}})
      if (!scene_.locations.count(key)) shell_default(key, {}, {value});
    // The growth field averaged over 8 cm rather than 6: MakeHuman ponytail01's guides cross at
    // 0.073–0.095 over six seeds instead of 0.085–0.149, short04's at 0.019–0.038 instead of
    // 0.030–0.047 (bench/results/thin_shells.md).
    if (!scene_.locations.count("hair.flow_smoothing"))
      shell_default("hair.flow_smoothing", {kShellFlowSmoothing});
    // Hair styled along its path: rods straight at rest, loaded at the tip and the root alone, do
    // not follow a flow that turns in the layer, and cross each other (the sculpted busts' guides
    // at 0.12–0.16; styled, 0.008–0.077); nor do they lie on the skull and then hang. Hair that
    // hangs rests along its fall (guides/fall_rest.h), the rest along the flow.
    if (!scene_.locations.count("hair.rest_shape")) shell_default("hair.rest_shape", {}, {"flow"});
    // Fibres spread about their guides wider than a thin layer is thick: those that skim out of
    // it (most by under 1 mm) are held in.
    if (!scene_.locations.count("strands.contain")) shell_default("strands.contain", {kShellContain});
    // A layer deeper than a wisp is wide is filled by its hair only if the fibres spread through
    // it (MakeHuman bob01, 3.4 cm deep: coverage 0.32 with round wisps, 0.57 spread); a thinner
    // one keeps the paper's wisps (short04 and ponytail01, 0.4 cm: spread, more fibres run past the
    // layer's edge and are cut). bench/results/thin_shells.md.
    if (!scene_.locations.count("strands.depth")) shell_default("strands.depth", {}, {"auto"});
    // Tips that run past the end of a thin layer (the hull's edge) are cut there.
    if (!scene_.locations.count("strands.cut_tips")) shell_default("strands.cut_tips", {1.0});
    // A raw shell that goes on past the scalp's hairline has the skin under it there, not the
    // hair layer down to the neck's axis: MakeHuman short04 / bob01 / ponytail01 put 4.9 / 20.4 /
    // 1.8 % of their fibre points inside the real head with the floor, 0.14 / 4.4 / 0.3 % with the
    // shell. A closed volume encloses what it overhangs by design (prepare's bust with hair over
    // the ears: coverage 0.73 with the floor, 0.67 with the shell), so "auto" keeps the floor
    // there (bench/results/thin_shells.md).
    if (!scene_.locations.count("fields.skin_beyond_hairline"))
      shell_default("fields.skin_beyond_hairline", {}, {"auto"});
    // The guides start from pre-guides that already lie in the layer: a looser stop loses nothing
    // there (MakeHuman short04: 0.979 of the nodes inside at 1e-6 and 1e-5, 35.9 and 29.0
    // evaluations a guide). An accuracy preset's own tolerance wins.
    if (!scene_.locations.count("guides.tolerance") && scene_.preset == "default")
      shell_default("guides.tolerance", {1e-5});
    // A rod loaded at its end alone runs straight where the skull curves away under a thin layer
    // and bends back too late: weightless guides carry three interior point forces (the layer
    // holding the hair), sampled densely enough that the rod cannot leave the layer between
    // samples, and pay more for a sample beyond the layer; a guide still more than 3 mm out is
    // tried from its other start. MakeHuman short04 / bob01 / ponytail01, guide nodes inside:
    // 0.983 / 0.995 / 0.979 without, 0.996 / 0.998 / 0.994 with (bench/results/thin_shells.md).
    if (!scene_.effects.gravity && !scene_.effects.contact && !scene_.locations.count("guides.point_forces"))
      shell_default("guides.point_forces", {kShellPointForces});
    if (!scene_.locations.count("guides.samples") && scene_.preset == "default")
      shell_default("guides.samples", {kShellSamples});
    if (!scene_.locations.count("guides.outside_penalty"))
      shell_default("guides.outside_penalty", {kShellOutsidePenalty});
    if (!scene_.locations.count("guides.boundary_width"))
      shell_default("guides.boundary_width", {kShellBoundaryWidth});
  }

  static std::string type_name(const toml::node& node) {
    switch (node.type()) {
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a number";
      case toml::node_type::boolean: return "a boolean";
      case toml::node_type::array: return "an array";
      case toml::node_type::table: return "a table";
      default: return "a date or time";
    }
  }

  static std::string value_text(const toml::node& node) {
    std::ostringstream out;
    node.visit([&](const auto& v) { out << v; });
    return out.str();
  }

  bool number_of(const toml::node& node, double& x) {
    if (const auto* i = node.as_integer()) return x = static_cast<double>(i->get()), true;
    if (const auto* f = node.as_floating_point()) return x = f->get(), true;
    return false;
  }

  void wrong_type(const SceneKey& k, const toml::node& node, const std::string& expected) {
    error(where(node.source()), k.name + " must be " + expected + ", not " + type_name(node) + " (" + value_text(node) + ")");
  }

  void out_of_range(const SceneKey& k, const toml::node& node, double x) {
    char value[64];
    std::snprintf(value, sizeof value, "%.10g", x);
    error(where(node.source()), k.name + " = " + value + " is out of range; allowed: " + k.range_text() +
                                    (k.unit.empty() ? "" : " " + k.unit));
  }

  void read_value(const SceneKey& k, const toml::node& node) {
    std::vector<double> numbers;
    std::vector<std::string> texts;
    switch (k.kind) {
      case KeyKind::integer: {
        const auto* i = node.as_integer();
        if (!i) return wrong_type(k, node, "an integer");
        const double x = static_cast<double>(i->get());
        if (!k.in_range(x)) return out_of_range(k, node, x);
        numbers.push_back(x);
        break;
      }
      case KeyKind::number: {
        double x;
        if (!number_of(node, x)) return wrong_type(k, node, "a number");
        if (!k.in_range(x)) return out_of_range(k, node, x);
        numbers.push_back(x);
        break;
      }
      case KeyKind::boolean: {
        const auto* b = node.as_boolean();
        if (!b) return wrong_type(k, node, "true or false");
        numbers.push_back(b->get() ? 1.0 : 0.0);
        break;
      }
      case KeyKind::text: {
        const auto* s = node.as_string();
        if (!s) return wrong_type(k, node, "a string");
        if (!check_choice(k, node, s->get())) return;
        texts.push_back(s->get());
        break;
      }
      case KeyKind::path:
      case KeyKind::folder: {
        const auto* s = node.as_string();
        if (!s) return wrong_type(k, node, "a string (a path)");
        if (s->get().empty()) return error(where(node.source()), k.name + " is an empty path");
        fs::path p = fs::path(s->get());
        if (p.is_relative()) p = file_.parent_path() / p;
        p = p.lexically_normal();
        std::error_code ec;
        if (k.kind == KeyKind::path) {
          if (!fs::exists(p, ec))
            return error(where(node.source()), k.name + ": no such file " + p.string() +
                                                    " (relative paths start at the scene file's folder)");
          if (fs::is_directory(p, ec))
            return error(where(node.source()), k.name + ": " + p.string() + " is a folder; name a file");
        } else if (fs::exists(p, ec) && !fs::is_directory(p, ec)) {
          return error(where(node.source()), k.name + ": " + p.string() + " exists and is not a folder");
        }
        texts.push_back(p.string());
        break;
      }
      case KeyKind::vector3:
      case KeyKind::pair:
      case KeyKind::point2: {
        const auto* a = node.as_array();
        const std::size_t n = k.kind == KeyKind::vector3 ? 3 : 2;
        const std::string expected = k.kind == KeyKind::vector3 ? "an array of 3 numbers [x, y, z]"
                                     : k.kind == KeyKind::pair  ? "an array [lo, hi] of 2 numbers"
                                                                : "a chart point [x, y] of 2 numbers";
        if (!a || a->size() != n) return wrong_type(k, node, expected);
        for (const toml::node& e : *a) {
          double x;
          if (!number_of(e, x)) return wrong_type(k, node, expected);
          if (!std::isfinite(x)) return error(where(node.source()), k.name + " has a non-finite component");
          if (k.kind == KeyKind::pair && !k.in_range(x)) return out_of_range(k, node, x);
          numbers.push_back(x);
        }
        if (k.kind == KeyKind::pair && numbers[0] > numbers[1])
          return error(where(node.source()), k.name + " = " + value_text(node) + " has lo > hi; write [lo, hi]");
        if (k.kind == KeyKind::vector3 && Vec3(numbers[0], numbers[1], numbers[2]).norm() == 0.0)
          return error(where(node.source()), k.name + " must be a non-zero direction");
        if (k.kind == KeyKind::vector3) scene_.directions_as_written[k.name] = Vec3(numbers[0], numbers[1], numbers[2]);
        if (k.kind == KeyKind::point2 && numbers[0] * numbers[0] + numbers[1] * numbers[1] > 1.0 + 1e-12) {
          char point[64];
          std::snprintf(point, sizeof point, "[%g, %g]", numbers[0], numbers[1]);
          return error(where(node.source()),
                       k.name + " = " + point + " lies outside the chart's unit disk; give a point with x² + y² ≤ 1");
        }
        break;
      }
      case KeyKind::text_list: {
        const auto* a = node.as_array();
        if (!a) return wrong_type(k, node, "an array of strings");
        for (const toml::node& e : *a) {
          const auto* s = e.as_string();
          if (!s) return wrong_type(k, node, "an array of strings");
          if (!check_choice(k, e, s->get())) return;
          if (std::find(texts.begin(), texts.end(), s->get()) != texts.end())
            return error(where(e.source()), k.name + " lists \"" + s->get() + "\" twice");
          texts.push_back(s->get());
        }
        break;
      }
    }
    k.store(scene_, numbers, texts);
  }

  bool check_choice(const SceneKey& k, const toml::node& node, const std::string& value) {
    if (k.choices.empty() || std::find(k.choices.begin(), k.choices.end(), value) != k.choices.end()) return true;
    std::string allowed;
    for (const std::string& c : k.choices) allowed += (allowed.empty() ? "\"" : ", \"") + c + "\"";
    std::string message = k.name + " = \"" + value + "\" is not allowed; choose one of " + allowed;
    if (k.name == "format") message += " (this build reads " + std::string(kSceneFormat) + " scenes)";
    error(where(node.source()), message);
    return false;
  }

  Where location_of(const std::string& key) const {
    const auto it = scene_.locations.find(key);
    return it == scene_.locations.end() ? Where{0, 0} : Where{it->second.line, it->second.column};
  }

  // Rules that involve several keys.
  void check_consistency() {
    const SceneWeights& w = scene_.guides.weights;
    const double sum = w.direction + w.similarity + w.boundary + w.density;
    if (std::fabs(sum - 1.0) > 1e-9) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "guides.weights must sum to 1 (paper eq. 6), but direction %.6g + similarity %.6g + "
                    "boundary %.6g + density %.6g = %.9g",
                    w.direction, w.similarity, w.boundary, w.density, sum);
      error(location_of("guides.weights.direction"), text);
    }
    if (scene_.effects.density == DensityModel::none && w.density != 0.0)
      error(location_of("guides.weights.density"),
            "guides.weights.density is non-zero but effects.density = \"none\"; declare a density model or set it to 0");
    if (scene_.effects.density != DensityModel::none && w.density == 0.0)
      error(location_of("effects.density"),
            "a density model is declared but guides.weights.density = 0, so it would have no effect; give it a weight");
    for (const std::string name : {"density", "tilt", "length"}) {
      const std::optional<fs::path>& p =
          name == "density" ? scene_.maps.density : name == "tilt" ? scene_.maps.tilt : scene_.maps.length;
      if (scene_.effects.uses_map(name) && !p)
        error(location_of("effects.maps"), "effects.maps uses the " + name + " map but [maps] has no " +
                                               name + " path; add maps." + name + " = \"file.png\"");
      if (!scene_.effects.uses_map(name) && p)
        error(location_of("maps." + name), "maps." + name + " is given but effects.maps does not list \"" +
                                                            name + "\"; add it there or remove the path");
    }
    if (scene_.guides.point_forces > 0 && (scene_.effects.gravity || scene_.effects.contact))
      error(location_of("guides.point_forces"),
            "guides.point_forces act on weightless hair (solved by single shooting), but effects." +
                std::string(scene_.effects.gravity ? "gravity" : "contact") +
                " is declared; set guides.point_forces = 0 or leave the effect out");
    if (scene_.hair.rest_shape == "flow" && scene_.hair.flow == "local")
      error(location_of("hair.rest_shape"),
            "hair.rest_shape = \"flow\" styles the hair along the growth field, but hair.flow = \"local\" makes none; "
            "set hair.flow = \"field\" or \"relief\", or hair.rest_shape = \"straight\"");
    const Vec3& down = scene_.units.down;
    const Vec3& front = scene_.units.front;
    if (down.cross(front).norm() < 0.1)
      error(location_of("units.front"), "units.front must not be parallel to units.down");
  }

  fs::path file_;
  std::vector<std::string> lines_;
  std::set<std::string> names_, tables_;
  Scene scene_;
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace

Scene parse_scene_text(const std::string& text, const fs::path& file) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  return SceneParser(text, absolute).parse(text);
}

Scene parse_scene(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(file.string(), "no such scene file");
  if (fs::is_directory(file, ec)) throw InputError(file.string(), "is a folder; name a scene .toml file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "cannot be read (permissions?)");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_scene_text(text, file);
}

}  // namespace hairfit
