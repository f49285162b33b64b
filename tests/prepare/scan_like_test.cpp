// `hairfit prepare` on scan-like busts (prepare/scan_like.h): far from the origin, coarse with an
// overhang, tilted by 30°, dressed with braids, bows and a bun, and noisy. Each must prepare into
// files `run` accepts and then run, its strands inside the prepared volume and off the scalp
// (direct winding-number sums, exact segment–triangle tests); the far scan must give the centred
// scan's files moved by the offset.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <tuple>

#include "io/obj_mesh.h"
#include "pipeline/inputs.h"
#include "pipeline/pipeline.h"
#include "pipeline/prepared_scene.h"
#include "prepare/prepare.h"
#include "prepare/refine.h"
#include "prepare/scan_like.h"
#include "prepare/surface_checks.h"
#include "spec/scene.h"
#include "mask_options.h"
#include "../support/independent_check.h"
#include "../support/report_figure.h"
#include "../support/run_in_process.h"
#include "../support/run_hairfit.h"
#include "../support/scene_text.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::figure;
using hairfit::testing::mask_options;
namespace fs = std::filesystem;

namespace {

// The case prepared through the files a user has: the scan written as OBJ, read back, prepared and
// written with run's own validation; returns the scene folder.
fs::path prepare_case(const ScanLikeCase& c, const BustScan& scan, Prepared& p) {
  const fs::path dir = hairfit::testing::fresh_scratch_folder("scan-like-" + c.name);
  const fs::path scan_file = dir / (c.name + ".obj");
  write_obj_mesh(scan_file, scan.mesh, {}, scan.colors);
  const LoadedMesh loaded = load_obj_mesh(scan_file);
  const PrepareOptions o = mask_options();
  p = prepare_scan(loaded.mesh, loaded.colors, o, scan_file.string());
  write_validated_prepared(p, scan_file, o, dir / "scene");
  return dir / "scene";
}

}  // namespace

TEST_CASE("every scan-like bust prepares into files run accepts, and its strands stay inside and off the scalp") {
  for (const ScanLikeCase& c : scan_like_cases(0.5)) {
    INFO(c.name);
    const BustScan scan = make_scan_like(c);
    Prepared p;
    const fs::path scene_dir = prepare_case(c, scan, p);
    MESSAGE(c.name << ": " << scan.mesh.triangles.size() << " triangles, scalp by " << p.scalp_how);
    for (const std::string& repair : p.repairs) MESSAGE(c.name << ": repaired " << repair);
    // The noise folds the hull's slivers (untangled) and roughens the hull under the strip (lowered).
    if (c.name == "noisy") {
      CHECK(p.untangled.pairs_found > 0);
      CHECK(p.untangled.pairs_left == 0);
      CHECK(p.scalp.strip_feet > 0);
    } else {
      CHECK(p.untangled.pairs_found == 0);
    }
    CHECK(p.checks.scalp_disk);
    CHECK(p.checks.scalp_inward_triangles == 0);
    CHECK(p.checks.intersections == 0);
    if (c.name == "dressed") {
      // At a 0.5 cm voxel the strip steps where the hairline zigzags, and two piece vertices 1e-4 cm
      // apart fan to one hairline vertex in the step's corner: a fixed 1e-3 cm step in front of that
      // sliver crossed the riser, and the scan was refused ("1 scalp triangles face inward").
      PrepareOptions coarse_grid = mask_options();
      coarse_grid.scalp.voxel = 0.5;
      const Prepared p5 = prepare_scan(scan.mesh, scan.colors, coarse_grid, "dressed.obj");
      CHECK(p5.scalp.method == "level set");
      CHECK(p5.checks.scalp_disk);
      CHECK(p5.checks.scalp_inward_triangles == 0);
      CHECK(p5.checks.intersections == 0);
    }
    std::ofstream(scene_dir / "small.toml")
        << hairfit::testing::with_keys(hairfit::testing::read_all((scene_dir / "scene.toml").string()),
                                       hairfit::testing::small_run_keys());
    const Scene scene = parse_scene(scene_dir / "small.toml");
    const Inputs inputs = load_inputs(scene);
    const PipelineResult r = hairfit::testing::run_in_process(scene, inputs);
    const Curves& fibres = r.values.strands->fibres;
    REQUIRE(fibres.count() > 100);
    const auto check = hairfit::testing::independent_check(inputs.volume.mesh, true, inputs.scalp.mesh, fibres);
    MESSAGE(c.name << ": strands inside by direct sums " << check.inside << ", segments crossing the scalp "
                   << check.crossings << " of " << check.segments);
    CHECK(check.finite);
    CHECK(check.inside >= 0.99);
    CHECK(check.crossings == 0);
    CHECK(figure(r.report, "strands", "scalp_crossings") == 0);
  }
}

