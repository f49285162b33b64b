#include "pipeline/cut_picture.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/obj_mesh.h"
#include "render/contact_sheet.h"
#include "render/render_3d.h"
#include "spec/scene.h"

namespace hairfit {

Image render_cut(const std::filesystem::path& scene_file, ViewName view, int width, int height, int threads) {
  const Scene scene = parse_scene(scene_file);
  const std::filesystem::path record_file = scene_file.parent_path() / "prepare.json";
  std::ifstream in(record_file);
  if (!in)
    throw InputError(scene_file.string(), "has no prepare.json beside it; the cut picture is for scenes written by "
                                          "`hairfit prepare` (other scenes: --stage inputs)");
  nlohmann::json record;
  try {
    in >> record;
    record.at("scan").get<std::string>();
    record.at("scale_to_cm").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(record_file.string(), std::string("is not a prepare record: ") + e.what());
  }
  const LoadedMesh scan = load_obj_mesh(record["scan"].get<std::string>(), record["scale_to_cm"].get<double>());
  const double to_cm = scene.units.to_cm();
  const LoadedMesh scalp = load_obj_mesh(scene.inputs.scalp, to_cm);
  const LoadedMesh volume = load_obj_mesh(scene.inputs.volume, to_cm);

  RenderOptions options;
  options.threads = threads;
  const int panel = width / 2;
  auto draw = [&](Drawing3D drawing) {
    const auto [lo, hi] = drawing_bounds(drawing);
    return render_3d(drawing, fit_camera(view, scene.units.down, scene.units.front, lo, hi, panel, height), options);
  };
  const Color hair{0.55f, 0.33f, 0.15f}, hair_outline{0.95f, 0.65f, 0.30f};
  Drawing3D selected;
  selected.meshes = {MeshLayer{&scan.mesh, MeshStyle::shaded, Color{0.75f, 0.75f, 0.78f}},
                     MeshLayer{&volume.mesh, MeshStyle::silhouette, hair, 0.45f, hair_outline}};
  selected.title = "scan and the hair cut from it";
  Drawing3D under;
  under.meshes = {MeshLayer{&scalp.mesh, MeshStyle::shaded},
                  MeshLayer{&volume.mesh, MeshStyle::silhouette, hair, 0.12f, hair_outline}};
  under.title = "scalp under the hair's outline";
  // Both panels share the scan's framing so they can be compared.
  under.meshes.push_back(MeshLayer{&scan.mesh, MeshStyle::silhouette, Color{0.6f, 0.6f, 0.6f}, 0.0f,
                                   Color{0.45f, 0.45f, 0.5f}, 1.0});
  return contact_sheet({draw(selected), draw(under)}, {"hull", "scalp"}, 2);
}

}  // namespace hairfit
