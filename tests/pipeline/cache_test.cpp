// The stage cache: keys follow exactly what each stage reads (a changed key misses that stage and
// the ones after it, and nothing else), a cached run equals a cold one byte for byte, and a
// corrupt or foreign entry is detected and recomputed.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <regex>

#include "pipeline/pipeline.h"
#include "pipeline/stage_cache.h"
#include "pipeline/stage_plan.h"
#include "spec/scene_keys.h"
#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

const Scene& smoke_scene() {
  static const Scene scene = parse_scene(source_path("fixtures/smoke/scene.toml"));
  return scene;
}
const Inputs& smoke_inputs() {
  static const Inputs inputs = load_inputs(smoke_scene());
  return inputs;
}

// The stages whose keys differ between the smoke scene and the scene after `change`.
std::vector<std::string> missed(const std::function<void(Scene&)>& change, const Scene& base = smoke_scene()) {
  Scene scene = base;
  change(scene);
  const std::map<std::string, std::string> before = stage_keys(base, smoke_inputs()), after = stage_keys(scene, smoke_inputs());
  std::vector<std::string> out;
  for (const std::string& name : stage_names())
    if (after.count(name) && (!before.count(name) || before.at(name) != after.at(name))) out.push_back(name);
  return out;
}

using Names = std::vector<std::string>;

std::string fresh_folder(const std::string& name) {
  const fs::path path = hairfit::testing::scratch_path("cache-" + name);
  fs::remove_all(path);
  return path.string();
}

// status of every stage in report.json, in order ("fields=cached chart=computed ...").
std::string statuses(const std::string& out_dir) {
  const std::string report = read_all(out_dir + "/report.json");
  std::string all;
  const std::regex stage("\"([a-z]+)\": \\{\\s*\"status\": \"([a-z]+)\"");
  for (auto it = std::sregex_iterator(report.begin(), report.end(), stage); it != std::sregex_iterator(); ++it)
    all += (*it)[1].str() + "=" + (*it)[2].str() + " ";
  return all;
}

// report.json without what legitimately differs between runs: times, memory, threads, cache status.
std::string report_without_run_figures(const std::string& out_dir) {
  const std::string report = read_all(out_dir + "/report.json");
  return std::regex_replace(report, std::regex("\"(seconds|cpu_seconds|peak_memory_bytes|status|threads)\": [^,\\n]+"), "");
}

}  // namespace

TEST_CASE("every stage configures for every combination of effects, and computes with the options it is keyed on") {
  Scene scene = smoke_scene();
  for (bool on : {false, true}) {
    scene.effects.gravity = scene.effects.contact = scene.effects.cutting = scene.effects.winding = on;
    for (DensityModel m : {DensityModel::none, DensityModel::binary, DensityModel::continuous}) {
      scene.effects.density = m;
      const std::vector<ConfiguredStage> stages = configure_stages(scene);
      REQUIRE(stages.size() == (m == DensityModel::none ? 6u : 7u));
      for (const ConfiguredStage& s : stages) {
        CHECK(!s.options.empty());
        CHECK(s.compute);
      }
    }
  }
}

TEST_CASE("the keyed options are values after defaults, exact to the last bit") {
  Scene scene = smoke_scene();
  // A value that differs from the default only in its last digits is another key.
  scene.guides.tolerance = 1e-6 * (1 + 1e-15);
  CHECK(missed([&](Scene& s) { s = scene; }) == Names{"guides", "strands"});
  // Writing a default out changes nothing: the scene after defaults is what is keyed.
  CHECK(missed([](Scene& s) { s.guides.tolerance = Scene().guides.tolerance; }).empty());
}

// A test per stage: a key the stage reads misses it and every later stage, and nothing earlier.
TEST_CASE("fields: a new voxel size misses the fields and every stage that reads them") {
  // The chart and the roots read the scalp mesh, not its field.
  CHECK(missed([](Scene& s) { s.fields.voxel = 0.4; }) == Names{"fields", "preguides", "guides", "strands"});
}

