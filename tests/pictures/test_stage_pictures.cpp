// Pictures of every stage of the smoke scene: sizes, determinism, errors, and the strands drawn
// where the hair volume is.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>

#include "../support/run_hairfit.h"
#include "core/error.h"
#include "pipeline/stage_pictures.h"
#include "render/render_3d.h"

using namespace hairfit;
using hairfit::testing::source_path;

namespace {

struct Smoke {
  Scene scene;
  Inputs inputs;
  PipelineResult result;
};

const Smoke& smoke() {
  static const Smoke once = [] {
    Smoke s;
    s.scene = parse_scene(source_path("fixtures/smoke/scene.toml"));
    s.inputs = load_inputs(s.scene);
    RunOptions options;
    options.threads = 2;
    options.write_outputs = false;
    s.result = run_pipeline(s.scene, s.inputs, options);
    return s;
  }();
  return once;
}

}  // namespace

TEST_CASE("every stage renders at the size asked, from every view, the same bytes twice") {
  const Smoke& s = smoke();
  for (const std::string& stage : picture_stages()) {
    if (stage == "all" || stage == "density") continue;  // smoke declares no density model
    INFO(stage);
    const Image a = render_stage(stage, s.scene, s.inputs, s.result.values, ViewName::three_quarter, 240, 200, 2);
    CHECK(a.width == 240);
    CHECK(a.height == 200);
    const Image b = render_stage(stage, s.scene, s.inputs, s.result.values, ViewName::three_quarter, 240, 200, 1);
    CHECK(encode_png(a) == encode_png(b));
  }
  for (ViewName view : {ViewName::front, ViewName::side, ViewName::back, ViewName::top}) {
    const Image image = render_stage("strands", s.scene, s.inputs, s.result.values, view, 160, 120, 2);
    CHECK(image.width == 160);
    CHECK(image.height == 120);
  }
  const Image sheet = render_stage("all", s.scene, s.inputs, s.result.values, ViewName::front, 400, 400, 2);
  CHECK(sheet.width > 400);  // a contact sheet of every stage, tiles of half the size asked
}

TEST_CASE("the strands' pixels fall inside the projected silhouette of the hair volume") {
  const Smoke& s = smoke();
  // Draw the volume alone, opaque, and the strands alone, with the same camera: every pixel the
  // strands cover must be covered by the volume too (≥ 99 %; the rest are fibres cut past the rim).
  const Curves& fibres = s.result.values.strands->fibres;
  Drawing3D volume_only, strands_only;
  volume_only.meshes.push_back(MeshLayer{&s.inputs.volume.mesh});
  CurveLayer curves;
  curves.curves = &fibres;
  curves.hair_shading = false;
  strands_only.curves.push_back(curves);
  const auto [lo, hi] = drawing_bounds(volume_only);
  for (ViewName view : {ViewName::front, ViewName::side, ViewName::top}) {
    const Camera camera = fit_camera(view, s.scene.units.down, s.scene.units.front, lo, hi, 300, 300);
    RenderOptions options;
    options.supersample = 1;
    const Image v = render_3d(volume_only, camera, options), h = render_3d(strands_only, camera, options);
    const Image empty = render_3d(Drawing3D{}, camera, options);
    long hair = 0, hair_inside = 0;
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 300; ++x) {
        const bool is_hair = std::memcmp(h.pixel(x, y), empty.pixel(x, y), 3) != 0;
        const bool in_volume = std::memcmp(v.pixel(x, y), empty.pixel(x, y), 3) != 0;
        hair += is_hair;
        hair_inside += is_hair && in_volume;
      }
    INFO("view " << view_name(view) << ": " << hair_inside << " of " << hair << " hair pixels inside");
    REQUIRE(hair > 1000);
    CHECK(static_cast<double>(hair_inside) / hair >= 0.99);
  }
}

TEST_CASE("an unknown stage or view is refused with the valid names") {
  const Smoke& s = smoke();
  CHECK_THROWS_WITH_AS(render_stage("hairdo", s.scene, s.inputs, s.result.values, ViewName::front, 64, 64, 1),
                       doctest::Contains("valid stages: inputs, fields, chart, roots, preguides, guides, strands, density, all"),
                       InputError);
  CHECK_THROWS_WITH_AS(render_stage("density", s.scene, s.inputs, s.result.values, ViewName::front, 64, 64, 1),
                       doctest::Contains("declares no density model"), InputError);
  const auto r = hairfit::testing::run_hairfit("render " + source_path("fixtures/smoke/scene.toml") +
                                               " --stage guides --view sideways --out /tmp/never.png");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("valid views: front, side, back, top, three-quarter") != std::string::npos);
  const auto q = hairfit::testing::run_hairfit("render " + source_path("fixtures/smoke/scene.toml") + " --stage hairdo");
  CHECK(q.exit_code == 2);
  CHECK(q.err.find("valid stages:") != std::string::npos);
}

TEST_CASE("render --out FOLDER writes the picture into the folder under its default name") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "hairfit-render-into-folder";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto r = hairfit::testing::run_hairfit("render " + source_path("fixtures/smoke/scene.toml") +
                                               " --stage chart --size 64x64 --out " + dir.string());
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::is_regular_file(dir / "chart-front.png"));
  std::filesystem::remove_all(dir);
}
