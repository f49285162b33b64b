#include "prepare/prepare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/obj_mesh.h"
#include "core/fast_winding.h"
#include "field/hair_region.h"
#include "prepare/scalp_level_set.h"
#include "prepare/surface_checks.h"
#include "scalp/shell_hair.h"
#include "prepare/refine.h"
#include "prepare/weld.h"
#include "spec/scene.h"

namespace hairfit {

namespace {

constexpr double kSnapDegrees = 35.0;
// The whorl the written scene declares (hair.swirl): on the six sculpted busts it takes the flow
// crossing from 0.51–0.61 to 0.12–0.28 and keeps 0.995–0.999 of the strand points inside
// (0.996–0.997 without); at 89° the plain bust keeps only 0.989.
constexpr double kPreparedSwirl = 70.0;

std::string vec_text(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g)", v.x(), v.y(), v.z());
  return text;
}

std::string toml_vector(const Vec3& v) {
  char text[96];
  auto clean = [](double x) { return std::abs(x) < 1e-12 ? 0.0 : x; };
  std::snprintf(text, sizeof text, "[%.6g, %.6g, %.6g]", clean(v.x()), clean(v.y()), clean(v.z()));
  return text;
}

// The signed coordinate axis nearest to `d` (unit), and the angle to it in degrees.
std::pair<Vec3, double> nearest_axis(const Vec3& d, const Vec3& orthogonal_to = Vec3::Zero()) {
  Vec3 best = Vec3::Zero();
  double best_cos = -2.0;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      const Vec3 e = sign * Vec3::Unit(axis);
      if (std::abs(e.dot(orthogonal_to)) > 1e-9) continue;
      if (e.dot(d) > best_cos) best_cos = e.dot(d), best = e;
    }
  return {best, std::acos(std::clamp(best_cos, -1.0, 1.0)) * 180.0 / M_PI};
}

// Scans are exported axis-aligned in practice, while the hair cap leans back by 20–30°: a detected
// direction within kSnapDegrees of a coordinate axis is taken as that axis.
Vec3 snapped(const Vec3& d, const Vec3& orthogonal_to, std::string& how, const std::string& what) {
  const auto [axis, angle] = nearest_axis(d, orthogonal_to);
  char text[256];
  if (angle <= kSnapDegrees) {
    std::snprintf(text, sizeof text, "detected: %s %s, %.0f° from the axis %s, taken as the axis", what.c_str(),
                  vec_text(d).c_str(), angle, vec_text(axis).c_str());
    how = text;
    return axis;
  }
  std::snprintf(text, sizeof text, "detected: %s %s (no coordinate axis within %.0f°)", what.c_str(),
                vec_text(d).c_str(), kSnapDegrees);
  how = text;
  return d;
}

// Up: the hair cap's vector area Σ ½(b − a)×(c − a) (outward triangles) points from the
// hairline's plane toward the crown — up, leaning back. Front: the opposite of its horizontal
// part, since hair covers the back of the head more than the forehead.
void detect_directions(const Hull& hull, const PrepareOptions& o, Prepared& p) {
  Vec3 vector_area = Vec3::Zero();
  for (const Vec3i& t : hull.mesh.triangles) {
    const Vec3& a = hull.mesh.positions[t[0]];
    vector_area += 0.5 * (hull.mesh.positions[t[1]] - a).cross(hull.mesh.positions[t[2]] - a);
  }
  if (o.up) {
    p.up = o.up->normalized();
    p.up_how = "declared";
  } else {
    p.up = snapped(vector_area.normalized(), Vec3::Zero(), p.up_how, "the hair cap faces");
  }
  if (o.front) {
    p.front = (*o.front - o.front->dot(p.up) * p.up).normalized();
    p.front_how = "declared";
    return;
  }
  const Vec3 horizontal = -(vector_area - vector_area.dot(p.up) * p.up);
  if (horizontal.norm() > std::sin(5.0 * M_PI / 180.0) * vector_area.norm()) {
    p.front = snapped(horizontal.normalized(), p.up, p.front_how, "the hair leans away from");
    p.front = (p.front - p.front.dot(p.up) * p.up).normalized();
    return;
  }
  // A symmetric cap says nothing about the face: the usual convention of the up axis.
  const auto [axis, angle] = nearest_axis(p.up);
  p.front = std::abs(axis.z()) > 0.5 ? Vec3(0, -1, 0) : Vec3(0, 0, 1);
  p.front = (p.front - p.front.dot(p.up) * p.up).normalized();
  p.front_how = "assumed (the hair is symmetric front to back; declare --front)";
  (void)angle;
}