TEST_CASE("chart: a new front direction misses the chart and what follows, not the fields") {
  CHECK(missed([](Scene& s) { s.units.front = Vec3(0.1, 0, 1).normalized(); }) ==
        Names{"chart", "roots", "preguides", "guides", "strands"});
}

TEST_CASE("roots: a new hair density or seed misses roots and what follows") {
  CHECK(missed([](Scene& s) { s.hair.density = 2.0; }) == Names{"roots", "preguides", "guides", "strands"});
  CHECK(missed([](Scene& s) { s.seed = 8; }) == Names{"roots", "preguides", "guides", "strands"});
}

TEST_CASE("roots: tilting toward the thicker layer makes the roots read the volume's field") {
  // "down" is the default: writing it out misses nothing, so existing scenes keep their caches.
  CHECK(missed([](Scene& s) { s.hair.tilt_toward = "down"; }).empty());
  CHECK(missed([](Scene& s) { s.hair.tilt_toward = "thicker"; }) == Names{"roots", "preguides", "guides", "strands"});
  Scene thicker = smoke_scene();
  thicker.hair.tilt_toward = "thicker";
  CHECK(missed([](Scene& s) { s.fields.voxel = 0.4; }, thicker) == Names{"fields", "roots", "preguides", "guides", "strands"});
}

TEST_CASE("preguides: a new load cap misses pre-guides and what follows") {
  CHECK(missed([](Scene& s) { s.preguides.max_load = 500; }) == Names{"preguides", "guides", "strands"});
}

TEST_CASE("guides: new weights miss only the guides and the strands") {
  CHECK(missed([](Scene& s) {
          s.guides.weights.direction = 0.5;
          s.guides.weights.boundary = 0.3;
        }) == Names{"guides", "strands"});
}

TEST_CASE("strands: more points per fibre misses only the strands") {
  CHECK(missed([](Scene& s) { s.strands.points = 20; }) == Names{"strands"});
  CHECK(missed([](Scene& s) { s.hair.cross_section = 2e-5; }) == Names{"preguides", "guides", "strands"});
}

TEST_CASE("density: with a model, its voxel misses the guides (they batch against it) and the density stage") {
  Scene with = smoke_scene();
  with.effects.density = DensityModel::continuous;
  with.guides.weights = SceneWeights{0.3, 0.2, 0.3, 0.2};
  CHECK(missed([](Scene& s) { s.density.voxel = 0.5; }, with) == Names{"guides", "strands", "density"});
  CHECK(missed([](Scene& s) { s.density.strength = 2; }, with) == Names{"guides", "strands", "density"});
}

TEST_CASE("what no stage reads misses nothing: outputs, and the keys of effects that are off") {
  CHECK(missed([](Scene& s) { s.output.strands = {"ply"}; }).empty());
  CHECK(missed([](Scene& s) { s.output.renders = {"side", "top"}; }).empty());
  CHECK(missed([](Scene& s) { s.rod.gravity = 500; }).empty());         // gravity is off
  CHECK(missed([](Scene& s) { s.hair.mass_density = 2; }).empty());     // gravity is off
  CHECK(missed([](Scene& s) { s.strands.turns = 3; }).empty());         // winding is off
  CHECK(missed([](Scene& s) { s.density.voxel = 0.5; }).empty());       // no density model
  CHECK(missed([](Scene& s) { s.hair.length_range = {1, 2}; }).empty());  // no length map
  // ... and switching the effect on misses what it feeds.
  CHECK(missed([](Scene& s) { s.effects.gravity = true; }) == Names{"preguides", "guides", "strands"});
  CHECK(missed([](Scene& s) { s.effects.winding = true; }) == Names{"strands"});
}

