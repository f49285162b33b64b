// scene.resolved.toml (spec/resolved_scene.h): it parses back to the scene that was run, key by key
// and bit for bit; it names where each value came from; what a run derives stays a comment, so
// running the file again derives it again; and that rerun writes the same outputs byte for byte.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "pipeline/report.h"
#include "spec/resolved_scene.h"
#include "spec/scene.h"
#include "spec/scene_keys.h"
#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

const std::string kInputs = "format = \"hairfit-scene/1\"\n"
                            "inputs = { scalp = \"" + source_path("fixtures/meshes/scalp.obj") + "\", volume = \"" +
                            source_path("fixtures/meshes/spheroid_volume.obj") + "\" }\n";

// The scene written as scene.toml into `folder` and parsed.
Scene scene_in(const fs::path& folder, const std::string& text) {
  fs::create_directories(folder);
  std::ofstream(folder / "scene.toml") << text;
  return parse_scene(folder / "scene.toml");
}

// The resolved scene of `scene` written into `folder`, and parsed back.
Scene resolved_again(const Scene& scene, const fs::path& folder, const std::vector<DerivedKey>& derived = {}) {
  fs::create_directories(folder);
  std::ofstream(folder / kResolvedSceneFile) << resolved_scene_text(scene, derived, folder);
  return parse_scene(folder / kResolvedSceneFile);
}

void check_same_values(const Scene& a, const Scene& b) {
  for (const SceneKey& k : scene_keys()) {
    if (k.kind == KeyKind::path || k.kind == KeyKind::folder) continue;  // shown as placeholders
    INFO(k.name);
    CHECK(k.show(a) == k.show(b));
  }
  CHECK(a.inputs.scalp == b.inputs.scalp);
  CHECK(a.inputs.volume == b.inputs.volume);
  CHECK(a.maps.density == b.maps.density);
  CHECK(a.maps.tilt == b.maps.tilt);
  CHECK(a.maps.length == b.maps.length);
  CHECK(a.output.occluder == b.output.occluder);
  CHECK(a.hair.from_shell == b.hair.from_shell);
}

// The lines of table [name] in a resolved scene.
std::string table_text(const std::string& text, const std::string& name) {
  const std::size_t begin = text.find("\n[" + name + "]\n");
  if (begin == std::string::npos) return "";
  return text.substr(begin + 1, text.find("\n[", begin + 1) - begin);
}

// The line of `text` that starts with `start`, or "".
std::string line_starting(const std::string& text, const std::string& start) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    if (line.rfind(start, 0) == 0) return line;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return "";
}

// Every file of `dir` (relative path → bytes) but those that hold the run itself: report.json
// (times, the scene's path) and the resolved scene (its sources name the file it was run from).
std::map<std::string, std::string> outputs_of(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || name == "report.json" || name == kResolvedSceneFile) continue;
    files[fs::relative(e.path(), dir).string()] = read_all(e.path().string());
  }
  return files;
}

}  // namespace

TEST_CASE("the resolved scene parses back to the same value of every key, bit for bit") {
  const fs::path dir = testing::fresh_scratch_folder("resolved-values");
  const std::string maps = "[effects]\nmaps = [\"density\", \"length\"]\n[maps]\ndensity = \"" +
                           source_path("fixtures/maps/density.png") + "\"\nlength = \"" +
                           source_path("fixtures/maps/length.png") + "\"\n";
  const std::map<std::string, std::string> scenes{
      {"shell", ""},  // hair from the shell: its defaults, hair.length and hair.tilt unset
      {"preset", "preset = \"final\"\nseed = 9007199254740991\n[hair]\nlength = 12.3456789012345\ntilt = 33\n"},
      // Directions that normalising twice moves by a bit, and numbers that need 17 digits.
      {"directions", "[units]\ndown = [0.3, -1, 0.1]\nfront = [0.1, 0.2, 1]\n[hair]\ntilt = 0.1\n"
                     "[guides.weights]\ndirection = 0.3\nsimilarity = 0.3\nboundary = 0.4\n"},
      {"maps", maps + "[output]\noccluder = \"" + source_path("fixtures/meshes/scalp.obj") + "\"\n"},
  };
  for (const auto& [name, text] : scenes) {
    INFO(name);
    const Scene scene = scene_in(dir / name, kInputs + text);
    const fs::path out = dir / name / "out";
    check_same_values(scene, resolved_again(scene, out));
    // Beside the scene, the inputs are written relative to the output folder.
    CHECK(line_starting(resolved_scene_text(scene, {}, out), "dir = ").find("dir = \".\"") == 0);
  }
}

