#include <doctest/doctest.h>

#include <fstream>
#include <regex>
#include <set>

#include "../support/run_hairfit.h"
#include "spec/scene.h"
#include "spec/scene_keys.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;

namespace {

const std::string kInputs =
    "format = \"hairfit-scene/1\"\n"
    "inputs = { scalp = \"" + source_path("fixtures/meshes/scalp.obj") + "\", volume = \"" +
    source_path("fixtures/meshes/spheroid_volume.obj") + "\" }\n";

Scene parse(const std::string& extra) { return parse_scene_text(kInputs + extra, "/tmp/scene.toml"); }

std::string first_error(const std::string& extra) {
  try {
    parse(extra);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a minimal scene takes every documented default") {
  const Scene s = parse("");
  CHECK(s.seed == 1);
  CHECK(s.hair.density == 200.0);
  CHECK(s.guides.weights.direction + s.guides.weights.similarity + s.guides.weights.boundary == doctest::Approx(1.0));
  CHECK(s.effects.names().empty());
  CHECK(s.output.dir == std::filesystem::path("/tmp/out"));
  CHECK(s.inputs.scalp.is_absolute());
}

TEST_CASE("values are read, converted and remembered with their line") {
  const Scene s = parse("seed = 42\n[units]\nlength = \"mm\"\ndown = [0, -2, 0]\n[fields]\nvoxel = 1\n"
                        "[effects]\ndensity = \"continuous\"\ngravity = true\n"
                        "[guides.weights]\ndirection = 0.3\nsimilarity = 0.2\nboundary = 0.4\ndensity = 0.1\n");
  CHECK(s.seed == 42);
  CHECK(s.units.to_cm() == 0.1);
  CHECK(s.units.down.isApprox(Vec3(0, -1, 0)));  // normalised
  CHECK(s.fields.voxel == 1.0);                  // an integer is accepted for a number
  CHECK(s.effects.density == DensityModel::continuous);
  CHECK(s.effects.names() == std::vector<std::string>{"gravity", "density:continuous"});
  REQUIRE(s.locations.count("fields.voxel"));
  CHECK(s.locations.at("fields.voxel").line == 8);
  CHECK(s.locations.at("fields.voxel").column == 9);
}

TEST_CASE("unknown and misspelt keys name the line and suggest the right key") {
  CHECK(first_error("[guides]\nsampels = 8\n").find("/tmp/scene.toml:4:1: error: unknown key \"sampels\" in [guides] "
                                                     "(did you mean \"guides.samples\"?)") != std::string::npos);
  CHECK(first_error("[guides.weight]\ndirection = 1\n").find("did you mean \"guides.weights\"") != std::string::npos);
  CHECK(first_error("voxel = 1\n").find("(did you mean \"density.voxel\" or \"fields.voxel\"?)") != std::string::npos);
  CHECK(first_error("[colour]\nred = 1\n").find("unknown key \"colour\" at the top level") != std::string::npos);
}

TEST_CASE("every problem in a file is reported, not only the first") {
  const std::string e = first_error("[fields]\nvoxel = 0\nband = \"wide\"\nmargn = 1\n");
  CHECK(e.find("fields.voxel = 0 is out of range; allowed: (0, 100] cm") != std::string::npos);
  CHECK(e.find("fields.band must be a number, not a string") != std::string::npos);
  CHECK(e.find("did you mean \"fields.margin\"") != std::string::npos);
}

TEST_CASE("ranges, choices, pairs and directions are checked") {
  CHECK(first_error("[hair]\ntilt = 91\n").find("hair.tilt = 91 is out of range; allowed: [0, 90] degrees") != std::string::npos);
  CHECK(first_error("[rod]\nintegrator = \"euler\"\n").find("choose one of \"rk2\", \"rk4\"") != std::string::npos);
  CHECK(first_error("[hair]\nlength_range = [30, 10]\n").find("lo > hi") != std::string::npos);
  CHECK(first_error("[units]\ndown = [0, 0, 0]\n").find("non-zero direction") != std::string::npos);
  CHECK(first_error("[units]\nfront = [0, -3, 0]\n").find("must not be parallel") != std::string::npos);
  CHECK(first_error("[output]\nstrands = [\"obj\", \"obj\"]\n").find("lists \"obj\" twice") != std::string::npos);
  CHECK(first_error("[roots]\nguides = 2.5\n").find("roots.guides must be an integer") != std::string::npos);
  CHECK(first_error("format = \"hairfit-scene/9\"\n").find("error") != std::string::npos);
}

TEST_CASE("weights must sum to 1 and the error shows the sum") {
  const std::string e = first_error("[guides.weights]\ndirection = 0.5\n");
  CHECK(e.find("must sum to 1 (paper eq. 6)") != std::string::npos);
  CHECK(e.find("= 1.1") != std::string::npos);
}

TEST_CASE("maps and effects must agree") {
  const std::string map = source_path("fixtures/maps/tilt.png");
  CHECK(first_error("[maps]\ntilt = \"" + map + "\"\n").find("effects.maps does not list \"tilt\"") != std::string::npos);
  CHECK(first_error("[effects]\nmaps = [\"tilt\"]\n").find("[maps] has no tilt path") != std::string::npos);
  CHECK_NOTHROW(parse("[effects]\nmaps = [\"tilt\"]\n[maps]\ntilt = \"" + map + "\"\n"));
  // Hair styled along the growth field needs one.
  CHECK(first_error("[hair]\nlength = 10\nrest_shape = \"flow\"\n").find("hair.flow = \"local\" makes none") !=
        std::string::npos);
  CHECK_NOTHROW(parse("[hair]\nlength = 10\nflow = \"field\"\nrest_shape = \"flow\"\n"));
}

TEST_CASE("the reference page documents exactly the keys the parser accepts") {
  const std::string page = read_all(source_path("spec/reference.md"));
  const std::size_t begin = page.find("<!-- keys:begin -->\n"), end = page.find("<!-- keys:end -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  const std::string table = page.substr(begin + 20, end - begin - 20);
  // Byte equality keeps types, defaults and ranges in sync too; regenerate with `hairfit scene-keys`.
  CHECK(table == scene_keys_markdown());
  std::set<std::string> documented;
  const std::regex row("^\\| `([a-z_.]+)` \\|");
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, row)) documented.insert(m[1]);
  }
  std::set<std::string> accepted;
  for (const SceneKey& k : scene_keys()) accepted.insert(k.name);
  CHECK(documented == accepted);
}

