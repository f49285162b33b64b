// The flow on carved hulls (issue 48): every scan-like carved hull of reference/carved_hull.h, run
// as a new user would (the two meshes, the directions, the guides and the hairs per cm², every hair
// key at its default), one cold `hairfit run` each; the guides scored against the carved direction.
//   bench_carved_hulls [--threads T] [--hairfit PATH] [--scratch DIR] [--guides N] [--density D]
//                      [--set KEY=VALUE]…   (extra scene keys under [hair], for designs side by side)
// The guides' angle to the carving and the share against its sign are reference/carved_hull.h's
// score_carved_flow; the roots' angle is their growth direction's, the field where hair starts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runs.h"
#include "field/hair_region.h"
#include "io/curve_files.h"
#include "io/obj_mesh.h"
#include "io/ply_points.h"
#include "reference/carved_hull.h"

using namespace hairfit;
using namespace hairfit::bench;

namespace {

// The growth field at the roots: the median angle of each root's growth direction (in the plane
// across the head's radial direction) to the carved line there.
double score_roots(CarvedStyle style, const PlyPoints& roots) {
  const PlyColumn *dx = roots.column("dx"), *dy = roots.column("dy"), *dz = roots.column("dz");
  std::vector<double> angles;
  if (!dx || !dy || !dz) return NAN;
  for (std::size_t i = 0; i < roots.positions.size(); ++i) {
    const CarvedDirection truth = carved_direction(style, roots.positions[i]);
    if (!(truth.weight > 0.5)) continue;
    const Vec3 radial = truth.direction.cross(roots.positions[i]).cross(truth.direction).normalized();
    Vec3 d(dx->values[i], dy->values[i], dz->values[i]);
    d -= d.dot(radial) * radial;
    if (!(d.norm() > 1e-9)) continue;
    angles.push_back(std::acos(std::min(1.0, std::fabs(d.normalized().dot(truth.direction)))) * 180.0 / M_PI);
  }
  return angles.empty() ? NAN : median(angles);
}

// The share of the guides' nodes after the root inside the layer by its generalized winding
// number, exactly (HairRegion::inside_hull: the open cap's number less the scalp's, > ½), which
// is 1 in the layer and 0 outside it for a carved cap whose rim is the scalp's: the truth the
// fields' trilinear values only approach within a voxel of a hairline.
double inside_by_winding(const CarvedHull& hull, const Curves& guides) {
  const HairRegion layer(hull.hull, hull.scalp, /*hull_closed=*/false);
  long long nodes = 0, inside = 0;
  for (std::size_t c = 0; c < guides.count(); ++c)
    for (std::size_t i = 1; i < guides.size(c); ++i, ++nodes) inside += layer.inside_hull(guides.point(c, i));
  return nodes ? static_cast<double>(inside) / nodes : NAN;
}

}  // namespace

int main(int argc, char** argv) {
  RunSettings run{1, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-carved-hulls"};
  int guides = 600;
  double density = 20.0;
  std::vector<std::string> keys;
  for (int i = 1; i < argc; ++i) {
    if (parse_run_option(argc, argv, i, run)) continue;
    const std::string a = argv[i];
    if (a == "--guides" && i + 1 < argc) {
      guides = std::stoi(argv[++i]);
    } else if (a == "--density" && i + 1 < argc) {
      density = std::stod(argv[++i]);
    } else if (a == "--set" && i + 1 < argc) {
      keys.push_back(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_carved_hulls [--threads T] [--hairfit PATH] [--scratch DIR] [--guides N] "
                   "[--density D] [--set KEY=VALUE]…\n");
      return 2;
    }
  }
  std::printf("# Carved hulls at default hair keys\n\nhairfit: %s\nsource at: %s\n--threads %d, %d guides, %g hairs/cm²",
              run.hairfit.c_str(), source_commit().c_str(), run.threads, guides, density);
  for (const std::string& k : keys) std::printf(", hair.%s", k.c_str());
  std::printf("; load average before: %s\n\n", load_average().c_str());
  std::printf("| hull | hull triangles | roots: angle to the carving ° | median angle to the carving ° | against the grain | nodes scored | flow crossing "
              "| guides inside | guides inside, winding | strands inside | coverage | evaluations / guide | guide CPU s |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  try {
    for (CarvedStyle style : all_carved_styles()) {
      const std::string name = carved_style_name(style);
      const fs::path dir = run.scratch / name;
      fs::create_directories(dir);
      const CarvedHull hull = make_carved_hull(style);
      write_obj_mesh(dir / "scalp.obj", hull.scalp);
      write_obj_mesh(dir / "hull.obj", hull.hull);
      {
        std::ofstream s(dir / "scene.toml");
        s << "format = \"hairfit-scene/1\"\nseed = 1\n[units]\nlength = \"cm\"\ndown = [0, -1, 0]\nfront = [0, 0, 1]\n"
             "[inputs]\nscalp = \"scalp.obj\"\nvolume = \"hull.obj\"\n[hair]\ndensity = "
          << density << "\n";
        for (const std::string& k : keys) s << k << "\n";
        s << "[roots]\nguides = " << guides << "\n";
      }
      const RunRecord r = run_hairfit(run.hairfit, dir / "scene.toml", dir / "out", run.threads);
      const Curves guides_read = read_hair_file(dir / "out" / "guides.hair");
      const CarvedFlowScore score = score_carved_flow(style, guides_read);
      const double at_roots = score_roots(style, read_ply_points(dir / "out" / "roots.ply"));
      std::printf("| %s | %zu | %.1f | %.1f | %.3f | %zu | %.3f | %.4f | %.4f | %.4f | %.3f | %.1f | %.2f |\n", name.c_str(),
                  hull.hull.triangles.size(), at_roots, score.median_degrees, score.against, score.nodes,
                  r.figure("guides", "flow_crossing"), r.figure("guides", "inside_fraction"),
                  inside_by_winding(hull, guides_read),
                  r.figure("strands", "inside_fraction"), r.figure("strands", "coverage"),
                  r.figure("guides", "mean_evaluations"), r.stage("guides") ? r.stage("guides")->cpu_seconds : 0.0);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_carved_hulls: %s\n", e.what());
    return 1;
  }
  std::printf("\ntarget: median angle to the carving ≤ 15°, flow crossing ≤ 0.10, guides and strands inside ≥ 0.99, coverage ≥ 0.90, "
              "≤ 30 evaluations a guide\nload average after: %s\n", load_average().c_str());
  return 0;
}