TEST_CASE("the scene text's form does not matter, the input files' content does") {
  const fs::path dir = fresh_folder("scenes");
  fs::create_directories(dir / "meshes");
  fs::copy_file(source_path("fixtures/meshes/scalp.obj"), dir / "meshes/scalp.obj");
  fs::copy_file(source_path("fixtures/meshes/spheroid_volume.obj"), dir / "meshes/volume.obj");
  fs::copy_file(source_path("fixtures/maps/tilt.png"), dir / "tilt.png");
  auto keys = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    const Scene scene = parse_scene(dir / name);
    return stage_keys(scene, load_inputs(scene));
  };
  const std::string plain =
      "format = \"hairfit-scene/1\"\nseed = 7\n[inputs]\nscalp = \"meshes/scalp.obj\"\nvolume = \"meshes/volume.obj\"\n"
      "[effects]\nmaps = [\"tilt\"]\ncutting = true\n[maps]\ntilt = \"tilt.png\"\n[hair]\ndensity = 1.5\nlength = 15\n"
      "tilt_range = [0, 75]\n[fields]\nvoxel = 0.5\nband = 3\n[roots]\nguides = 40\npreguide_spacing = 3.0\n[rod]\n"
      "segments = 24\n[guides]\nsamples = 8\n[strands]\npoints = 12\n";
  // Reordered tables, comments, other number spellings, a default written out, inline tables.
  const std::string reformatted =
      "# the same scene\nformat = \"hairfit-scene/1\"\nseed = 7\nstrands = { points = 12 }\n[guides]\nsamples = 8  # few\n"
      "max_iterations = 100\n[rod]\nsegments = 24\n[roots]\npreguide_spacing = 3\nguides = 40\n[fields]\nband = 3.0\n"
      "voxel = 5e-1\n[hair]\ntilt_range = [0.0, 75.0]\nlength = 15.0\ndensity = 1.50\n[maps]\ntilt = \"./tilt.png\"\n"
      "[effects]\ncutting = true\nmaps = [\"tilt\"]\n[inputs]\nvolume = \"meshes/../meshes/volume.obj\"\nscalp = \"meshes/scalp.obj\"\n";
  const auto base = keys("a.toml", plain);
  CHECK(keys("b.toml", reformatted) == base);
  // The same meshes under other names: still the same keys.
  fs::copy_file(dir / "meshes/volume.obj", dir / "other-volume.obj");
  std::string renamed = plain;
  renamed.replace(renamed.find("meshes/volume.obj"), 17, "other-volume.obj");
  CHECK(keys("c.toml", renamed) == base);
  // One vertex moved in the volume: the fields miss (and all that reads them), the chart does not.
  std::string obj = read_all((dir / "other-volume.obj").string());
  const std::size_t v = obj.find("\nv ");
  obj.insert(obj.find('.', v + 3) + 1, "1");  // its first coordinate moves by about 0.05 cm
  std::ofstream(dir / "other-volume.obj") << obj;
  const auto changed = keys("c.toml", renamed);
  CHECK(changed.at("fields") != base.at("fields"));
  CHECK(changed.at("chart") == base.at("chart"));
  CHECK(changed.at("roots") == base.at("roots"));
  CHECK(changed.at("preguides") != base.at("preguides"));
  fs::remove_all(dir);
}

