#include "pipeline/stage_pictures.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <functional>

#include "density/statistics.h"
#include "field/hair_region.h"
#include "render/chart_plot.h"
#include "render/contact_sheet.h"
#include "render/plot.h"
#include "render/render_3d.h"
#include "rod/rod_point_forces.h"

namespace hairfit {

const std::vector<std::string>& picture_stages() {
  static const std::vector<std::string> names{"inputs", "fields", "chart", "roots", "preguides", "guides", "strands",
                                              "density", "all"};
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
  if (stage == "all") return "";
  return stage;
}

namespace {

// What the pre-guides show of the hull's hair: how many hang, how long they are (10th–90th
// percentile) and how many reach their depth.
std::string preguide_caption(const PreguideRoots& roots, const PreGuides& preguides) {
  const RootSet& r = roots.roots;
  int hanging = 0, reached = 0;
  std::vector<double> lengths;
  for (int i = 0; i < r.size(); ++i) hanging += hangs(r, i), lengths.push_back(r.lengths[i]);
  for (const PreGuide& g : preguides.items) reached += g.reached;
  std::string caption;
  if (hanging > 0) caption += ", " + std::to_string(hanging) + " hanging";
  if (!lengths.empty()) {
    std::sort(lengths.begin(), lengths.end());
    char range[64];
    std::snprintf(range, sizeof range, ", %.0f to %.0f cm", lengths[lengths.size() / 10], lengths[9 * lengths.size() / 10]);
    caption += range;
  }
  return caption + ", " + std::to_string(reached) + " at depth (red; blue: short of it)";
}

// Two pictures side by side (`stacked`: one above the other) in a width × height image.
Image two_panels(const Image& left, const Image& right, int width, int height, bool stacked = false) {
  Image out = make_image(width, height, 0, 0, 0);
  auto blit = [&](const Image& panel, int x0, int y0) {
    for (int y = 0; y < panel.height && y0 + y < height; ++y)
      for (int x = 0; x < panel.width && x0 + x < width; ++x)
        std::copy(panel.pixel(x, y), panel.pixel(x, y) + 4,
                  &out.rgba[(static_cast<std::size_t>(y0 + y) * width + x0 + x) * 4]);
  };
  blit(left, 0, 0);
  if (stacked)
    blit(right, 0, left.height);
  else
    blit(right, left.width, 0);
  return out;
}

// Two panels, each drawn at half the picture: side by side, or one above the other when `width`
// is below `stack_below`, where side by side would leave them too narrow for their titles and
// labels (a contact sheet's tile).
Image halves(const std::function<Image(int, int)>& first, const std::function<Image(int, int)>& second, int width,
             int height, int stack_below) {
  const bool stacked = width < stack_below;
  const int w = stacked ? width : width / 2, h = stacked ? height / 2 : height;
  return two_panels(first(w, h), second(stacked ? width : width - w, stacked ? height - h : height), width, height,
                    stacked);
}

// A slice of a distance field through the head's mid-sagittal plane (spanned by front and up),
// sampled over the field's extent, as a diverging heat map with the surface as the zero contour.
Image field_slice(const DistanceField& field, const Scene& scene, const std::string& title, int width, int height) {
  const Vec3 up = -scene.units.down;
  const Vec3 front = (scene.units.front - scene.units.front.dot(up) * up).normalized();
  const Vec3 lo = field.origin(), hi = field.origin() + field.voxel() * field.dims().cast<double>();
  const Vec3 centre = 0.5 * (lo + hi);
  // Extents along front and up: project the box's corners.
  double f_min = 1e300, f_max = -1e300, u_min = 1e300, u_max = -1e300;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    f_min = std::min(f_min, (corner - centre).dot(front)), f_max = std::max(f_max, (corner - centre).dot(front));
    u_min = std::min(u_min, (corner - centre).dot(up)), u_max = std::max(u_max, (corner - centre).dot(up));
  }
  HeatMap map;
  map.title = title;
  map.x_label = "front (cm)";
  map.y_label = "up (cm)";
  map.value_label = "signed distance (cm)";
  ScalarGrid& g = map.grid;
  g.width = 200;
  g.height = std::max(2, static_cast<int>(200 * (u_max - u_min) / (f_max - f_min)));
  g.x_min = f_min, g.x_max = f_max, g.y_min = u_min, g.y_max = u_max;
  g.values.resize(static_cast<std::size_t>(g.width) * g.height);
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const double x = f_min + (f_max - f_min) * i / (g.width - 1), y = u_min + (u_max - u_min) * j / (g.height - 1);
      g.values[static_cast<std::size_t>(j) * g.width + i] = field.value(centre + x * front + y * up);
    }
  return render_heat_map(map, width, height);
}