// An OBJ with every coordinate at %.17g minus `shift` (exact: the test meshes are multiples of 2⁻²⁴ cm).
void write_moved_obj(const fs::path& path, const Mesh& mesh, const Vec3& shift) {
  std::ofstream out(path);
  char line[128];
  for (const Vec3& x : mesh.positions) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", x.x() - shift.x(), x.y() - shift.y(), x.z() - shift.z());
    out << line;
  }
  for (const Vec3i& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

TEST_CASE("a scan 10⁴ times its size from the origin prepares and runs as the centred scan, moved") {
  const ScanLikeCase far = scan_like_case("far", 0.5);
  ScanLikeCase centred = far;
  centred.offset = Vec3::Zero();
  const BustScan far_scan = make_scan_like(far), centred_scan = make_scan_like(centred);
  const PrepareOptions o = mask_options();
  const Prepared pf = prepare_scan(far_scan.mesh, far_scan.colors, o, "far.obj");
  const Prepared pc = prepare_scan(centred_scan.mesh, centred_scan.colors, o, "centred.obj");
  // The same computation in the same frame: the same triangles, positions moved by the offset.
  CHECK(pf.origin - pc.origin == far.offset);
  const double size = 58.0;
  for (const auto& [name, a, b] : {std::tuple{"scalp", &pf.scalp.scalp, &pc.scalp.scalp},
                                   std::tuple{"volume", &pf.scalp.volume, &pc.scalp.volume}}) {
    INFO(name);
    REQUIRE(a->positions.size() == b->positions.size());
    CHECK(a->triangles == b->triangles);
    double worst = 0.0;
    for (std::size_t v = 0; v < a->positions.size(); ++v)
      worst = std::max(worst, (a->positions[v] - far.offset - b->positions[v]).cwiseAbs().maxCoeff());
    MESSAGE(name << ": largest difference after moving back " << worst << " cm (" << worst / size << " of the size)");
    CHECK(worst <= 1e-9 * size);
  }
  // The far scene as prepare writes it (17 digits), and the same files moved back to the origin:
  // both run in the same frame, so their strands agree once moved.
  const fs::path dir = hairfit::testing::fresh_scratch_folder("scan-like-far-run");
  write_validated_prepared(pf, dir / "far.obj", o, dir / "far");
  fs::create_directories(dir / "centred");
  fs::copy_file(dir / "far" / "scene.toml", dir / "centred" / "scene.toml");
  for (const char* name : {"scalp.obj", "volume.obj"})
    write_moved_obj(dir / "centred" / name, load_obj_mesh(dir / "far" / name).mesh, far.offset);
  PipelineResult results[2];
  Inputs inputs[2];
  for (int k = 0; k < 2; ++k) {
    const fs::path scene_dir = dir / (k == 0 ? "far" : "centred");
    std::ofstream(scene_dir / "small.toml") << hairfit::testing::with_keys(
        hairfit::testing::read_all((scene_dir / "scene.toml").string()), hairfit::testing::small_run_keys());
    const Scene scene = parse_scene(scene_dir / "small.toml");
    inputs[k] = load_inputs(scene);
    results[k] = hairfit::testing::run_in_process(scene, inputs[k]);
  }
  CHECK(inputs[0].origin - inputs[1].origin == far.offset);
  const Curves &ff = results[0].values.strands->fibres, &fc = results[1].values.strands->fibres;
  const auto check_far = hairfit::testing::independent_check(inputs[0].volume.mesh, true, inputs[0].scalp.mesh, ff);
  MESSAGE("far: strands inside " << check_far.inside << ", crossings " << check_far.crossings << " of " << check_far.segments);
  CHECK(check_far.inside >= 0.99);
  CHECK(check_far.crossings == 0);
  // Values in the run's frame: equal bit for bit.
  REQUIRE(ff.points.size() == fc.points.size());
  CHECK(ff.points == fc.points);
}

TEST_CASE("a scan prepare cannot make a scene of is refused with exit 2 and nothing written") {
  // The plain bust with a second, skin-coloured head inside it pushed up through its crown: the
  // scan crosses itself along a ring no local smoothing clears, and the skin coming through the
  // hair leaves no layer under it. The output folder and the file already in it stay as they were.
  BustScan scan = make_sculpted_bust(BustStyle::plain, 0.5);
  const int n = static_cast<int>(scan.mesh.positions.size());
  for (int v = 0; v < n; ++v) {
    scan.mesh.positions.push_back(Vec3(0.0, 5.5, 0.0) + 0.8 * (scan.mesh.positions[v] - Vec3(0.0, 4.0, 0.0)));
    scan.colors.push_back(Vec3(kSkinColor[0], kSkinColor[1], kSkinColor[2]));
  }
  const std::size_t triangles = scan.mesh.triangles.size();
  for (std::size_t t = 0; t < triangles; ++t) scan.mesh.triangles.push_back(scan.mesh.triangles[t] + Vec3i::Constant(n));
  const fs::path dir = hairfit::testing::fresh_scratch_folder("scan-like-refused");
  write_obj_mesh(dir / "crossed.obj", scan.mesh, {}, scan.colors);
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out" / "scene.toml") << "# the user's own\n";
  const auto r = hairfit::testing::run_hairfit("prepare " + (dir / "crossed.obj").string() + " --out " +
                                               (dir / "out").string() + " --mask 0.3,0.18,0.1 --threads 2");
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("crossed.obj") != std::string::npos);
  CHECK(r.err.find("the scan crosses itself at") != std::string::npos);
  CHECK(hairfit::testing::read_all((dir / "out" / "scene.toml").string()) == "# the user's own\n");
  CHECK(!fs::exists(dir / "out" / "scalp.obj"));
  CHECK(!fs::exists(dir / ".out.prepare-staging"));
}

