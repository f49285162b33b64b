// Only the effects declared (docs/design.md §8): an effect that is off loads nothing, allocates no grid,
// sets no load or option, and leaves no trace in report.json; switched on, each one shows.
#include <doctest/doctest.h>

#include <filesystem>

#include "pipeline/pipeline.h"
#include "pipeline/stage_options.h"
#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

Scene smoke_with_effects(bool on) {
  Scene s = parse_scene(source_path("fixtures/smoke/scene.toml"));
  s.effects.gravity = on;
  s.effects.density = on ? DensityModel::binary : DensityModel::none;
  s.effects.maps = on ? std::vector<std::string>{"density", "tilt", "length"} : std::vector<std::string>{};
  s.maps.density = source_path("fixtures/maps/density.png");
  s.maps.length = source_path("fixtures/maps/length.png");
  s.effects.cutting = on;
  s.effects.winding = on;
  if (on) s.guides.weights = SceneWeights{0.3, 0.2, 0.3, 0.2};
  return s;
}

struct Run {
  Scene scene;
  Inputs inputs;
  PipelineResult result;
  std::string report;
  std::string out;
};

Run run(bool on) {
  Run r{smoke_with_effects(on), {}, {}, {}, {}};
  r.inputs = load_inputs(r.scene);
  r.out = hairfit::testing::scratch_path(on ? "effects-on" : "effects-off").string();
  fs::remove_all(r.out);
  RunOptions o;
  o.threads = 2;
  o.out_dir = r.out;
  r.result = run_pipeline(r.scene, r.inputs, o);
  r.report = read_all(r.out + "/report.json");
  return r;
}

}  // namespace

TEST_CASE("effects that are off leave no trace; switched on, each leaves its own") {
  for (bool on : {false, true}) {
    INFO("effects " << (on ? "on" : "off"));
    const Run r = run(on);
    const StageValues& v = r.result.values;
    // Gravity: no weight on any rod.
    CHECK((hair_material(r.scene).gravity.norm() > 0) == on);
    // Maps: none loaded.
    CHECK((r.inputs.density_map != nullptr) == on);
    CHECK((r.inputs.tilt_map != nullptr) == on);
    CHECK((r.inputs.length_map != nullptr) == on);
    // Density model: no grid, no stage, no files, no F4 figure.
    CHECK((v.guide_density != nullptr) == on);
    CHECK((v.fibre_density != nullptr) == on);
    CHECK(fs::exists(r.out + "/density") == on);
    CHECK((r.report.find("\"density\": {") != std::string::npos) == on);
    CHECK((r.report.find("mean_f4") != std::string::npos) == on);
    CHECK((r.report.find("density_batches") != std::string::npos) == on);
    // Cutting and winding: no fibre cut, no cut figure, no turns.
    int cut = 0;
    for (char c : v.strands->cut) cut += c;
    if (!on) CHECK(cut == 0);
    CHECK((r.report.find("\"cut\":") != std::string::npos) == on);
    CHECK((strand_options(r.scene).wisp.turns != 0) == on);
    // The report's list of effects.
    for (const char* effect : {"\"gravity\"", "\"density:binary\"", "\"map:density\"", "\"map:tilt\"", "\"map:length\"",
                               "\"cutting\"", "\"winding\""})
      CHECK((r.report.find(effect) != std::string::npos) == on);
    // Every stage reports its peak memory.
    for (const StageReport& s : r.result.report.stages) CHECK(s.peak_memory_bytes > 0);
    fs::remove_all(r.out);
  }
}