TEST_CASE("the commented example scene sets every key and is valid") {
  const Scene s = parse_scene(source_path("spec/example.toml"));
  for (const SceneKey& k : scene_keys()) {
    INFO(k.name);
    CHECK(s.locations.count(k.name) == 1);
  }
}

TEST_CASE("every shipped scene validates") {
  for (const char* scene : {"fixtures/spheroid/scene.toml", "fixtures/straight/scene.toml", "fixtures/smoke/scene.toml",
                            "spec/example.toml"}) {
    INFO(scene);
    const auto r = run_hairfit("validate " + source_path(scene));
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("valid scene") != std::string::npos);
    CHECK(r.out.find("a topological disk") != std::string::npos);
  }
}

TEST_CASE("the bad-scene corpus: exit 2, the file, the line and what to do") {
  struct Case {
    const char* scene;
    std::string expected;  // must appear in stderr, which must start with the file concerned
    const char* file;      // the file the message starts with (relative to tests/corpus)
  };
  const Case cases[] = {
      {"syntax_error", ":9:8: error: TOML syntax error", "scenes/syntax_error.toml"},
      {"unknown_key", ":9:1: error: unknown key \"resolution\" in [fields]", "scenes/unknown_key.toml"},
      {"misspelt_key", ":9:1: error: unknown key \"similarty\" in [guides.weights] (did you mean \"guides.weights.similarity\"?)",
       "scenes/misspelt_key.toml"},
      {"wrong_type", ":8:10: error: roots.guides must be an integer, not a string", "scenes/wrong_type.toml"},
      {"out_of_range", ":8:9: error: fields.voxel = -0.5 is out of range; allowed: (0, 100] cm", "scenes/out_of_range.toml"},
      {"weights_sum", ":8:13: error: guides.weights must sum to 1 (paper eq. 6), but direction 0.5 + similarity 0.3 + "
                      "boundary 0.4 + density 0 = 1.2",
       "scenes/weights_sum.toml"},
      {"missing_mesh", ":4:9: error: inputs.scalp: no such file", "scenes/missing_mesh.toml"},
      {"mesh_nan", ":3:5: error: vertex 3 has a non-finite or unreadable coordinate \"nan\"", "data/nan.obj"},
      {"scalp_closed", ": error: the scalp must be a topological disk (one piece, one boundary loop), but it is closed",
       "data/closed.obj"},
      {"scalp_two_loops", ": error: the scalp must be a topological disk (one piece, one boundary loop), but it has 2 "
                          "boundary loops",
       "data/annulus.obj"},
      {"corrupt_png", ": error: is a corrupt PNG", "data/corrupt.png"},
      {"missing_format", ": error: required key format is missing", "scenes/missing_format.toml"},
      {"density_without_weight", ":8:11: error: a density model is declared but guides.weights.density = 0",
       "scenes/density_without_weight.toml"},
  };
  for (const Case& c : cases) {
    INFO(c.scene);
    const std::string file = source_path(std::string("tests/corpus/") + c.file);
    const auto r = run_hairfit("validate " + source_path(std::string("tests/corpus/scenes/") + c.scene + ".toml"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.rfind(file, 0) == 0);
    CHECK(r.err.find(file + c.expected) != std::string::npos);
    CHECK(r.out.empty());
  }
}

TEST_CASE("run refuses bad input before writing anything") {
  const std::string out = hairfit::testing::scratch_path("refused-run").string();
  const auto r = run_hairfit("run " + source_path("tests/corpus/scenes/mesh_nan.toml") + " --out " + out);
  CHECK(r.exit_code == 2);
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("command-line misuse exits 2 with a usage line") {
  auto r = run_hairfit("frobnicate");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("unknown command \"frobnicate\"") != std::string::npos);
  r = run_hairfit("validate");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("usage: hairfit validate") != std::string::npos);
  r = run_hairfit("run " + source_path("fixtures/smoke/scene.toml") + " --thread 2");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("unknown option --thread") != std::string::npos);
  r = run_hairfit("--version");
  CHECK(r.exit_code == 0);
  CHECK(r.out.rfind("hairfit ", 0) == 0);
  CHECK(run_hairfit("--help").out.find("validate SCENE") != std::string::npos);
}

