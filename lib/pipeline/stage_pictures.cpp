#include "pipeline/stage_pictures.h"

#include <algorithm>

#include "render/render_3d.h"

namespace hairfit {

const std::vector<std::string>& picture_stages() {
  static const std::vector<std::string> names{"inputs", "roots", "preguides", "guides", "strands"};
  return names;
}

void check_picture_stage(const std::string& stage) {
  const std::vector<std::string>& names = picture_stages();
  if (std::find(names.begin(), names.end(), stage) != names.end()) return;
  std::string valid;
  for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("--stage", "no picture of a stage named \"" + stage + "\"; valid stages: " + valid);
}

std::string stage_needed_for_picture(const std::string& stage) {
  if (stage == "inputs") return "fields";
  return stage;
}

namespace {

Polylines polylines(const Curves& curves) {
  Polylines lines(curves.count());
  for (std::size_t c = 0; c < curves.count(); ++c)
    lines[c].assign(curves.points.begin() + curves.offsets[c], curves.points.begin() + curves.offsets[c + 1]);
  return lines;
}

}  // namespace

Image render_stage(const std::string& stage, const Scene& scene, const Inputs& inputs, const StageValues& values,
                   ViewName view, int width, int height, int threads) {
  check_picture_stage(stage);
  Drawing3D drawing;
  MeshLayer scalp{&inputs.scalp.mesh};
  MeshLayer volume{&inputs.volume.mesh, MeshStyle::silhouette};
  drawing.meshes = {scalp, volume};
  Polylines lines;
  std::vector<Vec3> points;
  CurveLayer curves;
  curves.curves = &lines;
  PointLayer dots;
  dots.points = &points;
  if (stage == "inputs") {
    drawing.title = "inputs: scalp and hair volume";
  } else if (stage == "roots") {
    points = values.clusters->bases.positions;
    dots.radius = 2.5;
    for (int c = 0; c < values.clusters->size(); ++c) dots.color_ids.push_back(c);
    drawing.points.push_back(dots);
    drawing.title = "roots: " + std::to_string(values.roots->pores.size()) + " pores, " +
                    std::to_string(values.clusters->size()) + " guide bases";
  } else if (stage == "preguides") {
    for (const PreGuide& g : values.preguides->items) {
      lines.push_back(g.shape.nodes);
      curves.color_ids.push_back(g.reached ? 2 : 0);
    }
    curves.width = 2.0;
    drawing.curves.push_back(curves);
    drawing.title = "pre-guides: " + std::to_string(values.preguides->size());
  } else if (stage == "guides") {
    lines = polylines(values.guides->curves());
    for (std::size_t c = 0; c < lines.size(); ++c) curves.color_ids.push_back(static_cast<int>(c));
    curves.width = 1.5;
    drawing.curves.push_back(curves);
    drawing.title = "guides: " + std::to_string(values.guides->size());
  } else if (stage == "strands") {
    lines = polylines(values.strands->fibres);
    drawing.meshes.pop_back();  // the hair hides the volume's outline
    curves.width = 1.0;
    drawing.curves.push_back(curves);
    drawing.title = "strands: " + std::to_string(lines.size()) + " fibres";
  }
  const auto [lo, hi] = drawing_bounds(drawing);
  const Camera camera = fit_camera(view, scene.units.down, scene.units.front, lo, hi, width, height);
  RenderOptions options;
  options.threads = threads;
  return render_3d(drawing, camera, options);
}

}  // namespace hairfit
