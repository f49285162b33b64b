#include <cstdio>

#include "args.h"
#include "commands.h"
#include "pipeline/inputs.h"
#include "spec/resolved_scene.h"
#include "spec/scene.h"

namespace hairfit::cli {

namespace {

const char* yes_no(bool b) { return b ? "yes" : "no"; }

void print_map(const char* name, const std::shared_ptr<const GreyMap>& map) {
  if (map) std::printf("  %-8s map %d×%d, %d-bit\n", name, map->width, map->height, map->bits);
}

}  // namespace

int command_validate(const Arguments& argv) {
  const Args args(argv, {}, {"resolved"});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCENE file"};
  const Scene scene = parse_scene(args.positionals()[0]);
  const Inputs inputs = load_inputs(scene);
  // The scene as a run would resolve it into output.dir, short of what the run derives.
  if (args.has("resolved")) {
    std::fputs(resolved_scene_text(scene, {}, scene.output.dir).c_str(), stdout);
    return 0;
  }
  const InputsSummary s = summarise_inputs(inputs);

  std::printf("%s: valid scene (%s)\n", scene.file.string().c_str(), scene.format.c_str());
  const MeshTopology& st = s.scalp_topology;
  std::printf("  scalp    %s\n           %d triangles, %d vertices, %.2f cm², Euler characteristic %d: %s\n",
              scene.inputs.scalp.string().c_str(), st.faces, st.vertices, s.scalp_area, st.euler_characteristic,
              st.is_disk() ? "a topological disk" : "NOT a disk");
  std::printf("           found %s\n", describe(inputs.scalp_report).c_str());
  if (inputs.scalp.welded_duplicates || inputs.scalp.dropped_degenerate)
    std::printf("           on reading: welded %d duplicate vertices, dropped %d zero-area triangles\n",
                inputs.scalp.welded_duplicates, inputs.scalp.dropped_degenerate);
  if (inputs.scalp_reversed) std::printf("           its triangles faced into the head: reversed\n");
  const MeshTopology& vt = s.volume_topology;
  std::printf("  volume   %s\n           %d triangles, %d vertices, %.2f cm², closed: %s\n",
              scene.inputs.volume.string().c_str(), vt.faces, vt.vertices, s.volume_area,
              yes_no(inputs.volume_report.closed()));
  std::printf("           found %s\n", describe(inputs.volume_report).c_str());
  if (inputs.volume.welded_duplicates || inputs.volume.dropped_degenerate)
    std::printf("           on reading: welded %d duplicate vertices, dropped %d zero-area triangles\n",
                inputs.volume.welded_duplicates, inputs.volume.dropped_degenerate);
  if (inputs.volume_reversed) std::printf("           its triangles faced inward: reversed\n");
  std::printf("  region   %s; %.1f%% of the scalp lies inside it, %.1f%% outside (one probe per triangle, "
              "generalized winding numbers)\n",
              inputs.volume_report.closed() ? "inside the closed volume, in front of the scalp"
                                            : "the shell the open volume encloses with the scalp reversed",
              100.0 * s.scalp_inside_fraction, 100.0 * (1.0 - s.scalp_inside_fraction));
  print_map("density", inputs.density_map);
  print_map("tilt", inputs.tilt_map);
  print_map("length", inputs.length_map);
  std::string effects;
  for (const std::string& e : scene.effects.names()) effects += (effects.empty() ? "" : ", ") + e;
  std::printf("  effects  %s\n", effects.empty() ? "none declared" : effects.c_str());
  if (scene.hair.from_shell)
    std::printf("  hair     neither hair.length nor hair.tilt given: both are derived from the shell when the scene\n"
                "           runs (report.json roots.hair_length_cm, hair_tilt_degrees), with the thin-shell defaults\n"
                "           for the keys not given (spec/reference.md, \"Hair that suits its shell\");\n"
                "           --resolved lists them, a run's scene.resolved.toml also the length and tilt\n");
  return 0;
}

}  // namespace hairfit::cli
