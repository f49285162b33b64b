// hairfit prepare SCAN.obj --out DIR (--plane P|--cap C|--mask RGB [--mask-tolerance D] [--mask-smoothing N])
//   [--units U | --head-height H]
//   [--up x,y,z] [--front x,y,z] [--crown-thickness T] [--ramp R] [--max-hole F] [--weld D]
//   [--scalp auto|radial|level-set] [--scalp-voxel H] [--threads N]
// From one raw scan to a ready-to-run scene: DIR/volume.obj, DIR/scalp.obj, DIR/scene.toml and
// DIR/prepare.json (lib/prepare/prepare.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "io/obj_mesh.h"
#include "pipeline/prepared_scene.h"
#include "prepare/prepare.h"

namespace hairfit::cli {

namespace {

std::vector<double> numbers(const Args& args, const std::string& name, std::size_t count, const std::string& form) {
  std::stringstream in(*args.text(name));
  std::string part;
  std::vector<double> out;
  while (std::getline(in, part, ',')) {
    char* end = nullptr;
    const double x = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(x))
      throw UsageError{"--" + name + " needs " + form + ", not \"" + *args.text(name) + "\""};
    out.push_back(x);
  }
  if (out.size() != count) throw UsageError{"--" + name + " needs " + form + ", not \"" + *args.text(name) + "\""};
  return out;
}

HairSelection selection(const Args& args) {
  const int given = args.has("plane") + args.has("cap") + args.has("mask");
  if (given != 1)
    throw UsageError{"select the hair with exactly one of --plane px,py,pz,nx,ny,nz, --cap cx,cy,cz,ax,ay,az,DEG "
                     "or --mask R,G,B (scan coordinates and colours)"};
  HairSelection s;
  if (args.has("plane")) {
    const auto v = numbers(args, "plane", 6, "a point and a normal, px,py,pz,nx,ny,nz");
    s.kind = HairSelection::Kind::plane;
    s.point = Vec3(v[0], v[1], v[2]);
    s.normal = Vec3(v[3], v[4], v[5]);
    if (s.normal.norm() == 0.0) throw UsageError{"--plane needs a non-zero normal"};
  } else if (args.has("cap")) {
    const auto v = numbers(args, "cap", 7, "a centre, an axis and a half-angle in degrees, cx,cy,cz,ax,ay,az,DEG");
    s.kind = HairSelection::Kind::cap;
    s.centre = Vec3(v[0], v[1], v[2]);
    s.axis = Vec3(v[3], v[4], v[5]);
    s.half_angle = v[6];
    if (s.axis.norm() == 0.0 || !(s.half_angle > 0.0 && s.half_angle <= 180.0))
      throw UsageError{"--cap needs a non-zero axis and a half-angle in (0, 180] degrees"};
  } else {
    const auto v = numbers(args, "mask", 3, "the hair's colour as in the file, R,G,B");
    s.kind = HairSelection::Kind::mask;
    s.color = Vec3(v[0], v[1], v[2]);
    s.tolerance = args.number("mask-tolerance", s.tolerance);
    if (!(s.tolerance >= 0.0)) throw UsageError{"--mask-tolerance must be ≥ 0"};
    const double smoothing = args.number("mask-smoothing", s.mask_smoothing);
    if (!(smoothing >= 0.0 && smoothing <= 100.0 && smoothing == std::floor(smoothing)))
      throw UsageError{"--mask-smoothing must be a whole number of rounds from 0 to 100"};
    s.mask_smoothing = static_cast<int>(smoothing);
  }
  return s;
}

}  // namespace

