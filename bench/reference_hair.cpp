// The round trip against reference hair this method did not make (issue 47, item 5): a MakeHuman
// hairstyle's cards become reference hair (lib/reference/reference_cards.h), a hull is voxelised
// from them (reference_hull.h), `hairfit run` fills it at default hair keys (the scalp, the hull,
// the directions, the guides and hairs per cm²: round_trip_scene.h), and the strands are compared
// with the cards point by point at 2 cm / 45° (reference_match.h), as lines and root to tip.
// Prints Markdown; bench/results/reference_hair.md holds its output.
//   bench_reference_hair [--styles braid01,bob01,ponytail01] [--data DIR] [--guides N] [--density D]
//                        [--seed S] [--voxel H] [--dilation R] [--pictures DIR]
//                        [--threads T] [--hairfit PATH] [--scratch DIR]
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runs.h"
#include "io/curve_files.h"
#include "io/obj_mesh.h"
#include "io/png_image.h"
#include "reference/reference_cards.h"
#include "reference/reference_hull.h"
#include "reference/reference_match.h"
#include "reference/round_trip_scene.h"
#include "render/contact_sheet.h"
#include "render/color.h"
#include "render/render_3d.h"

using namespace hairfit;
using namespace hairfit::bench;

namespace {

constexpr double kDecimetre = 10.0;  // MakeHuman's unit, in cm
constexpr double kPointSpacing = 0.5;  // cm between generated points along a fibre

struct Settings {
  RunSettings run{1, 2, HAIRFIT_BINARY, fs::temp_directory_path() / "hairfit-bench-reference-hair"};
  std::vector<std::string> styles{"braid01", "bob01", "ponytail01"};
  fs::path data = fs::path(HAIRFIT_SOURCE_DIR) / "../shared/data/makehuman";
  RoundTripScene scene;  // 600 guides, 50 hairs/cm², seed 1
  ReferenceHullOptions hull;
  fs::path pictures;  // empty: none
};

// The style's cards: the fitted positions of hair_<style>_full.obj with the faces and texture of
// the upstream raw/<style>.obj, whose vertex i it is (checked: same vertices, same fans).
TexturedMesh makehuman_cards(const fs::path& data, const std::string& style, double& fit_shift) {
  TexturedMesh raw = load_obj_textured(data / "raw" / (style + ".obj"), kDecimetre);
  const TexturedMesh fitted = load_obj_textured(data / ("hair_" + style + "_full.obj"), kDecimetre);
  if (fitted.mesh.positions.size() != raw.mesh.positions.size() || fitted.mesh.triangles != raw.mesh.triangles)
    throw std::runtime_error(style + ": the _full mesh does not number its vertices and faces as raw/" + style + ".obj");
  fit_shift = 0.0;
  for (std::size_t i = 0; i < raw.mesh.positions.size(); ++i)
    fit_shift = std::max(fit_shift, (raw.mesh.positions[i] - fitted.mesh.positions[i]).norm());
  raw.mesh.positions = fitted.mesh.positions;
  return raw;
}

// A tick along each point's direction (every `every`th point), 0.6 cm long, in one of `bins`
// curve sets by bin(k).
std::vector<Curves> direction_ticks(const OrientedPoints& p, int every, int bins, const std::function<int(std::size_t)>& bin) {
  std::vector<Curves> out(bins);
  for (std::size_t k = 0; k < p.points.size(); k += every)
    out[bin(k)].add({p.points[k] - 0.3 * p.directions[k], p.points[k] + 0.3 * p.directions[k]});
  return out;
}

// The picture of one view: the scalp, the hull's silhouette, and tick sets in their colours.
Image view_picture(ViewName view, const Mesh& scalp, const Mesh& hull, const std::vector<Curves>& ticks,
                   const std::vector<Color>& colors, int threads) {
  Drawing3D d;
  d.meshes.push_back({&scalp});
  d.meshes.push_back({&hull, MeshStyle::silhouette});
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    CurveLayer layer;
    layer.curves = &ticks[k];
    layer.color = colors[k];
    layer.hair_shading = false;
    layer.root_darkening = 0.6f;  // each tick darker at its root side
    d.curves.push_back(layer);
  }
  const auto [lo, hi] = bounding_box(hull);  // every panel at the hull's scale
  RenderOptions render;
  render.threads = threads;
  return render_3d(d, fit_camera(view, Vec3(0, -1, 0), Vec3(0, 0, 1), lo, hi, 400, 560), render);
}