double scale_for(const Mesh& scan, const Vec3& up, const PrepareOptions& o, const std::string& file) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3& p : scan.positions) lo = std::min(lo, p.dot(up)), hi = std::max(hi, p.dot(up));
  double scale = 1.0;
  if (o.head_height > 0.0) {
    scale = o.head_height / (hi - lo);
  } else {
    const std::vector<std::string> units{"mm", "cm", "dm", "m", "in"};
    if (std::find(units.begin(), units.end(), o.units) == units.end())
      throw InputError("--units", "unknown unit \"" + o.units + "\"; valid: mm, cm, dm, m, in");
    SceneUnits u;
    u.length = o.units;
    scale = u.to_cm();
  }
  const double height = (hi - lo) * scale;
  if (height < 5.0 || height > 150.0) {
    char text[384];
    std::snprintf(text, sizeof text,
                  "the scan is %.4g cm tall along up %s when read in %s, which is no bust or head; declare the "
                  "scan's unit with --units mm|cm|dm|m|in or its height with --head-height H (cm)",
                  height, vec_text(up).c_str(), o.head_height > 0.0 ? "the declared height" : o.units.c_str());
    throw InputError(file, text);
  }
  return scale;
}

// `base` with the scalp added, scalp vertex v taken as base vertex shared[v] where that is ≥ 0,
// turned over when `reversed`.
Mesh with_scalp(Mesh base, const std::vector<int>& shared, const Prepared& p, bool reversed) {
  const Mesh& scalp = p.scalp.scalp;
  std::vector<int> index = shared;
  for (std::size_t v = 0; v < scalp.positions.size(); ++v) {
    if (index[v] >= 0) continue;
    index[v] = static_cast<int>(base.positions.size());
    base.positions.push_back(scalp.positions[v]);
  }
  for (const Vec3i& t : scalp.triangles)
    base.triangles.emplace_back(index[t[0]], index[reversed ? t[2] : t[1]], index[reversed ? t[1] : t[2]]);
  return base;
}

// The checks that failed, each a clause ("the hull is not a disk"), joined by "; ": empty when all
// passed.
std::string failures(const PrepareChecks& c, const Vec3& origin) {
  std::vector<std::string> failed;
  if (!c.hull_disk) failed.push_back("the hull is not a disk");
  if (!c.scalp_disk) failed.push_back("the scalp is not a disk");
  if (c.scalp_inward_triangles)
    failed.push_back(std::to_string(c.scalp_inward_triangles) + " scalp triangles face inward (e.g. at " +
                     vec_text(c.first_inward + origin) + ")");
  if (c.intersections)
    failed.push_back("hull, floor and scalp intersect (" + std::to_string(c.intersections) + " pairs, e.g. at " +
                     vec_text(c.first_intersection + origin) + ")");
  if (!(c.deepest_winding > 0.5)) failed.push_back("the scalp is not inside the hull");
  if (!c.hairline_shared) failed.push_back("the scalp's hairline differs from the hull's");
  std::string text;
  for (const std::string& f : failed) text += (text.empty() ? "" : "; ") + f;
  return text;
}

// How far check() goes: every check, for a scalp that is kept and reported; or up to the first
// check that fails, for a trial whose failure only decides that another method is tried (the
// checks cost about as much as the radial scalp itself on a 270 000-triangle scan).
enum class CheckScope { all, until_failure };