TEST_CASE("a run hits the cache where the keys say so, and a cached run equals a cold one byte for byte") {
  const std::string cache = fresh_folder("cache"), cold = fresh_folder("cold"), warm = fresh_folder("warm"),
                    again = fresh_folder("again");
  const std::string scene = source_path("fixtures/smoke/scene.toml");
  REQUIRE(run_hairfit("run " + scene + " --no-cache --threads 2 --out " + cold).exit_code == 0);
  REQUIRE(run_hairfit("run " + scene + " --cache " + cache + " --threads 2 --out " + warm).exit_code == 0);
  CHECK(statuses(warm) == "fields=computed chart=computed roots=computed preguides=computed guides=computed strands=computed ");
  const auto r = run_hairfit("run " + scene + " --cache " + cache + " --threads 1 --out " + again);
  REQUIRE(r.exit_code == 0);
  // The strands are rebuilt from the cached guides (stage_plan.cpp says why).
  CHECK(statuses(again) == "fields=cached chart=cached roots=cached preguides=cached guides=cached strands=computed ");
  CHECK(r.err.find("guides: cached") != std::string::npos);  // plain progress lines: stderr is no terminal
  // Every output file and every digest and figure of the report, cached against cold.
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(cold)) {
    if (!e.is_regular_file() || e.path().filename() == "report.json") continue;
    const std::string relative = fs::relative(e.path(), cold).string();
    INFO(relative);
    CHECK(read_all(again + "/" + relative) == read_all(e.path().string()));
  }
  CHECK(report_without_run_figures(again) == report_without_run_figures(cold));

  // New weights in a copy of the scene: only the guides and strands are computed again.
  const fs::path copy = fs::path(cold) / "scene.toml";
  std::string text = read_all(scene);
  for (const char* path : {"../meshes/", "../maps/"}) text = std::regex_replace(text, std::regex(path), source_path("fixtures/") + (path + 3));
  text = std::regex_replace(text, std::regex("\\[guides\\]\nsamples = 8\n"),
                            "[guides]\nsamples = 8\n[guides.weights]\ndirection = 0.5\nsimilarity = 0.2\nboundary = 0.3\n");
  std::ofstream(copy) << text;
  REQUIRE(run_hairfit("run " + copy.string() + " --cache " + cache + " --quiet --out " + warm).exit_code == 0);
  CHECK(statuses(warm) == "fields=cached chart=cached roots=cached preguides=cached guides=computed strands=computed ");
  for (const std::string& dir : {cache, cold, warm, again}) fs::remove_all(dir);
}

TEST_CASE("a corrupt, truncated or foreign cache entry is detected, reported and recomputed") {
  const std::string cache = fresh_folder("bad-cache"), cold = fresh_folder("bad-cold"), out = fresh_folder("bad-out");
  const std::string scene = source_path("fixtures/smoke/scene.toml");
  REQUIRE(run_hairfit("run " + scene + " --cache " + cache + " --until guides --out " + cold).exit_code == 0);
  const std::map<std::string, std::string> keys = stage_keys(smoke_scene(), smoke_inputs());
  const StageCache store(cache);
  const fs::path guides = store.entry_path("guides", keys.at("guides"));
  const fs::path chart = store.entry_path("chart", keys.at("chart"));
  REQUIRE(fs::exists(guides));
  const std::string good = read_all(guides.string());

  auto run_and_check = [&](const std::string& what) {
    INFO(what);
    const auto r = run_hairfit("run " + scene + " --cache " + cache + " --until guides --out " + out);
    REQUIRE(r.exit_code == 0);
    CHECK(statuses(out) == "fields=cached chart=cached roots=cached preguides=cached guides=computed ");
    CHECK(r.err.find("recomputing guides") != std::string::npos);
    CHECK(r.err.find(what) != std::string::npos);
    CHECK(read_all(out + "/guides.csv") == read_all(cold + "/guides.csv"));
    CHECK(read_all(guides.string()) == good);  // and the entry is whole again
  };
  std::string bytes = good;
  bytes[bytes.size() / 2] ^= 0x20;  // one flipped bit in the payload
  std::ofstream(guides, std::ios::binary) << bytes;
  run_and_check("checksum");
  std::ofstream(guides, std::ios::binary) << good.substr(0, good.size() - 100);
  run_and_check("header says");
  fs::copy_file(chart, guides, fs::copy_options::overwrite_existing);  // another stage's entry under this name
  run_and_check("another key");
  bytes = good;
  bytes[8] = 99;  // another format version
  std::ofstream(guides, std::ios::binary) << bytes;
  run_and_check("cache format 99");
  std::ofstream(guides, std::ios::binary) << "not a cache entry at all";
  run_and_check("not a hairfit cache entry");
  for (const std::string& dir : {cache, cold, out}) fs::remove_all(dir);
}

