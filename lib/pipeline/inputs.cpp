#include "pipeline/inputs.h"

#include <algorithm>

#include "io/png_map.h"

namespace hairfit {

namespace {

// Share of (up to ~200 evenly picked) scalp vertices whose winding number in the volume is > ½.
double scalp_inside_fraction(const Mesh& scalp, const Mesh& volume) {
  const int step = std::max<int>(1, static_cast<int>(scalp.positions.size()) / 200);
  int inside = 0, tested = 0;
  for (std::size_t i = 0; i < scalp.positions.size(); i += step, ++tested)
    if (winding_number(volume, scalp.positions[i]) > 0.5) ++inside;
  return tested ? static_cast<double>(inside) / tested : 0.0;
}

}  // namespace

Inputs load_inputs(const Scene& scene) {
  const double to_cm = scene.units.to_cm();
  Inputs in;
  in.scalp = load_obj_mesh(scene.inputs.scalp, to_cm);
  require_disk(in.scalp.mesh, analyse_topology(in.scalp.mesh), scene.inputs.scalp.string());
  in.volume = load_obj_mesh(scene.inputs.volume, to_cm);
  if (scene.effects.uses_map("density")) in.density_map = load_grey_map(*scene.maps.density);
  if (scene.effects.uses_map("tilt")) in.tilt_map = load_grey_map(*scene.maps.tilt);
  if (scene.effects.uses_map("length")) in.length_map = load_grey_map(*scene.maps.length);

  // The volume must hold the scalp: sample scalp vertices and test their winding number.
  const double inside = scalp_inside_fraction(in.scalp.mesh, in.volume.mesh);
  if (inside < 0.9) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the hair volume must enclose the scalp, but only %.0f%% of the scalp's vertices lie inside it "
                  "(check that both meshes use units.length = \"%s\", that the volume's normals face outward, and "
                  "that inputs.scalp and inputs.volume are not swapped)",
                  100.0 * inside, scene.units.length.c_str());
    throw InputError(scene.inputs.volume.string(), text);
  }
  return in;
}

InputsSummary summarise_inputs(const Inputs& inputs) {
  InputsSummary s;
  s.scalp_topology = analyse_topology(inputs.scalp.mesh);
  s.scalp_area = surface_area(inputs.scalp.mesh);
  s.volume_topology = analyse_topology(inputs.volume.mesh);
  s.volume_area = surface_area(inputs.volume.mesh);
  s.scalp_inside_fraction = scalp_inside_fraction(inputs.scalp.mesh, inputs.volume.mesh);
  return s;
}

}  // namespace hairfit