Image chart_picture(const StageValues& v, bool with_roots, int width, int height) {
  ChartDrawing d;
  d.vertices = v.chart->chart;
  d.triangles = v.chart->mesh.triangles;
  d.title = "chart: Floater mean-value map onto the unit disk";
  if (with_roots && v.roots) {
    // At most ~20 000 pores keep the picture readable; a fixed stride keeps it deterministic.
    const int n = v.roots->pores.size();
    const int stride = std::max(1, n / 20000);
    for (int i = 0; i < n; i += stride) {
      d.points.push_back(v.roots->pores.chart[i]);
      d.point_ids.push_back(v.clusters->pore_cluster[i]);
    }
    for (int c = 0; c < v.clusters->size(); ++c) {
      d.circles.push_back(ChartCircle{v.clusters->bases.chart[c], v.clusters->radius[c], c});
      d.highlights.push_back(v.clusters->bases.chart[c]);
    }
    d.title = "chart: " + std::to_string(n) + " pores in " + std::to_string(v.clusters->size()) + " clusters";
  }
  return render_chart(d, width, height);
}

// The paper's Fig. 5 and 6: segments per cell over the cells, and the density on the centre
// sagittal plane, of the final fibres.
Image density_picture(const Scene& scene, const StageValues& v, int width, int height, int threads) {
  if (!v.fibre_density)
    throw InputError(scene.file.string(), "declares no density model (effects.density = \"none\"), so there is no "
                                          "density stage to draw; declare one or pick another stage");
  const SegmentHistogram histogram = segment_histogram(v.fibre_density->geometry(), v.strands->fibres, threads);
  BarPlot bars;
  bars.title = "segments per cell (Fig. 5)";
  bars.x_label = "segments per cell";
  bars.y_label = "cells";
  bars.values.assign(histogram.cells_with.begin() + std::min<std::size_t>(1, histogram.cells_with.size()), histogram.cells_with.end());
  bars.x_start = 1.0;
  const Vec3 up = -scene.units.down;
  const DensitySlice slice = centre_slice(*v.fibre_density, scene.units.front.cross(up).normalized(), up);
  HeatMap map;
  map.title = "density, centre sagittal slice (Fig. 6)";
  map.x_label = "cm";
  map.y_label = "up (cm)";
  map.value_label = "length / cell diagonal";
  map.scale = ColorScale::sequential;
  map.smooth = false;
  map.grid.width = slice.width;
  map.grid.height = slice.height;
  map.grid.values = slice.values;
  map.grid.x_max = slice.u_step.norm() * (slice.width - 1);
  map.grid.y_max = slice.v_step.norm() * (slice.height - 1);
  return halves([&](int w, int h) { return render_bar_plot(bars, w, h); },
                [&](int w, int h) { return render_heat_map(map, w, h); }, width, height, 1000);
}

constexpr int kLegibleTile = 480;  // px: the smallest picture whose plot labels do not collide

}  // namespace

