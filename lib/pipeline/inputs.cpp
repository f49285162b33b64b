#include "pipeline/inputs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <future>

#include "io/png_map.h"
#include "pipeline/stage_options.h"
#include "pipeline/winding.h"
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

// The volume's inside must be well defined: the distance field's sign and the winding number both
// assume a closed, manifold, consistently oriented surface.
void require_closed_volume(const Mesh& volume, const std::string& file) {
  const MeshTopology topo = analyse_topology(volume);
  std::string what;
  if (!topo.nonmanifold_vertices.empty()) {
    const Vec3& p = volume.positions[topo.nonmanifold_vertices.front()];
    char text[160];
    std::snprintf(text, sizeof text, "has edges shared by 3 or more triangles (at (%.6g, %.6g, %.6g) and %zu other vertices)",
                  p.x(), p.y(), p.z(), topo.nonmanifold_vertices.size() - 1);
    what = text;
  } else if (!topo.boundary_loops.empty()) {
    const Vec3& p = volume.positions[topo.boundary_loops.front().front()];
    char text[160];
    std::snprintf(text, sizeof text, "has %zu hole(s) (a boundary loop passes (%.6g, %.6g, %.6g))", topo.boundary_loops.size(),
                  p.x(), p.y(), p.z());
    what = text;
  } else if (!topo.orientation_consistent) {
    what = "is not consistently oriented (some neighbouring triangles turn the other way)";
  } else {
    return;
  }
  throw InputError(file, "the hair volume must be a closed surface whose every edge joins two triangles turning the same "
                         "way, but it " + what + "; make it watertight with outward normals");
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

// Shares of (up to ~200 evenly picked) scalp vertices whose winding number in the volume is > ½
// (inside) and < −½ (inside a volume whose triangles face inward). Scalp vertices that are also
// volume vertices lie on it, neither in nor out (a prepared scene's hairline, on the volume's thin
// rim, reads a winding number near 0): they are not picked.
struct Enclosure {
  double inside = 0.0;
  double inside_inverted = 0.0;
};

Enclosure scalp_enclosure(const Mesh& scalp, const Mesh& volume) {
  std::vector<std::array<double, 3>> on_volume;
  for (const Vec3& p : volume.positions) on_volume.push_back({p.x(), p.y(), p.z()});
  std::sort(on_volume.begin(), on_volume.end());
  std::vector<int> picked;
  for (std::size_t v = 0; v < scalp.positions.size(); ++v) {
    const Vec3& p = scalp.positions[v];
    if (!std::binary_search(on_volume.begin(), on_volume.end(), std::array<double, 3>{p.x(), p.y(), p.z()}))
      picked.push_back(static_cast<int>(v));
  }
  const int step = std::max<int>(1, static_cast<int>(picked.size()) / 200);
  int inside = 0, inverted = 0, tested = 0;
  for (std::size_t i = 0; i < picked.size(); i += step, ++tested) {
    const double w = closed_winding_number(volume, scalp.positions[picked[i]]);  // the volume is closed (checked)
    inside += w > 0.5;
    inverted += w < -0.5;
  }
  if (tested == 0) return {};
  return {static_cast<double>(inside) / tested, static_cast<double>(inverted) / tested};
}

void require_enclosure(const Scene& scene, const Inputs& in) {
  const Enclosure e = scalp_enclosure(in.scalp.mesh, in.volume.mesh);
  if (e.inside >= 0.9) return;
  char text[400];
  if (e.inside_inverted >= 0.9)
    std::snprintf(text, sizeof text,
                  "the hair volume's triangles face inward (its winding number about %.0f%% of the scalp's vertices "
                  "is −1); reverse the order of every face's vertices so its normals face outward",
                  100.0 * e.inside_inverted);
  else
    std::snprintf(text, sizeof text,
                  "the hair volume must enclose the scalp, but only %.0f%% of the scalp's vertices lie inside it "
                  "(check that both meshes use units.length = \"%s\", that the volume's normals face outward, and "
                  "that inputs.scalp and inputs.volume are not swapped)",
                  100.0 * e.inside, scene.units.length.c_str());
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
  check_scalp_for_chart(in.scalp.mesh, scene.units.front, scene.units.down, scalp_file);
  in.volume = volume.valid() ? volume.get() : load_obj_mesh(scene.inputs.volume, to_cm);
  require_plausible_coordinates(in.volume.mesh, volume_file, scene.units.length);
  require_closed_volume(in.volume.mesh, volume_file);
  if (scene.effects.uses_map("density")) in.density_map = load_grey_map(*scene.maps.density);
  if (scene.effects.uses_map("tilt")) in.tilt_map = load_grey_map(*scene.maps.tilt);
  if (scene.effects.uses_map("length")) in.length_map = load_grey_map(*scene.maps.length);

  require_enclosure(scene, in);
  // What later stages would refuse for its size, refused now, before anything is written.
  require_field_fits(in.scalp.mesh, field_spec(scene, scalp_file));
  require_field_fits(in.volume.mesh, field_spec(scene, volume_file));
  if (density_declared(scene)) density_geometry(scene, in.volume.mesh);
  return in;
}

InputsSummary summarise_inputs(const Inputs& inputs) {
  InputsSummary s;
  s.scalp_topology = analyse_topology(inputs.scalp.mesh);
  s.scalp_area = surface_area(inputs.scalp.mesh);
  s.volume_topology = analyse_topology(inputs.volume.mesh);
  s.volume_area = surface_area(inputs.volume.mesh);
  s.scalp_inside_fraction = scalp_enclosure(inputs.scalp.mesh, inputs.volume.mesh).inside;
  return s;
}

}  // namespace hairfit
