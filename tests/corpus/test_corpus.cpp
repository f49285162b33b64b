// The bad-input corpus (issue 12): every scene in tests/corpus/scenes is refused with exit code 2
// and a message that starts with the file at fault and names the item and the fix, and `run`
// leaves an existing output folder exactly as it was. tests/corpus/accepted holds the edge cases
// that are valid input, with the exact behaviour they get. The messages of the older cases are
// checked in tests/spec/test_scene_parser.cpp (through validate); make_data.py writes the data files.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "../support/run_hairfit.h"
#include "io/obj_mesh.h"
#include "io/png_map.h"
#include "scalp/chart.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

std::string corpus(const std::string& relative) { return source_path("tests/corpus/" + relative); }

std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) files[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? read_all(e.path().string()) : "(folder)";
  return files;
}

}  // namespace

TEST_CASE("every corpus scene: run exits 2, names the file, the item and the fix, and leaves the output folder untouched") {
  struct Case {
    const char* scene;
    const char* file;      // relative to tests/corpus: the message starts with it
    std::string expected;  // follows the file name in the message
  };
  const std::vector<Case> cases = {
      // scenes
      {"scalp_is_folder", "scenes/scalp_is_folder.toml", ":4:9: error: inputs.scalp: " + corpus("data") + " is a folder; name a file"},
      {"volume_missing", "scenes/volume_missing.toml", ":5:10: error: inputs.volume: no such file " + corpus("data/no_such_volume.obj")},
      {"map_missing", "scenes/map_missing.toml", ":11:8: error: maps.tilt: no such file " + corpus("scenes/no_such_tilt.png")},
      {"chart_point_outside", "scenes/chart_point_outside.toml",
       ":9:9: error: hair.whorl = [0.9, 0.9] lies outside the chart's unit disk; "
       "give a point with x² + y² ≤ 1"},
      {"map_unknown_kind", "scenes/map_unknown_kind.toml",
       ":8:9: error: effects.maps = \"colour\" is not allowed; choose one of \"density\", \"tilt\", \"length\""},
      {"map_is_mesh", "data/cube.obj", ": error: is not a PNG file; maps must be grey-value PNG images (8 or 16 bit)"},
      {"units_too_large", "data/cap.obj",
       ": error: distance field: a grid of 1617×217×1409 voxels at 0.25 cm needs 5.59 GiB, more than the limit of 2 GiB; "
       "use a voxel of at least 0.356 cm, or raise max_memory"},
      // meshes
      {"mesh_empty", "data/empty.obj", ": error: has no vertices; it must be a triangle mesh in Wavefront OBJ format"},
      {"mesh_inf", "data/cap_inf.obj", ":3:5: error: vertex 2 has a non-finite or unreadable coordinate \"inf\"; every vertex needs three finite numbers"},
      {"mesh_bad_index", "data/cap_bad_index.obj",
       ":15:7: error: face refers to vertex 9 but the file has 7 vertices (valid: 1..7 or negative relative indices)"},
      {"mesh_binary", "data/binary.obj", ": error: is a binary file, not an OBJ text file; export the mesh as Wavefront OBJ"},
      {"mesh_enormous", "data/cap_enormous.obj",
       ": error: has a vertex at (0, 5.5e+30, 0) cm, beyond ±1000000 cm (10 km) of the origin; check units.length = \"cm\" "
       "and the scale the mesh was exported at"},
      {"scalp_nonmanifold", "data/cap_nonmanifold.obj",
       ": error: the scalp must be a topological disk (one piece, one boundary loop), but it has non-manifold edges (shared "
       "by 3 or more triangles) at vertices 1 (0, 5.5, 0) 2 (2, 5, 0)"},
      {"scalp_edge_on", "data/cap.obj",
       ": error: the scalp's hairline is edge-on when seen from above (along units.down), so the chart cannot tell left "
       "from right; check units.down"},
      {"scalp_outside", "data/cube.obj",
       ": error: no part of the scalp lies inside the hair volume, so there is no region to fill: check that both "
       "meshes use units.length = \"cm\", that inputs.scalp and inputs.volume are not swapped, and that the volume "
       "covers the scalp"},
      {"volume_too_small", "data/cube_small.obj", ": error: no part of the scalp lies inside the hair volume"},
      // maps
      {"map_empty", "data/empty.png", ": error: is not a PNG file; maps must be grey-value PNG images (8 or 16 bit)"},
      {"map_zero_width", "data/zero_width.png", ": error: has no pixels (its header says 0×1); maps need at least 1×1 pixel"},
      {"map_colour", "data/colour.png",
       ": error: is a colour image (pixel 1,0 is not grey); maps must be grey-value images: convert it to greyscale"},
      // found by fuzzing: a zero-length IDAT cut off in its CRC at the end of the file
      {"map_empty_idat_cut", "data/fuzz_empty_idat_cut.png",
       ": error: is a corrupt PNG (its chunks are cut off or malformed); re-export it as a grey PNG"},
  };
  const fs::path out = hairfit::testing::fresh_scratch_folder("corpus");
  fs::create_directories(out / "fields");
  std::ofstream(out / "report.json") << "{\"an\": \"earlier run\"}\n";
  std::ofstream(out / "fields" / "scalp.nrrd") << "earlier field\n";
  const auto before = snapshot(out);
  std::set<std::string> seen;
  for (const auto& e : fs::directory_iterator(corpus("scenes"))) {
    if (e.path().extension() != ".toml") continue;
    const std::string name = e.path().stem().string();
    INFO(name);
    const auto r = run_hairfit("run " + e.path().string() + " --threads 1 --out " + out.string());
    CHECK(r.exit_code == 2);
    CHECK(r.err.rfind(source_path(""), 0) == 0);  // starts with the file at fault (a corpus or fixture file)
    CHECK(r.err.find(": error: ") != std::string::npos);
    CHECK(r.out.empty());
    CHECK(snapshot(out) == before);
    for (const Case& c : cases)
      if (name == c.scene) {
        seen.insert(name);
        CHECK(r.err.rfind(corpus(c.file) + c.expected, 0) == 0);
      }
  }
  CHECK(seen.size() == cases.size());  // every case of the table exists
  fs::remove_all(out);
}