PrepareChecks check(const Prepared& p, int threads, CheckScope scope = CheckScope::all) {
  PrepareChecks c;
  const Mesh& hull = p.hull.mesh;
  const Mesh& scalp = p.scalp.scalp;
  const bool stop_early = scope == CheckScope::until_failure;
  // The cheap checks first: topology, the shared hairline, and the winding number at the deepest
  // scalp vertex.
  c.hull_disk = analyse_topology(hull).is_disk();
  c.scalp_disk = analyse_topology(scalp).is_disk();
  c.hairline_shared = p.scalp.hairline.size() == p.hull.hairline.size();
  for (std::size_t k = 0; c.hairline_shared && k < p.scalp.hairline.size(); ++k)
    c.hairline_shared = scalp.positions[p.scalp.hairline[k]] == hull.positions[p.hull.hairline[k]];
  const int deepest = static_cast<int>(std::max_element(p.scalp.thickness.begin(), p.scalp.thickness.end()) -
                                       p.scalp.thickness.begin());
  c.deepest_winding = winding_number(p.scalp.volume, scalp.positions[deepest]);
  if (stop_early && !failures(c, Vec3::Zero()).empty()) return c;  // the checks not yet run read as passed
  // Facing: just in front of each scalp triangle lies the layer, inside the hull closed by the
  // reversed scalp (facing_out_of; the step shrinks for the strip's slivers).
  std::vector<int> on_hull(scalp.positions.size(), -1);
  for (std::size_t k = 0; k < p.scalp.hairline.size(); ++k) on_hull[p.scalp.hairline[k]] = p.hull.hairline[k];
  const FastWindingNumber layer(with_scalp(hull, on_hull, p, true), HairRegion::kFirstBeta, threads);
  const std::vector<int> inward = facing_out_of(scalp, layer, threads);
  c.scalp_inward_triangles = static_cast<int>(inward.size());
  if (!inward.empty()) c.first_inward = triangle_centroid(scalp, inward[0]);
  if (stop_early && c.scalp_inward_triangles > 0) return c;
  // One mesh of hull, floor and scalp sharing the hairline: any crossing among them shows up as a
  // self-intersection.
  const Mesh all = with_scalp(p.scalp.volume, p.scalp.volume_vertex, p, false);
  const auto pairs = self_intersections(all, 16, threads);
  c.intersections = static_cast<int>(pairs.size());
  if (!pairs.empty()) c.first_intersection = triangle_centroid(all, pairs[0].first);
  if (stop_early && c.intersections > 0) return c;
  const std::vector<double> curvature = mean_curvature(scalp);
  std::vector<double> under;
  for (std::size_t v = 0; v < curvature.size(); ++v)
    if (p.scalp.ramp[v] >= 0.5) under.push_back(curvature[v]);
  if (!under.empty()) {
    std::sort(under.begin(), under.end());
    c.curvature_p95 = under[static_cast<std::size_t>(0.95 * (under.size() - 1))];
    c.curvature_max = under.back();
  }
  return c;
}

// For a refusal: where the scan crosses itself, since that is then the likeliest cause (the hull
// cut from it is untangled, but skin through the hair, or folds no smoothing clears, remain).
// Only on this path: the search costs about a tenth of preparing.
std::string crossing_note(const Mesh& scan, const Prepared& p, int threads) {
  const auto pairs = self_intersections(scan, kMaxUntanglePairs, threads);
  if (pairs.empty()) return "";
  const Vec3 at = triangle_centroid(scan, pairs[0].first) * p.scale_to_cm + p.origin;
  return "; the scan crosses itself at " + std::to_string(pairs.size()) + (pairs.size() >= static_cast<std::size_t>(kMaxUntanglePairs) ? " or more" : "") +
         " pairs of triangles (e.g. at " + vec_text(at) + ")";
}

double max_thickness(const Prepared& p) {
  return p.scalp.thickness.empty() ? 0.0 : *std::max_element(p.scalp.thickness.begin(), p.scalp.thickness.end());
}