TEST_CASE("each key names where its value came from: the scene's line, the preset, the shell default, the default") {
  const fs::path dir = testing::fresh_scratch_folder("resolved-sources");
  fs::create_directories(dir / "meshes");
  for (const char* mesh : {"scalp.obj", "spheroid_volume.obj"})
    fs::copy_file(source_path("fixtures/meshes/") + mesh, dir / "meshes" / mesh);
  const Scene scene = scene_in(dir, "format = \"hairfit-scene/1\"\n"
                                    "inputs = { scalp = \"meshes/scalp.obj\", volume = \"meshes/spheroid_volume.obj\" }\n"
                                    "preset = \"final\"\nseed = 5\n[hair]\ndensity = 3\n");
  const fs::path out = scene.output.dir;
  const std::string text = resolved_scene_text(scene, {}, out);
  CHECK(line_starting(text, "seed = 5 ").find("# scene.toml:4") != std::string::npos);
  CHECK(line_starting(text, "density = 3 ").find("# scene.toml:6") != std::string::npos);
  CHECK(line_starting(text, "samples = 64 ").find("# preset \"final\"") != std::string::npos);
  CHECK(line_starting(text, "flow = \"relief\" ").find("# shell default") != std::string::npos);
  CHECK(line_starting(text, "integrator = \"rk4\" ").find("# default") != std::string::npos);
  CHECK(line_starting(text, "dir = \".\" ").find("# default") != std::string::npos);
  CHECK(line_starting(resolved_scene_text(scene, {}, dir / "elsewhere"), "dir = \".\" ").find("# hairfit run --out") !=
        std::string::npos);
  CHECK(line_starting(text, "scalp = ").find("scalp = \"../meshes/scalp.obj\"") == 0);  // relative to the output folder
  CHECK(line_starting(text, "# density: unset") != "");                 // maps.density: no file
  // hair.length and hair.tilt stay unset: the run derives them from the shell.
  const std::string hair = table_text(text, "hair");
  CHECK(line_starting(hair, "# length: unset").find("derived") != std::string::npos);
  CHECK(line_starting(hair, "# tilt: unset").find("derived") != std::string::npos);
  CHECK(line_starting(hair, "length = ") == "");
  CHECK(line_starting(hair, "tilt = ") == "");
}

TEST_CASE("a derived key is a comment with its figure; a key that resolved at run time keeps its value") {
  const fs::path dir = testing::fresh_scratch_folder("resolved-derived");
  const Scene scene = scene_in(dir, kInputs);
  const std::vector<DerivedKey> derived{{"hair.length", "9", "the shell, reach 13.15 cm"},
                                        {"strands.depth", "\"wisp\"", "auto, T 0.37 cm"}};
  const std::string text = resolved_scene_text(scene, derived, scene.output.dir);
  CHECK(line_starting(text, "# length = 9 ").find("# derived: the shell, reach 13.15 cm") != std::string::npos);
  CHECK(line_starting(text, "depth = \"auto\" ").find("# shell default") != std::string::npos);
  CHECK(line_starting(text, "#   at run time: \"wisp\" ").find("# derived: auto, T 0.37 cm") != std::string::npos);
  const Scene again = resolved_again(scene, scene.output.dir, derived);
  CHECK(again.hair.from_shell);  // the rerun derives hair.length again
  check_same_values(scene, again);

  StageReport stage;
  stage.derive("hair.tilt", "80", "the shell");
  CHECK(stage.derived.size() == 1);
  CHECK_THROWS_AS(stage.derive("hair.lenght", "9", "a typo"), std::logic_error);
}