TEST_CASE("prepared files run would refuse are not written: a scalp that is no disk") {
  // A prepared scene whose scalp has lost one inner triangle (two boundary loops): run's own
  // checks refuse it in the staging folder, and the output folder is not created.
  const ScanLikeCase c = scan_like_case("coarse");
  const BustScan scan = make_scan_like(c);
  const PrepareOptions o = mask_options();
  Prepared p = prepare_scan(scan.mesh, scan.colors, o, "coarse.obj");
  std::vector<char> on_rim(p.scalp.scalp.positions.size(), 0);
  for (int v : p.scalp.hairline) on_rim[v] = 1;
  const MeshTopology topology = analyse_topology(p.scalp.scalp);
  for (int v : topology.boundary_loops[0]) on_rim[v] = 1;
  const auto inner = std::find_if(p.scalp.scalp.triangles.begin(), p.scalp.scalp.triangles.end(),
                                  [&](const Vec3i& t) { return !on_rim[t[0]] && !on_rim[t[1]] && !on_rim[t[2]]; });
  REQUIRE(inner != p.scalp.scalp.triangles.end());
  p.scalp.scalp.triangles.erase(inner);
  const fs::path dir = hairfit::testing::fresh_scratch_folder("scan-like-not-disk");
  std::string message;
  try {
    write_validated_prepared(p, dir / "coarse.obj", o, dir / "out");
  } catch (const InputError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.find((dir / "coarse.obj").string() + ": error: ") == 0);
  CHECK(message.find("that `hairfit run` would refuse, so it wrote nothing") != std::string::npos);
  CHECK(message.find((dir / "out" / "scalp.obj").string()) != std::string::npos);
  CHECK(!fs::exists(dir / "out"));
  CHECK(!fs::exists(dir / ".out.prepare-staging"));
}

TEST_CASE("a coarse scan is split into four until its median edge is short enough, the surface unchanged") {
  // A unit right triangle split twice: 16 triangles, the same area, edges a quarter as long.
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
  m.triangles = {Vec3i(0, 1, 2)};
  const std::vector<Vec3> colors = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const Refined r = refine_coarse_scan(m, colors, 1.5);
  CHECK(r.splits == 2);
  CHECK(r.mesh.triangles.size() == 16);
  CHECK(r.mesh.positions.size() == 15);  // (4 + 1)(4 + 2)/2 grid points
  CHECK(surface_area(r.mesh) == doctest::Approx(8.0).epsilon(1e-12));
  CHECK(r.median_edge_before == doctest::Approx(4.0));
  CHECK(r.median_edge_after == doctest::Approx(1.0));
  // Colours are linear: each vertex's colour is its position over 4 in x and y.
  for (std::size_t v = 0; v < r.mesh.positions.size(); ++v) {
    CHECK(r.colors[v].x() == doctest::Approx(r.mesh.positions[v].x() / 4.0));
    CHECK(r.colors[v].y() == doctest::Approx(r.mesh.positions[v].y() / 4.0));
  }
  const MeshTopology t = analyse_topology(r.mesh);
  CHECK(t.is_disk());
  CHECK(t.orientation_consistent);
  // A fine mesh is left alone.
  CHECK(refine_coarse_scan(m, colors, 5.0).splits == 0);
}