Prepared prepare_centred(const Mesh& raw_scan, const std::vector<Vec3>& colors, const PrepareOptions& o,
                         const std::string& file, const Vec3& origin) {
  Prepared p;
  p.origin = origin;  // in scan units until the scale is known
  const auto [lo, hi] = bounding_box(raw_scan);
  const double tolerance = o.weld_tolerance >= 0.0 ? o.weld_tolerance : 1e-6 * (hi - lo).norm();
  const Welded welded = weld_vertices(raw_scan, tolerance);
  p.welded_vertices = welded.merged_vertices;
  std::vector<Vec3> welded_colors;
  if (colors.size() == raw_scan.positions.size())
    for (int old : welded.new_to_old) welded_colors.push_back(colors[old]);
  // A coarse scan (median edge beyond 1/40 of its size: 1 cm on a bust) is split into smaller
  // flat triangles first (refine.h), and prepare.json says so.
  const Refined refined = refine_coarse_scan(welded.mesh, welded_colors, (hi - lo).maxCoeff() / 40.0);
  p.refine_splits = refined.splits;
  p.median_edge_before = refined.median_edge_before;
  p.median_edge_after = refined.median_edge_after;
  welded_colors = refined.colors;
  const Mesh& scan = refined.mesh;

  const SelectionField field = selection_field(scan, welded_colors, o.selection, file);
  p.hull = cut_hull(scan, field, o.hull, file);
  detect_directions(p.hull, o, p);
  p.scale_to_cm = scale_for(scan, p.up, o, file);
  p.origin *= p.scale_to_cm;  // where the checks' messages place what they found, in cm
  for (Vec3& x : p.hull.mesh.positions) x *= p.scale_to_cm;
  // Noise that folds the scan's small triangles over their neighbours makes the hull cross
  // itself: those neighbourhoods are smoothed (untangle.h; the hairline stays, so hull and skin
  // still meet there). The skin is not written, so its folds are left.
  p.untangled = untangle_self_intersections(p.hull.mesh, o.threads);
  if (p.untangled.pairs_found > 0) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "the hull crossed itself (%d pairs of triangles, e.g. at %s): %d vertices around them smoothed in "
                  "%d round%s, moved %.3g cm at most",
                  p.untangled.pairs_found, vec_text(p.untangled.first_found + p.origin).c_str(), p.untangled.vertices_moved,
                  p.untangled.rounds, p.untangled.rounds == 1 ? "" : "s", p.untangled.largest_move);
    p.repairs.push_back(text + (p.untangled.pairs_left > 0 ? ", " + std::to_string(p.untangled.pairs_left) + " pairs left" : ""));
  }
  p.hull.centre *= p.scale_to_cm;
  p.hull.selected_area *= p.scale_to_cm * p.scale_to_cm;
  p.hull.kept_area *= p.scale_to_cm * p.scale_to_cm;
  p.hull.hairline_length *= p.scale_to_cm;
  if (o.scalp_method != "auto" && o.scalp_method != "radial" && o.scalp_method != "level-set")
    throw InputError("--scalp", "unknown scalp method \"" + o.scalp_method + "\"; valid: auto, radial, level-set");
  std::string radial_failed;
  if (o.scalp_method != "level-set") {
    const int facing = static_cast<int>(inward_triangles(p.hull.mesh, p.hull.centre).size());
    if (facing > 0 && o.scalp_method == "auto") {
      radial_failed = std::to_string(facing) + " of the hull's " + std::to_string(p.hull.mesh.triangles.size()) +
                      " triangles face the head centre (it overhangs, folds or lies in tubes)";
    } else {
      p.scalp = make_scalp(p.hull, o.scalp, file);
      // Under `auto` a failing radial scalp is set aside for the level set, and only the first
      // failure is named; a declared radial scalp is checked in full for the report. The radial
      // scalp is star-shaped about the head centre as its hull is, unless it folds: a triangle
      // facing the centre sets it aside before the checks (a tenth of their cost). On every
      // sculpted bust and spacing measured, such a fold is what the checks then refuse (scalp
      // facing into the head, or crossing the hull or floor), and no radial scalp the checks pass
      // has one.
      const int folded = o.scalp_method == "auto" ? static_cast<int>(inward_triangles(p.scalp.scalp, p.hull.centre).size()) : 0;
      if (folded > 0) {
        radial_failed = std::to_string(folded) + " of the radial scalp's triangles face the head centre (it folds)";
      } else {
        p.checks = check(p, o.threads, o.scalp_method == "auto" ? CheckScope::until_failure : CheckScope::all);
        radial_failed = failures(p.checks, p.origin);
        if (radial_failed.empty() || o.scalp_method == "radial") p.scalp_how = "radial: the hull is star-shaped about the head centre";
      }
    }
  }
  if (p.scalp_how.empty()) {
    // The rest of the scan, cut at the same hairline, tells the level set where the skin is.
    SelectionField bare = field;
    for (double& f : bare.values) f = -f;
    if (field.at) bare.at = [at = field.at](const Vec3& x) { return -at(x); };
    Mesh skin = clip_at_level_set(scan, bare, o.hull.clip).mesh;
    for (Vec3& x : skin.positions) x *= p.scale_to_cm;
    p.scalp_how = o.scalp_method == "level-set" ? "level set: declared" : "level set: the radial scalp cannot be used here (" + radial_failed + ")";
    // The level set is resolved on a grid, and where hull and skin meet at a sharp, zigzag
    // hairline one grid can leave a strip clipping the hull that another does not: without a
    // declared voxel, two more are tried (0.8 and 1.25 times the default) before giving up.
    const double voxel = level_set_voxel(o.scalp);
    std::string tried;
    bool passed = false;
    for (double factor : {1.0, 0.8, 1.25}) {
      if (factor != 1.0 && o.scalp.voxel > 0.0) break;
      ScalpOptions grid = o.scalp;
      grid.voxel = factor * voxel;
      std::string failed;
      try {
        p.scalp = make_level_set_scalp(p.hull, skin, grid, file, o.threads);
        p.checks = check(p, o.threads);
        failed = failures(p.checks, p.origin);
      } catch (const InputError& e) {
        failed = e.what();
      }
      char text[64];
      std::snprintf(text, sizeof text, "%.3g cm", grid.voxel);
      if (failed.empty()) {
        if (!tried.empty()) p.scalp_how += "; voxel " + std::string(text) + " after " + tried;
        passed = true;
        break;
      }
      tried += (tried.empty() ? "" : "; ") + std::string(text) + " failed: " + failed;
    }
    if (!passed)
      throw InputError(file, "the level-set scalp derived from this hull fails its checks at every voxel tried (" +
                                 tried + ")" + crossing_note(scan, p, o.threads) +
                                 "; try a smaller --crown-thickness or a longer --ramp, or repair the scan near the hairline");
    if (p.scalp.scalp_holes_filled + p.scalp.floor_holes_filled > 0) {
      char text[320];
      std::snprintf(text, sizeof text,
                    "the level set had holes where the layer thins inside the hair: %d in the scalp, %d in the floor "
                    "(the longest %.3g cm), filled",
                    p.scalp.scalp_holes_filled, p.scalp.floor_holes_filled, p.scalp.longest_hole_filled);
      p.repairs.push_back(text);
    }
    if (p.scalp.dropped_parts > 0)
      p.repairs.push_back("the level set had " + std::to_string(p.scalp.dropped_parts) +
                          " pieces apart from the scalp and floor under the hair: left out");
    if (p.scalp.strip_feet > 0)
      p.repairs.push_back("the level-set scalp's strip crossed the hull near the hairline: lowered under " +
                          std::to_string(p.scalp.strip_feet) + " hairline vertices");
  }
  const std::string failed = failures(p.checks, p.origin);
  if (!failed.empty())
    throw InputError(file, "the scalp derived from this hull (" + p.scalp.method + ") fails its checks: " + failed +
                               crossing_note(scan, p, o.threads) +
                               "; try a smaller --crown-thickness or a longer --ramp, or repair the scan near the hairline");
  return p;
}

}  // namespace