int command_prepare(const Arguments& argv) {
  const Args args(argv,
                  {"out", "plane", "cap", "mask", "mask-tolerance", "mask-smoothing", "units", "head-height", "up", "front",
                   "crown-thickness", "ramp", "max-hole", "weld", "scalp", "scalp-voxel", "threads"},
                  {});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCAN.obj"};
  if (!args.has("out")) throw UsageError{"--out DIR is required"};
  if (args.has("units") && args.has("head-height")) throw UsageError{"give --units or --head-height, not both"};
  PrepareOptions o;
  o.selection = selection(args);
  o.units = args.text("units").value_or("cm");
  o.head_height = args.number("head-height", 0.0);
  if (args.has("head-height") && !(o.head_height > 0.0)) throw UsageError{"--head-height must be a positive length in cm"};
  if (args.has("up")) o.up = args.vector3("up", Vec3::UnitY());
  if (args.has("front")) o.front = args.vector3("front", Vec3::UnitZ());
  if (o.up && o.up->norm() == 0.0) throw UsageError{"--up must be a non-zero direction"};
  if (o.front && o.up && o.front->cross(*o.up).norm() < 1e-6 * o.front->norm() * o.up->norm())
    throw UsageError{"--front must not be parallel to --up"};
  o.scalp.crown_thickness = args.number("crown-thickness", o.scalp.crown_thickness);
  o.scalp.ramp = args.number("ramp", o.scalp.ramp);
  o.hull.max_hole = args.number("max-hole", o.hull.max_hole);
  o.weld_tolerance = args.number("weld", o.weld_tolerance);
  o.scalp_method = args.text("scalp").value_or(o.scalp_method);
  if (o.scalp_method != "auto" && o.scalp_method != "radial" && o.scalp_method != "level-set")
    throw UsageError{"--scalp must be auto, radial or level-set"};
  o.scalp.voxel = args.number("scalp-voxel", o.scalp.voxel);
  if (!(o.scalp.voxel >= 0.0)) throw UsageError{"--scalp-voxel must be a length ≥ 0 in cm (0: min(0.25, T / 6))"};
  const double threads = args.number("threads", 0.0);
  if (!(threads >= 0.0 && threads == std::floor(threads))) throw UsageError{"--threads must be a whole number ≥ 0"};
  o.threads = static_cast<int>(threads);
  if (!(o.scalp.crown_thickness > 0.0)) throw UsageError{"--crown-thickness must be a positive length in cm"};
  if (!(o.scalp.ramp > 0.0)) throw UsageError{"--ramp must be a positive length in cm"};
  if (!(o.hull.max_hole >= 0.0)) throw UsageError{"--max-hole must be a share ≥ 0 of the hairline's length"};

  const std::string scan = args.positionals()[0];
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const Clock::time_point start = Clock::now();
  const LoadedMesh loaded = load_obj_mesh(scan);
  const double read_seconds = seconds_since(start);
  const Clock::time_point prepare_start = Clock::now();
  const Prepared p = prepare_scan(loaded.mesh, loaded.colors, o, scan);
  const double prepare_seconds = seconds_since(prepare_start);
  const std::string dir = *args.text("out");
  const Clock::time_point write_start = Clock::now();
  write_validated_prepared(p, scan, o, dir);
  const double write_seconds = seconds_since(write_start);

  double max_thickness = 0.0;
  for (double t : p.scalp.thickness) max_thickness = std::max(max_thickness, t);
  std::printf("%s: %zu triangles, scaled by %g to cm\n", scan.c_str(), loaded.mesh.triangles.size(), p.scale_to_cm);
  std::printf("  hair     %s\n", o.selection.describe().c_str());
  std::printf("  hull     %zu triangles, %.1f cm², hairline %.1f cm (%d parts selected, largest kept; %d holes filled)\n",
              p.hull.mesh.triangles.size(), p.hull.kept_area, p.hull.hairline_length, p.hull.parts, p.hull.holes_filled);
  std::printf("  scalp    %.1f cm², thickness 0 at the hairline to %.2f cm (crown %.2f cm, ramp %.2f cm)\n",
              surface_area(p.scalp.scalp), max_thickness, o.scalp.crown_thickness, p.scalp.ramp_length);
  std::printf("  scalp    made by %s\n", p.scalp_how.c_str());
  std::printf("  up       (%.3g, %.3g, %.3g) %s\n", p.up.x(), p.up.y(), p.up.z(), p.up_how.c_str());
  std::printf("  front    (%.3g, %.3g, %.3g) %s\n", p.front.x(), p.front.y(), p.front.z(), p.front_how.c_str());
  for (const std::string& repair : p.repairs) std::printf("  repaired %s\n", repair.c_str());
  std::printf("  checks   disks, outward, inside (winding %.3f), no intersections, shared hairline: passed\n",
              p.checks.deepest_winding);
  std::printf("  run      the written scene passes run's own input checks (hairfit validate)\n");
  std::printf("  wrote    %s/volume.obj, scalp.obj, scene.toml, prepare.json\n", dir.c_str());
  // Wall clock, printed only (prepare.json stays the same for the same scan and options).
  std::printf("  time     %.2f s: reading the scan %.2f s, preparing %.2f s, writing %.2f s\n",
              seconds_since(start), read_seconds, prepare_seconds, write_seconds);
  std::printf("  next     hairfit render %s/scene.toml --stage cut; hairfit run %s/scene.toml\n", dir.c_str(), dir.c_str());
  return 0;
}

}  // namespace hairfit::cli