namespace {

// A value of `key` other than the scene's, within the key's range; nullopt for keys that name
// files or folders, or lists (their changes are tested through content and by name above).
std::optional<Scene> with_key_changed(const Scene& base, const SceneKey& key) {
  Scene scene = base;
  const std::string shown = key.show(base);
  auto number = [&](double v) {
    for (double candidate : {v * 1.25 + 0.5, v * 0.8, v - 0.5, v + 1.0, (key.lo + key.hi) / 2})
      if (candidate != v && key.in_range(candidate) && std::isfinite(candidate))
        return key.kind == KeyKind::integer ? std::round(candidate) : candidate;
    return v;
  };
  switch (key.kind) {
    case KeyKind::integer:
    case KeyKind::number: {
      const double v = std::stod(shown);
      const double changed = number(v);
      if (changed == v) return std::nullopt;
      key.store(scene, {changed}, {});
      return scene;
    }
    case KeyKind::boolean:
      key.store(scene, {shown == "true" ? 0.0 : 1.0}, {});
      return scene;
    case KeyKind::text:
      for (const std::string& choice : key.choices)
        if ("\"" + choice + "\"" != shown) {
          key.store(scene, {}, {choice});
          return scene;
        }
      return std::nullopt;
    case KeyKind::vector3: {
      double x, y, z;
      if (std::sscanf(shown.c_str(), "[%lf, %lf, %lf]", &x, &y, &z) != 3) return std::nullopt;
      key.store(scene, {x + 0.1, y + 0.2, z - 0.1}, {});
      return scene;
    }
    case KeyKind::pair:
    case KeyKind::point2: {
      double a, b;
      if (std::sscanf(shown.c_str(), "[%lf, %lf]", &a, &b) != 2) return std::nullopt;
      const double lo = key.kind == KeyKind::point2 ? a * 0.5 + 0.1 : number(a);
      const double hi = key.kind == KeyKind::point2 ? b * 0.5 - 0.1 : std::max(lo, number(b));
      key.store(scene, {lo, hi}, {});
      return scene;
    }
    default:
      return std::nullopt;
  }
}

}  // namespace

// The cache keys hash the stages' options (options_codec.h): a scene key whose value reaches a
// stage's options but not their encoding would leave that stage's key unchanged, and a cached run
// would return a stale value. With every effect on, changing any key must miss some stage, apart
// from the keys no stage reads.
TEST_CASE("with every effect on, every scene key a stage reads changes a stage's cache key") {
  Scene all = smoke_scene();
  all.effects.gravity = all.effects.contact = all.effects.cutting = all.effects.winding = true;
  all.effects.density = DensityModel::continuous;
  all.hair.flow = "relief";  // reads the growth field's keys and the relief radius
  all.hair.tilt_toward = "hanging";  // reads the hang's margin too
  all.hair.whorl_radius = 3.0;
  all.hair.parting_radius = 1.0;
  all.preguides.immersion = "layer";
  all.strands.contain = 0.2;
  // Keys that name no stage's input: the scene's format and preset (a preset only sets other
  // keys), the input files' unit (coordinates are keyed by content), the range of a length map
  // this scene has not (the smoke inputs load a tilt map only); and below, the files read (keyed
  // by content) and where and what is written.
  const std::vector<std::string> unread = {"format", "preset", "units.length", "hair.length_range"};
  int changed = 0;
  for (const SceneKey& key : scene_keys()) {
    if (key.name.rfind("output.", 0) == 0 || key.name.rfind("inputs.", 0) == 0 || key.name.rfind("maps.", 0) == 0) continue;
    if (std::find(unread.begin(), unread.end(), key.name) != unread.end()) continue;
    const std::optional<Scene> scene = with_key_changed(all, key);
    if (!scene) continue;
    ++changed;
    CHECK_MESSAGE(!missed([&](Scene& s) { s = *scene; }, all).empty(), key.name << " changes no stage's cache key");
  }
  CHECK(changed > 60);
}

TEST_CASE("hair derived from the shell makes the roots read the volume's field") {
  Scene shell = smoke_scene();
  shell.hair.from_shell = true;  // as a scene without hair.length and hair.tilt parses
  CHECK(missed([](Scene& s) { s.fields.voxel = 0.4; }, shell) == Names{"fields", "roots", "preguides", "guides", "strands"});
}