TEST_CASE("--until density without a density model is refused before anything is written") {
  const std::string out = hairfit::testing::scratch_path("refused-until").string();
  const auto r = run_hairfit("run " + source_path("fixtures/smoke/scene.toml") + " --until density --out " + out);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("declares no density model") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("an accuracy preset sets the knobs the scene leaves alone, and an explicit key wins") {
  const Scene plain = parse("");
  CHECK(plain.preset == "default");
  const Scene preview = parse("preset = \"preview\"\n[guides]\nsamples = 12\n");
  const Scene finest = parse("preset = \"final\"\n");
  for (const ScenePreset& p : scene_presets()) {
    CAPTURE(p.name);
    const Scene s = parse("preset = \"" + p.name + "\"\n");
    for (const auto& [key, value] : p.values) {
      CAPTURE(key);
      const SceneKey* k = nullptr;
      for (const SceneKey& candidate : scene_keys())
        if (candidate.name == key) k = &candidate;
      REQUIRE(k != nullptr);        // every preset value names a real key
      CHECK(k->in_range(value));    // and lies in its range
      CHECK(std::stod(k->show(s)) == value);
    }
  }
  CHECK(preview.guides.samples == 12);  // set in the file: the preset does not touch it
  CHECK(preview.rod.segments == 32);
  CHECK(finest.guides.samples == 64);
  CHECK(plain.rod.segments == Scene().rod.segments);
  CHECK(first_error("preset = \"fastest\"\n").find("preset") != std::string::npos);
}

TEST_CASE("the reference page's preset table is the one the parser applies") {
  const std::string page = read_all(source_path("spec/reference.md"));
  const std::string open = "<!-- presets:begin -->\n";
  const std::size_t begin = page.find(open), end = page.find("<!-- presets:end -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  // Regenerate with `hairfit scene-keys --presets`.
  CHECK(page.substr(begin + open.size(), end - begin - open.size()) == scene_presets_markdown());
}

TEST_CASE("hair from the shell takes the guides' interior point forces; weighted hair and declared hair do not") {
  const Scene shell = parse("");  // no hair.length, no hair.tilt: hair from the shell
  CHECK(shell.hair.from_shell);
  CHECK(shell.guides.point_forces == 3);
  CHECK(shell.guides.samples == 32);
  CHECK(shell.guides.outside_penalty == 10.0);
  CHECK(shell.guides.boundary_width == 0.3);
  // An accuracy preset keeps its own samples; a key the file sets wins.
  CHECK(parse("preset = \"final\"\n").guides.samples == 64);
  CHECK(parse("[guides]\npoint_forces = 1\nsamples = 12\n").guides.point_forces == 1);
  // Weighted hair is solved by multiple shooting, which carries no point forces.
  CHECK(parse("[effects]\ngravity = true\n").guides.point_forces == 0);
  CHECK(parse("[effects]\ncontact = true\n").guides.point_forces == 0);
  // Declared hair keeps the paper's six loads and the other defaults.
  const Scene declared = parse("[hair]\nlength = 10\n");
  CHECK(declared.guides.point_forces == 0);
  CHECK(declared.guides.samples == 16);
  CHECK(declared.guides.outside_penalty == 3.0);
  // Asked for with gravity, they are refused, naming the key and the fix.
  const std::string e = first_error("[effects]\ngravity = true\n[guides]\npoint_forces = 2\n");
  CHECK(e.find("guides.point_forces act on weightless hair") != std::string::npos);
  CHECK(e.find("set guides.point_forces = 0") != std::string::npos);
  CHECK(first_error("[guides]\npoint_forces = 4\n").find("guides.point_forces = 4 is out of range; allowed: [0, 3]") !=
        std::string::npos);
}

TEST_CASE("hanging hair is a style the shell's hair keeps: the length and tilt are still derived") {
  const Scene hanging = parse("[hair]\ntilt_toward = \"hanging\"\n");
  CHECK(hanging.hair.tilt_toward == "hanging");
  CHECK(hanging.hair.from_shell);
  CHECK(hanging.preguides.immersion == "layer");  // hanging roots take the tip construction root by root
  CHECK(parse("").hair.tilt_toward == "thicker");
  // The shell's hair is styled along its path (along its fall where it hangs, guides/fall_rest.h);
  // declared hair stays straight.
  CHECK(parse("").hair.rest_shape == "flow");
  CHECK(hanging.hair.rest_shape == "flow");
  CHECK(parse("[hair]\nlength = 10\n").hair.rest_shape == "straight");
  CHECK(parse("[hair]\nrest_shape = \"straight\"\n").hair.rest_shape == "straight");
  CHECK(first_error("[hair]\ntilt_toward = \"falling\"\n").find("choose one of \"down\", \"thicker\", \"hanging\"") != std::string::npos);
}