// Side and back views, three panels each: the reference's sense (its directions' downward
// component: yellow down, purple up), the reference by recall and the generated points by
// precision (green matched, red not), over the scalp and the hull's silhouette.
void write_picture(const fs::path& file, const Mesh& scalp, const Mesh& hull, const OrientedPoints& reference,
                   const OrientedPoints& generated, const MatchOptions& o, int threads) {
  constexpr int kSenseBins = 5;
  std::vector<Color> sense_colors;
  for (int b = 0; b < kSenseBins; ++b) sense_colors.push_back(sequential_color((b + 0.5) / kSenseBins));
  const std::vector<Curves> sense = direction_ticks(reference, 1, kSenseBins, [&](std::size_t k) {
    const double down = -reference.directions[k].y();  // in [−1, 1]
    return std::min(kSenseBins - 1, static_cast<int>((down + 1.0) / 2.0 * kSenseBins));
  });
  const std::vector<unsigned char> recalled = matched_points(reference, generated, o);
  const std::vector<unsigned char> precise = matched_points(generated, reference, o);
  const std::vector<Curves> by_recall = direction_ticks(reference, 1, 2, [&](std::size_t k) { return recalled[k]; });
  const int every = std::max<int>(1, static_cast<int>(generated.points.size() / 40000));
  const std::vector<Curves> by_precision = direction_ticks(generated, every, 2, [&](std::size_t k) { return precise[k]; });
  const std::vector<Color> match_colors = {{0.95f, 0.25f, 0.2f}, {0.25f, 0.85f, 0.35f}};
  std::vector<Image> images;
  std::vector<std::string> captions;
  for (const ViewName view : {ViewName::side, ViewName::back}) {
    const std::string seen = view == ViewName::side ? ", side" : ", back";
    images.push_back(view_picture(view, scalp, hull, sense, sense_colors, threads));
    captions.push_back("reference sense" + seen);
    images.push_back(view_picture(view, scalp, hull, by_recall, match_colors, threads));
    captions.push_back("recall" + seen);
    images.push_back(view_picture(view, scalp, hull, by_precision, match_colors, threads));
    captions.push_back("precision" + seen);
  }
  write_png(file, contact_sheet(images, captions, 3));
}

void print_figures(const char* sense, const MatchFigures& m, double coverage) {
  std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.1f | %.3f | %.3f |\n", sense, m.precision, m.recall, m.f, m.reached,
              m.median_angle, m.near, coverage);
}