TEST_CASE("running the resolved scene again gives the same outputs byte for byte, cached or not") {
  const fs::path dir = testing::fresh_scratch_folder("resolved-rerun");
  // The smoke fixture (every hair key given), and hair from the shell on a raw MakeHuman shell,
  // test-sized: hair.length and hair.tilt derived by the roots, "auto" resolved by the fields and
  // the strands.
  const std::string makehuman = source_path("fixtures/makehuman/");
  std::ofstream(dir / "shell.toml")
      << "format = \"hairfit-scene/1\"\nseed = 3\n[units]\nlength = \"dm\"\n"
      << "[inputs]\nscalp = \"" << makehuman << "scalp.obj\"\nvolume = \"" << makehuman << "hair_short04_full.obj\"\n"
      << "[effects]\ncutting = true\n[hair]\ndensity = 4\ntilt_toward = \"hanging\"\n[fields]\nvoxel = 0.4\n"
      << "[roots]\nguides = 40\npreguide_spacing = 3\n[output]\nrenders = []\n";
  for (const std::string& scene : {source_path("fixtures/smoke/scene.toml"), (dir / "shell.toml").string()}) {
    INFO(scene);
    const fs::path first = dir / "first", second = dir / "second", cached = dir / "cached", cache = dir / "cache";
    for (const fs::path& d : {first, second, cached, cache}) fs::remove_all(d);
    REQUIRE(run_hairfit("run " + scene + " --threads 2 --quiet --cache " + cache.string() + " --out " + first.string())
                .exit_code == 0);
    const fs::path resolved = first / kResolvedSceneFile;
    REQUIRE(fs::exists(resolved));
    REQUIRE(run_hairfit("run " + resolved.string() + " --threads 1 --quiet --no-cache --out " + second.string())
                .exit_code == 0);
    const auto before = outputs_of(first), after = outputs_of(second);
    CHECK(before.size() >= 8);
    for (const auto& [path, bytes] : before) {
      INFO(path);
      REQUIRE(after.count(path) == 1);
      CHECK(after.at(path) == bytes);
    }
    CHECK(after.size() == before.size());
    // The rerun resolves to the same values, and derives the same keys from the same figures.
    const std::string text = read_all(resolved.string()), again = read_all((second / kResolvedSceneFile).string());
    check_same_values(parse_scene(resolved), parse_scene(second / kResolvedSceneFile));
    for (const char* derived : {"# length = ", "# tilt = ", "#   at run time: "})
      CHECK(line_starting(text, derived) == line_starting(again, derived));
    // A run whose stages come from the cache reports the same derived keys: the file is the same.
    REQUIRE(run_hairfit("run " + scene + " --threads 2 --quiet --cache " + cache.string() + " --out " + cached.string())
                .exit_code == 0);
    CHECK(read_all((cached / kResolvedSceneFile).string()) == text);
  }
  const std::string shell = read_all((dir / "first" / kResolvedSceneFile).string());
  // short04's hull carries its hair on below the rim: the length is the hull's, per root.
  CHECK(line_starting(shell, "# length = per root").find("# derived: the hull") != std::string::npos);
  CHECK(line_starting(shell, "# tilt = ").find("# derived: the shell") != std::string::npos);
  CHECK(line_starting(shell, "skin_beyond_hairline = \"auto\"") != "");
  CHECK(line_starting(shell, "#   at run time: \"shell\"").find("auto, the hull being open") != std::string::npos);
}

TEST_CASE("hairfit validate --resolved prints the resolved scene, and a bad scene is an error there too") {
  const auto r = run_hairfit("validate " + source_path("fixtures/smoke/scene.toml") + " --resolved");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.rfind("# The scene as hairfit resolved it", 0) == 0);
  CHECK(line_starting(r.out, "guides = 40 ").find("# scene.toml:26") != std::string::npos);
  CHECK(run_hairfit("validate " + source_path("tests/corpus/scenes/map_missing.toml") + " --resolved").exit_code == 2);
}