Prepared prepare_scan(const Mesh& input_scan, const std::vector<Vec3>& colors, const PrepareOptions& input_options,
                      const std::string& file) {
  // Everything is computed about the data's centre (frame_origin) and moved back at the end.
  const auto [lo, hi] = bounding_box(input_scan);
  const Vec3 origin = frame_origin(lo, hi);
  Mesh raw_scan = input_scan;
  for (Vec3& x : raw_scan.positions) x -= origin;
  PrepareOptions o = input_options;
  o.selection.point -= origin;
  o.selection.centre -= origin;
  Prepared p = prepare_centred(raw_scan, colors, o, file, origin);
  const Vec3 shift = origin * p.scale_to_cm;
  p.origin = shift;
  for (Mesh* mesh : {&p.hull.mesh, &p.scalp.scalp, &p.scalp.volume})
    for (Vec3& x : mesh->positions) x += shift;
  p.hull.centre += shift;
  return p;
}

namespace {

// The unit the meshes are written in: the scan's own, or cm when the scan was scaled to a declared
// head height (no unit names that scale).
std::string written_unit(const PrepareOptions& o) { return o.head_height > 0.0 ? "cm" : o.units; }

}  // namespace

std::string prepared_scene_text(const Prepared& p, const std::string& scan_name, const PrepareOptions& o) {
  char scaled[96];
  std::snprintf(scaled, sizeof scaled, "the scan was scaled by %.6g to cm (--head-height)", p.scale_to_cm);
  const std::string unit_comment = o.head_height > 0.0 ? scaled : "the meshes are in the scan's own frame and unit";
  // What the run will derive from the layer (scalp/shell_hair.h), for the comment.
  const ShellHair shell = hair_for_shell(o.scalp.crown_thickness, p.scalp.hairline_reach);
  char text[4096];
  std::snprintf(
      text, sizeof text,
      "# Written by `hairfit prepare` from %s: hair = %s; scalp by %s; crown thickness %.4g cm, ramp %.4g cm.\n"
      "# Keys not written here take their defaults (spec/reference.md); edit freely.\n"
      "format = \"%s\"\n"
      "seed = 1\n"
      "\n"
      "[units]\n"
      "length = \"%s\"               # %s\n"
      "down = %s    # up %s\n"
      "front = %s   # %s\n"
      "\n"
      "[inputs]\n"
      "scalp = \"scalp.obj\"\n"
      "volume = \"volume.obj\"\n"
      "\n"
      "[effects]\n"
      "cutting = true               # a scanned hull is tight: fibres that leave it for long are cut\n"
      "\n"
      "# Hair that fits the shell: 0 cm thick at the hairline, %.3g cm over the crown, and no point of it\n"
      "# farther than %.3g cm from the hairline. hair.length and hair.tilt are left to the run, which\n"
      "# derives them from the layer (about %.1f cm at %.0f°) with the thin-shell defaults: roots tilt\n"
      "# toward the thicker layer along a growth field steered by the hull's relief, pre-guides and\n"
      "# guides run in the layer, and fibres that skim out of it are held in. Set them here to choose\n"
      "# otherwise.\n"
      "[hair]\n"
      "swirl = %.0f                   # degrees: roots turn so the hair spirals into the crown like a whorl; turned\n"
      "                             # straight to the thicker layer it would meet there from every side\n",
      scan_name.c_str(), o.selection.describe().c_str(), p.scalp.method.c_str(), o.scalp.crown_thickness,
      p.scalp.ramp_length, kSceneFormat, written_unit(o).c_str(), unit_comment.c_str(), toml_vector(-p.up).c_str(), p.up_how.c_str(),
      toml_vector(p.front).c_str(), p.front_how.c_str(), max_thickness(p), p.scalp.hairline_reach, shell.length,
      shell.tilt, kPreparedSwirl);
  return text;
}