TEST_CASE("a scene path that is a folder or does not exist") {
  auto r = run_hairfit("validate " + corpus("data"));
  CHECK(r.exit_code == 2);
  CHECK(r.err == corpus("data") + ": error: is a folder; name a scene .toml file\n");
  r = run_hairfit("validate " + corpus("scenes/no_such_scene.toml"));
  CHECK(r.exit_code == 2);
  CHECK(r.err == corpus("scenes/no_such_scene.toml") + ": error: no such scene file\n");
}

// Accepted edge cases: valid input, with the behaviour they get.

TEST_CASE("accepted: 1×1, 16-bit and grey RGB maps") {
  const auto r = run_hairfit("validate " + corpus("accepted/maps_small_deep_grey.toml"));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("  density  map 1×1, 8-bit\n  tilt     map 3×1, 16-bit\n  length   map 2×1, 8-bit\n") != std::string::npos);

  // A 1×1 map is a constant: every point of the scalp gets its one value.
  const GreyMap one = load_grey_map(corpus("data/one_pixel.png"));
  REQUIRE(one.values.size() == 1);
  CHECK(one.values[0] == static_cast<float>(128 / 255.0));
  for (const Vec2& uv : {Vec2(0, 0), Vec2(0.5, 0.5), Vec2(1, 1), Vec2(-3, 7)}) CHECK(one.sample(uv) == one.values[0]);
  // 16 bit: each value is its 16-bit number / 65535, not rounded to 8 bits.
  const GreyMap deep = load_grey_map(corpus("data/deep.png"));
  CHECK(deep.bits == 16);
  REQUIRE(deep.values.size() == 3);
  CHECK(deep.values[0] == 0.0f);
  CHECK(deep.values[1] == static_cast<float>(12345 / 65535.0));
  CHECK(deep.values[2] == 1.0f);
  // RGB whose every pixel is grey is a grey map (editors often save greys as RGB).
  const GreyMap rgb = load_grey_map(corpus("data/grey_rgb.png"));
  REQUIRE(rgb.values.size() == 2);
  CHECK(rgb.values[0] == static_cast<float>(64 / 255.0));
  CHECK(rgb.values[1] == static_cast<float>(192 / 255.0));
  // A zero-length IDAT chunk before the data is valid PNG (stb_image mishandled it: fuzzing found it).
  const GreyMap padded = load_grey_map(corpus("data/empty_idat.png"));
  REQUIRE(padded.values.size() == 2);
  CHECK(padded.bits == 8);
  CHECK(padded.values[0] == static_cast<float>(64 / 255.0));
  CHECK(padded.values[1] == static_cast<float>(192 / 255.0));
}

TEST_CASE("accepted: a scalp whose triangles all face inward gets the same chart and outward normals") {
  const auto r = run_hairfit("validate " + corpus("accepted/scalp_flipped.toml"));
  CHECK(r.exit_code == 0);
  const Vec3 front(0, 0, 1), down(0, -1, 0);
  const ScalpChart up = make_scalp_chart(load_obj_mesh(corpus("data/cap.obj")).mesh, front, down, "cap");
  const ScalpChart flipped = make_scalp_chart(load_obj_mesh(corpus("data/cap_flipped.obj")).mesh, front, down, "flipped");
  CHECK(up.outward == 1);
  CHECK(flipped.outward == -1);
  REQUIRE(flipped.chart.size() == up.chart.size());
  for (std::size_t v = 0; v < up.chart.size(); ++v) {
    CHECK((flipped.chart[v] - up.chart[v]).norm() < 1e-14);
    CHECK((flipped.vertex_normals[v] - up.vertex_normals[v]).norm() < 1e-14);
    CHECK(up.vertex_normals[v].y() > 0.0);  // outward = up for this cap
  }
}

TEST_CASE("accepted: raw volumes (open, non-manifold, inward, a flipped patch) and an inconsistent scalp are cleaned and reported") {
  struct Case {
    const char* scene;
    std::vector<std::string> expected;  // lines validate prints
  };
  const std::vector<Case> cases = {
      {"volume_open", {"closed: no", "1 boundary loop (the rim), 0 holes, 0 non-manifold edges",
                       "the shell the open volume encloses with the scalp reversed; 100.0% of the scalp lies inside it"}},
      {"volume_nonmanifold", {"closed: no", "1 non-manifold edge"}},
      {"volume_inward", {"closed: yes", "its triangles faced inward: reversed", "100.0% of the scalp lies inside it"}},
      {"volume_inconsistent", {"closed: yes", "1 flipped patch (1 triangle)"}},
      {"scalp_inconsistent", {"1 flipped patch (1 triangle)", "a topological disk"}},
  };
  for (const Case& c : cases) {
    INFO(c.scene);
    const auto r = run_hairfit("validate " + corpus(std::string("accepted/") + c.scene + ".toml"));
    CHECK(r.exit_code == 0);
    for (const std::string& line : c.expected) CHECK(r.out.find(line) != std::string::npos);
  }
}
