#include "pipeline/inputs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <future>

#include "io/png_map.h"
#include "pipeline/stage_options.h"
#include "field/hair_region.h"
#include "scalp/chart.h"

namespace hairfit {

namespace {

// Coordinates beyond 10 km are a unit mistake or garbage; far beyond, squared distances overflow.
constexpr double kMaxCoordinateCm = 1e6;

void require_plausible_coordinates(const Mesh& mesh, const std::string& file, const std::string& unit) {
  for (const Vec3& p : mesh.positions) {
    if (p.cwiseAbs().maxCoeff() <= kMaxCoordinateCm) continue;  // also false for NaN
    char text[320];
    std::snprintf(text, sizeof text,
                  "has a vertex at (%.6g, %.6g, %.6g) cm, beyond ±%.0f cm (10 km) of the origin; check "
                  "units.length = \"%s\" and the scale the mesh was exported at",
                  p.x(), p.y(), p.z(), kMaxCoordinateCm, unit.c_str());
    throw InputError(file, text);
  }
}

// Vertices of a raw mesh closer than this share of its bounding box's diagonal are one vertex: far
// below any feature of a head (1e-7 of 30 cm is 30 nm), far above the round-off of exported
// coordinates.
constexpr double kWeldShare = 1e-7;

CleanMesh clean(const Mesh& raw) {
  const auto box = bounding_box(raw);
  return clean_mesh(raw, kWeldShare * (box.second - box.first).norm());
}

void move_by(Mesh& mesh, const Vec3& shift) {
  if (shift == Vec3::Zero()) return;
  for (Vec3& x : mesh.positions) x += shift;
}

Mesh reversed(Mesh mesh) {
  for (Vec3i& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

// Under gravity a fibre's dimensionless weight w = ρAgL³/EI sets how stiff its equations are; far
// beyond the hair the method is meant for (w ≈ 50 for 12 cm of real hair) the integrator
// overflows (measured: NaN from w ≈ 2e14 with 16 segments; finite up to 2e12 for 2 to 256
// segments), so such hair is refused before anything runs, with a margin of 100.
constexpr double kMaxDimensionlessWeight = 1e10;

void require_integrable_weight(const Scene& scene) {
  if (!scene.effects.gravity) return;
  const double length = scene.effects.uses_map("length") ? scene.hair.length_range[1] : scene.hair.length;
  const double area = scene.hair.cross_section, second_moment = area * area / (4.0 * M_PI);
  const double weight = scene.hair.mass_density * area * scene.rod.gravity * length * length * length /
                        (scene.hair.youngs_modulus * second_moment);
  if (!(weight > kMaxDimensionlessWeight)) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "with effects.gravity, hair of %g cm with hair.youngs_modulus = %g dyn/cm² has a dimensionless weight "
                "ρAgL³/EI = %.3g, beyond the %.0e the rod integrator can follow; raise hair.youngs_modulus (real hair: "
                "3.89e10), shorten the hair or turn effects.gravity off",
                length, scene.hair.youngs_modulus, weight, kMaxDimensionlessWeight);
  const auto at = scene.locations.find("hair.youngs_modulus");
  const int line = at == scene.locations.end() ? 0 : at->second.line, column = at == scene.locations.end() ? 0 : at->second.column;
  throw InputError({Diagnostic{{scene.file.string(), line, column}, text, ""}});
}

// Points just in front of the scalp, one per triangle (up to ~400 evenly picked): its centroid moved
// along its normal by 1e-4 of the scalp's size, off the surface where a shared hairline makes the
// winding number ½.
std::vector<Vec3> scalp_probes(const Mesh& scalp) {
  const auto box = bounding_box(scalp);
  const double offset = 1e-4 * (box.second - box.first).norm();
  const int count = static_cast<int>(scalp.triangles.size());
  const int step = std::max(1, count / 400);
  std::vector<Vec3> probes;
  for (int t = 0; t < count; t += step) probes.push_back(triangle_centroid(scalp, t) + offset * triangle_normal(scalp, t));
  return probes;
}

double share_inside(const HairRegion& region, const std::vector<Vec3>& probes) {
  int inside = 0;
  for (const Vec3& p : probes) inside += region.inside_hull(p);
  return probes.empty() ? 0.0 : static_cast<double>(inside) / probes.size();
}

// Orients the hull so that it encloses the scalp: a hull whose triangles face inward (every part
// of it, or its largest) puts the scalp outside; reversed, the same hull puts it inside. Returns
// the share of the scalp inside, and refuses a hull with the scalp entirely outside either way.
double enclose_scalp(const Scene& scene, Inputs& in, int threads) {
  const std::vector<Vec3> probes = scalp_probes(in.scalp.mesh);
  const bool closed = in.volume_report.closed();
  const double as_given = share_inside(HairRegion(in.volume.mesh, in.scalp.mesh, closed, threads), probes);
  if (as_given >= 0.5) return as_given;
  Mesh flipped = reversed(in.volume.mesh);
  const double share = share_inside(HairRegion(flipped, in.scalp.mesh, closed, threads), probes);
  if (share > as_given) {
    in.volume.mesh = std::move(flipped);
    in.volume_reversed = true;
    return share;
  }
  if (as_given > 0.0) return as_given;
  char text[400];
  std::snprintf(text, sizeof text,
                "no part of the scalp lies inside the hair volume, so there is no region to fill: check that both "
                "meshes use units.length = \"%s\", that inputs.scalp and inputs.volume are not swapped, and that the "
                "volume covers the scalp",
                scene.units.length.c_str());
  throw InputError(scene.inputs.volume.string(), text);
}

}  // namespace

Inputs load_inputs(const Scene& scene, int threads) {
  const double to_cm = scene.units.to_cm();
  const std::string scalp_file = scene.inputs.scalp.string(), volume_file = scene.inputs.volume.string();
  require_integrable_weight(scene);
  Inputs in;
  // With a second thread the volume is read while the scalp is read and checked; its errors are
  // reported only after the scalp's, as when they are read one after the other.
  std::future<LoadedMesh> volume;
  if (threads > 1) volume = std::async(std::launch::async, [&] { return load_obj_mesh(scene.inputs.volume, to_cm); });
  in.scalp = load_obj_mesh(scene.inputs.scalp, to_cm);
  require_plausible_coordinates(in.scalp.mesh, scalp_file, scene.units.length);
  // Far from the origin, everything is computed about a point near the scalp (Inputs::origin).
  const auto [scalp_low, scalp_high] = bounding_box(in.scalp.mesh);
  in.origin = frame_origin(scalp_low, scalp_high);
  move_by(in.scalp.mesh, -in.origin);
  CleanMesh scalp = clean(in.scalp.mesh);
  in.scalp_report = scalp.report;
  in.scalp.mesh = std::move(scalp.mesh);
  // The chart takes a scalp facing either way; the fields and the winding numbers take it facing
  // out of the head.
  if (check_scalp_for_chart(in.scalp.mesh, scene.units.front, scene.units.down, scalp_file) < 0) {
    in.scalp.mesh = reversed(in.scalp.mesh);
    in.scalp_reversed = true;
  }
  in.volume = volume.valid() ? volume.get() : load_obj_mesh(scene.inputs.volume, to_cm);
  require_plausible_coordinates(in.volume.mesh, volume_file, scene.units.length);
  move_by(in.volume.mesh, -in.origin);
  CleanMesh hull = clean(in.volume.mesh);
  if (hull.mesh.triangles.empty())
    throw InputError(volume_file, "the hair volume has no triangle of non-zero area left once its duplicate and "
                                  "degenerate triangles are dropped; export the hair's outer surface");
  in.volume_report = hull.report;
  in.volume.mesh = std::move(hull.mesh);
  if (scene.effects.uses_map("density")) in.density_map = std::make_shared<const GreyMap>(load_grey_map(*scene.maps.density));
  if (scene.effects.uses_map("tilt")) in.tilt_map = std::make_shared<const GreyMap>(load_grey_map(*scene.maps.tilt));
  if (scene.effects.uses_map("length")) in.length_map = std::make_shared<const GreyMap>(load_grey_map(*scene.maps.length));
  if (scene.output.occluder) {
    in.occluder = load_obj_mesh(*scene.output.occluder, to_cm).mesh;
    require_plausible_coordinates(*in.occluder, scene.output.occluder->string(), scene.units.length);
    move_by(*in.occluder, -in.origin);
  }

  in.scalp_inside_share = enclose_scalp(scene, in, threads);
  // What later stages would refuse for its size, refused now, before anything is written.
  require_field_fits(in.scalp.mesh, field_spec(scene, scalp_file));
  require_field_fits(in.volume.mesh, field_spec(scene, volume_file));
  if (density_declared(scene)) density_geometry(density_grid_spec(scene), in.volume.mesh);
  return in;
}

InputsSummary summarise_inputs(const Inputs& inputs) {
  InputsSummary s;
  s.scalp_topology = analyse_topology(inputs.scalp.mesh);
  s.scalp_area = surface_area(inputs.scalp.mesh);
  s.volume_topology = analyse_topology(inputs.volume.mesh);
  s.volume_area = surface_area(inputs.volume.mesh);
  s.scalp_inside_fraction = inputs.scalp_inside_share;
  return s;
}

}  // namespace hairfit