void write_prepared(const Prepared& p, const std::filesystem::path& scan, const PrepareOptions& o,
                    const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(dir.string(), "exists and is not a folder; --out names the folder to write the scene into");
  using Json = nlohmann::ordered_json;
  const auto vec = [](const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); };
  Json record;
  record["format"] = "hairfit-prepare/1";
  record["scan"] = fs::absolute(scan).lexically_normal().string();
  record["scale_to_cm"] = p.scale_to_cm;
  record["meshes_unit"] = written_unit(o);
  record["selection"] = o.selection.describe();
  record["up"] = vec(p.up);
  record["up_how"] = p.up_how;
  record["front"] = vec(p.front);
  record["front_how"] = p.front_how;
  record["welded_vertices"] = p.welded_vertices;
  record["refined"] = {{"splits", p.refine_splits},
                       {"median_edge_before_cm", p.median_edge_before * p.scale_to_cm},
                       {"median_edge_after_cm", p.median_edge_after * p.scale_to_cm}};
  record["untangled"] = {{"pairs_found", p.untangled.pairs_found},
                         {"pairs_left", p.untangled.pairs_left},
                         {"rounds", p.untangled.rounds},
                         {"vertices_moved", p.untangled.vertices_moved},
                         {"largest_move_cm", p.untangled.largest_move}};
  record["repaired"] = p.repairs;
  record["hull"] = {{"triangles", p.hull.mesh.triangles.size()},
                    {"area_cm2", p.hull.kept_area},
                    {"selected_triangles", p.hull.selected_triangles},
                    {"cut_triangles", p.hull.cut_triangles},
                    {"snapped_vertices", p.hull.snapped_vertices},
                    {"selected_parts", p.hull.parts},
                    {"selected_area_cm2", p.hull.selected_area},
                    {"shaved_triangles", p.hull.shaved_triangles},
                    {"holes_filled", p.hull.holes_filled},
                    {"hairline_cm", p.hull.hairline_length},
                    {"centre", vec(p.hull.centre)}};
  record["scalp"] = {{"method", p.scalp.method},
                     {"method_how", p.scalp_how},
                     {"triangles", p.scalp.scalp.triangles.size()},
                     {"area_cm2", surface_area(p.scalp.scalp)},
                     {"crown_thickness_cm", o.scalp.crown_thickness},
                     {"ramp_cm", p.scalp.ramp_length},
                     {"hairline_reach_cm", p.scalp.hairline_reach},
                     {"max_thickness_cm", max_thickness(p)},
                     {"envelope_rms_cm", p.scalp.envelope_rms},
                     {"envelope_outliers", p.scalp.envelope_outliers},
                     {"dropped_parts", p.scalp.dropped_parts},
                     {"scalp_holes_filled", p.scalp.scalp_holes_filled},
                     {"floor_holes_filled", p.scalp.floor_holes_filled},
                     {"longest_hole_filled_cm", p.scalp.longest_hole_filled},
                     {"strip_feet", p.scalp.strip_feet}};
  record["checks"] = {{"hull_disk", p.checks.hull_disk},
                      {"scalp_disk", p.checks.scalp_disk},
                      {"scalp_inward_triangles", p.checks.scalp_inward_triangles},
                      {"intersections", p.checks.intersections},
                      {"deepest_winding", p.checks.deepest_winding},
                      {"hairline_shared", p.checks.hairline_shared},
                      {"scalp_curvature_p95_per_cm", p.checks.curvature_p95},
                      {"scalp_curvature_max_per_cm", p.checks.curvature_max}};
  const std::string scene = prepared_scene_text(p, scan.filename().string(), o);
  // The meshes go out in the scan's own unit (units.length), as the scan came in; with a declared
  // head height no unit is named and they stay in cm.
  const double to_cm = o.head_height > 0.0 ? 1.0 : p.scale_to_cm;
  auto in_scan_unit = [to_cm](Mesh mesh) {
    if (to_cm != 1.0)
      for (Vec3& x : mesh.positions) x /= to_cm;
    return mesh;
  };
  write_obj_mesh(dir / "volume.obj", in_scan_unit(p.scalp.volume));
  write_obj_mesh(dir / "scalp.obj", in_scan_unit(p.scalp.scalp));
  write_text_file_atomically(dir / "prepare.json", record.dump(2) + "\n");
  write_text_file_atomically(dir / "scene.toml", scene);
}

}  // namespace hairfit