void round_trip(const Settings& s, const std::string& style) {
  double fit_shift = 0.0;
  const TexturedMesh cards = makehuman_cards(s.data, style, fit_shift);
  const Mesh scalp = load_obj_mesh(s.data / "scalp.obj", kDecimetre).mesh;
  const ReferenceHair reference = reference_from_cards(cards, scalp);
  ReferenceHullOptions hull_options = s.hull;
  hull_options.threads = s.run.threads;
  const ReferenceHull hull = reference_hull(cards.mesh, scalp, hull_options);

  const fs::path dir = s.run.scratch / style;
  fs::create_directories(dir);
  write_obj_mesh(dir / "scalp.obj", scalp);
  write_obj_mesh(dir / "hull.obj", hull.mesh);
  std::ofstream(dir / "scene.toml") << round_trip_scene_text(s.scene);
  const RunRecord run = run_hairfit(s.run.hairfit, dir / "scene.toml", dir / "out", s.run.threads);
  const Curves fibres = read_hair_file(dir / "out" / "strands.hair");
  const OrientedPoints generated = curve_points(fibres, kPointSpacing);
  std::vector<double> lengths;
  for (std::size_t c = 0; c < fibres.count(); ++c) {
    double length = 0.0;
    for (std::size_t k = 0; k + 1 < fibres.size(c); ++k) length += (fibres.point(c, k + 1) - fibres.point(c, k)).norm();
    lengths.push_back(length);
  }

  int islands = 0, along_u = 0, sensed = 0;
  for (const CardIsland& i : reference.islands) {
    if (!i.used) continue;
    ++islands, along_u += i.along == 0, sensed += i.sense_from_scalp;
  }
  std::printf("\n## %s\n\n", style.c_str());
  std::printf("Cards: %zu triangles (vertex i of hair_%s_full.obj is vertex i of raw/%s.obj, moved by the fit up to "
              "%.1f cm); %d UV islands used of %zu (%.1f %% of %.0f cm²), %d of them along u; the scalp decides the "
              "root on %d (%.1f %% of the used area), the texture's top on the rest. Reference points: %zu "
              "(4 per cm²).\n\n",
              cards.mesh.triangles.size(), style.c_str(), style.c_str(), fit_shift, islands, reference.islands.size(),
              100.0 * reference.used_area / reference.total_area, reference.total_area, along_u, sensed,
              100.0 * reference.sensed_area / reference.used_area, reference.samples.points.size());
  std::printf("| island (≥ 2 %% of the area) | triangles | cm² | along | ends apart cm | across cm | root / tip "
              "from the scalp cm | root from |\n|---:|---:|---:|---|---:|---:|---:|---|\n");
  for (std::size_t k = 0; k < reference.islands.size(); ++k) {
    const CardIsland& i = reference.islands[k];
    if (i.area < 0.02 * reference.total_area) continue;
    std::printf("| %zu | %d | %.0f | %s, root at its %s | %.1f | %.1f | %.1f / %.1f | %s |\n", k, i.triangles, i.area,
                i.along ? "v" : "u", i.root_at_high ? "top" : "bottom", i.end_separation, i.across_separation,
                i.root_scalp_distance, i.tip_scalp_distance, i.sense_from_scalp ? "the scalp" : "the texture's top");
  }
  std::printf("\n");
  std::printf("Hull: %zu triangles, %.1f cm voxels, %.1f cm beyond the cards and the scalp, %lld enclosed nodes "
              "filled.\n\n",
              hull.mesh.triangles.size(), hull_options.voxel, hull_options.dilation,
              static_cast<long long>(hull.filled_nodes));
  std::printf("Run: %zu fibres, median length %.1f cm, guides inside %.4f, strands inside %.4f, %.1f evaluations a "
              "guide, run CPU %.1f s; %d generated points (every %.1f cm of fibre).\n\n",
              fibres.count(), median(lengths),
              run.figure("guides", "inside_fraction"), run.figure("strands", "inside_fraction"),
              run.figure("guides", "mean_evaluations"), run.usage.cpu(), static_cast<int>(generated.points.size()),
              kPointSpacing);
  std::printf("| directions | precision | recall | F | reached | median angle ° | near | coverage |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|\n");
  MatchOptions o;
  o.threads = s.run.threads;
  const double coverage = run.figure("strands", "coverage");
  print_figures("as lines", match_reference(generated, reference.samples, o), coverage);
  MatchOptions signed_o = o;
  signed_o.signed_directions = true;
  print_figures("root to tip", match_reference(generated, reference.samples, signed_o), coverage);
  std::printf("| issue 47 target | | | ≥ 0.90 | ≥ 0.95 | | | ≥ 0.90 |\n");
  if (!s.pictures.empty()) {
    fs::create_directories(s.pictures);
    const fs::path file = s.pictures / (style + ".png");
    write_picture(file, scalp, hull.mesh, reference.samples, generated, o, s.run.threads);
    std::printf("\nPicture: %s\n", file.c_str());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    if (parse_run_option(argc, argv, i, s.run)) continue;
    const std::string a = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (!value) {
      std::fprintf(stderr, "bench_reference_hair: %s needs a value\n", a.c_str());
      return 2;
    }
    ++i;
    if (a == "--styles") {
      s.styles.clear();
      std::stringstream list(value);
      for (std::string style; std::getline(list, style, ',');) s.styles.push_back(style);
    } else if (a == "--data") s.data = value;
    else if (a == "--guides") s.scene.guides = std::atoi(value);
    else if (a == "--density") s.scene.density = std::atof(value);
    else if (a == "--seed") s.scene.seed = std::atoll(value);
    else if (a == "--voxel") s.hull.voxel = std::atof(value);
    else if (a == "--dilation") s.hull.dilation = std::atof(value);
    else if (a == "--pictures") s.pictures = value;
    else {
      std::fprintf(stderr, "usage: bench_reference_hair [--styles a,b] [--data DIR] [--guides N] [--density D] [--seed S] "
                           "[--voxel H] [--dilation R] [--pictures DIR] [--threads T] [--hairfit PATH] [--scratch DIR]\n");
      return 2;
    }
  }
  std::string command = "build/bench/bench_reference_hair";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::printf("# Round trip against MakeHuman reference hair (issue 47, item 5)\n\n`%s`\n\nhairfit: %s\nsource at: %s\n"
              "%d guides, %g hairs/cm², seed %lld, every other hair key at its default; --threads %d; load average "
              "before: %s\n",
              command.c_str(), s.run.hairfit.c_str(), source_commit().c_str(), s.scene.guides, s.scene.density,
              static_cast<long long>(s.scene.seed), s.run.threads, load_average().c_str());
  try {
    for (const std::string& style : s.styles) round_trip(s, style);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_reference_hair: %s\n", e.what());
    return 1;
  }
  std::printf("\nload average after: %s\n", load_average().c_str());
  return 0;
}