Image render_stage(const std::string& stage, const Scene& scene, const Inputs& inputs, const StageValues& values,
                   ViewName view, int width, int height, int threads) {
  check_picture_stage(stage);
  if (stage == "density") return density_picture(scene, values, width, height, threads);
  if (stage == "all") {
    std::vector<Image> tiles;
    std::vector<std::string> captions;
    const int tile = std::max(200, std::min(width, height) / 2);
    // The labels have one size: a tile smaller than kLegibleTile is drawn at a whole multiple of
    // its size and averaged down, so its plots keep their full-size layout instead of overlapping.
    const int factor = (kLegibleTile + tile - 1) / tile;
    for (const std::string& s : picture_stages()) {
      if (s == "all" || (s == "density" && !values.fibre_density)) continue;
      tiles.push_back(averaged_down(render_stage(s, scene, inputs, values, view, factor * tile, factor * tile, threads), factor));
      captions.push_back(s);
    }
    return contact_sheet(tiles, captions, 4);
  }
  if (stage == "fields") {
    const char* skin = values.scalp_field != values.scalp_distance ? "skin field, mid-sagittal slice"
                                                                   : "scalp field, mid-sagittal slice";
    return halves([&](int w, int h) { return field_slice(*values.scalp_field, scene, skin, w, h); },
                  [&](int w, int h) { return field_slice(*values.volume_field, scene, "volume field, mid-sagittal slice", w, h); },
                  width, height, 800);
  }
  if (stage == "chart") return chart_picture(values, false, width, height);
  Drawing3D drawing;
  // The head hides the hair behind it: the declared occluder (the scan), else the scalp closed
  // by a floor across its hairline, the head the fields count.
  const Mesh head = inputs.occluder ? Mesh{} : closed_head(inputs.scalp.mesh);
  MeshLayer scalp{inputs.occluder ? &*inputs.occluder : &head};
  MeshLayer volume{&inputs.volume.mesh, MeshStyle::silhouette};
  drawing.meshes = {scalp, volume};
  Curves lines;
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
    // The growth field: at every pre-guide root a 1 cm tick along its growth direction's tangent.
    const RootSet& ticks = values.preguide_roots->roots;
    for (int i = 0; i < ticks.size(); ++i) {
      const Vec3 t = ticks.directions[i] - ticks.directions[i].dot(ticks.normals[i]) * ticks.normals[i];
      if (t.norm() < 1e-9) continue;
      const Vec3 base = ticks.positions[i] + 0.05 * ticks.normals[i];
      lines.add({base, base + 1.0 * t.normalized()});
    }
    curves.hair_shading = false;
    curves.color = Color{0.95f, 0.95f, 0.95f};
    curves.width = 1.5;
    drawing.curves.push_back(curves);
    drawing.title = "roots: " + std::to_string(values.roots->pores.size()) + " pores, " +
                    std::to_string(values.clusters->size()) + " guides";
  } else if (stage == "preguides") {
    for (const PreGuide& g : values.preguides->items) {
      lines.add(g.shape.nodes);
      curves.color_ids.push_back(g.reached ? 2 : 0);
    }
    curves.width = 2.0;
    drawing.curves.push_back(curves);
    drawing.title = "pre-guides: " + std::to_string(values.preguides->size()) + preguide_caption(*values.preguide_roots,
                                                                                                 *values.preguides);
  } else if (stage == "guides") {
    lines = values.guides->curves();
    for (std::size_t c = 0; c < lines.count(); ++c) curves.color_ids.push_back(static_cast<int>(c));
    curves.width = 1.5;
    drawing.curves.push_back(curves);
    drawing.title = "guides: " + std::to_string(values.guides->size());
    // Where the layer holds a guide (guides.point_forces): a dot at each non-zero point force.
    int held = 0;
    for (const Guide& g : values.guides->items) {
      const int count = static_cast<int>(g.point_forces.size()), segments = static_cast<int>(g.shape.nodes.size()) - 1;
      for (int k = 0; k < count; ++k)
        if (!g.point_forces[k].isZero(0.0)) points.push_back(g.shape.nodes[point_force_node(k + 1, count, segments)]);
      held += held_by_layer(g);
    }
    if (!points.empty()) {
      dots.color = Color{0.95f, 0.25f, 0.2f};
      drawing.points.push_back(dots);
      drawing.title += ", " + std::to_string(held) + " held by the layer (red: point forces)";
    }
  } else if (stage == "strands") {
    curves.curves = &values.strands->fibres;  // drawn where they are
    drawing.meshes.pop_back();  // the hair hides the volume's outline
    curves.width = 1.0;
    drawing.curves.push_back(curves);
    drawing.title = "strands: " + std::to_string(values.strands->fibres.count()) + " fibres";
  }
  const int width_3d = stage == "roots" ? width / 2 : width;
  const auto [lo, hi] = drawing_bounds(drawing);
  const Camera camera = fit_camera(view, scene.units.down, scene.units.front, lo, hi, width_3d, height);
  RenderOptions options;
  options.threads = threads;
  const Image picture = render_3d(drawing, camera, options);
  if (stage == "roots") return two_panels(chart_picture(values, true, width - width_3d, height), picture, width, height);
  return picture;
}

}  // namespace hairfit
