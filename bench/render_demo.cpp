// Renders demo pictures of every kind the render library draws, into a folder (default /tmp/
// hairfit_render_demo), and times the 3D renderer on many curves.
//   bench_render_demo [OUT_DIR] [--strands N] [--threads T]
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "io/png_image.h"
#include "render/chart_plot.h"
#include "render/contact_sheet.h"
#include "render/plot.h"
#include "core/shapes.h"
#include "render/render_3d.h"

using namespace hairfit;

namespace {

// Strands growing from the upper back of a head-sized sphere (radius 8): out along the normal,
// then falling, kept outside the head, with a small curl. 16 points each; `ids` gets a patch id.
Curves make_strands(int count, std::vector<int>& ids) {
  Curves curves;
  for (int s = 0; s < count; ++s) {
    const double u = (s + 0.5) / count;
    const double y = 1.0 - 1.05 * u;  // spherical Fibonacci points over the cap y > −0.05
    const double phi = s * 2.399963229728653;
    const Vec3 n(std::sqrt(1 - y * y) * std::cos(phi), y, std::sqrt(1 - y * y) * std::sin(phi));
    if (n.z() > 0.35 && n.y() < 0.55) continue;  // leave the face free
    std::vector<Vec3> curve;
    Vec3 p = 8.0 * n, dir = (n + Vec3(0, 0.3, 0)).normalized();
    const Vec3 side = n.cross(Vec3(0, 1, 0)).norm() > 1e-6 ? Vec3(n.cross(Vec3(0, 1, 0)).normalized()) : Vec3(1, 0, 0);
    const double curl = 0.25 + 0.2 * std::sin(3.0 * phi);
    for (int k = 0; k < 16; ++k) {
      curve.push_back(p + curl * std::sin(1.2 * k + phi) * side * (k / 15.0));
      dir = (dir + Vec3(0, -0.28, 0)).normalized();
      p += 1.25 * dir;
      if (p.norm() < 8.4) p = 8.4 * p.normalized();  // stay outside the head
    }
    curves.add(curve);
    ids.push_back(static_cast<int>(std::floor((std::atan2(n.z(), n.x()) + M_PI) / (2 * M_PI) * 6)) + 6 * (y > 0.5));
  }
  return curves;
}

// A grid of the signed distance to the sphere |p| = 8 in the plane z = 0, with no data beyond a
// band of 5 (as a narrow-band field would give).
ScalarGrid sphere_slice() {
  ScalarGrid g;
  g.width = 81, g.height = 61;
  g.x_min = -16, g.x_max = 16, g.y_min = -10, g.y_max = 14;
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const double x = g.x_min + i * (g.x_max - g.x_min) / (g.width - 1), y = g.y_min + j * (g.y_max - g.y_min) / (g.height - 1);
      const double d = std::hypot(x, y) - 8.0;
      g.values.push_back(std::abs(d) <= 5.0 ? d : NAN);
    }
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "/tmp/hairfit_render_demo";
  int strands = 100000, threads = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--strands") && i + 1 < argc) strands = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else out = argv[i];
  }
  const Mesh head = uv_sphere(Vec3::Zero(), 8.0, 48, 96);
  Mesh volume = uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  for (Vec3& p : volume.positions) p = Vec3(0, -6, -1.5) + Vec3(14.0 * p.x(), 18.0 * p.y(), 14.5 * p.z());
  std::vector<int> ids;
  const Curves curves = make_strands(strands, ids);
  const Vec3 down(0, -1, 0), front(0, 0, 1);
  RenderOptions options;
  options.threads = threads;

  // Full head of hair, timed.
  Drawing3D drawing;
  drawing.meshes.push_back({&head, MeshStyle::shaded});
  MeshLayer shell;
  shell.mesh = &volume;
  shell.style = MeshStyle::silhouette;
  drawing.meshes.push_back(shell);
  CurveLayer hair;
  hair.curves = &curves;
  drawing.curves.push_back(hair);
  const auto [lo, hi] = drawing_bounds(drawing);
  std::vector<Image> sheet;
  std::vector<std::string> captions;
  for (const std::string& name : view_names()) {
    const Camera camera = fit_camera(parse_view(name), down, front, lo, hi, 800, 800);
    drawing.title = "strands, " + name;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const Image image = render_3d(drawing, camera, options);
    const double cpu_ms = 1000.0 * (std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("render_3d %s: %zu strands x 16 points, 800x800, ss 2, %d thread(s): %.0f ms wall, %.0f ms CPU\n",
                name.c_str(), curves.count(), threads, ms, cpu_ms);
    write_png(out + "/strands_" + name + ".png", image);
    sheet.push_back(render_3d(drawing, fit_camera(parse_view(name), down, front, lo, hi, 400, 400), options));
    captions.push_back(name);
  }

  // A few hundred guides coloured by patch, with their roots, over the scalp.
  Curves guides;
  std::vector<int> guide_ids;
  std::vector<Vec3> bases;
  for (std::size_t k = 0; k < curves.count(); k += std::max<std::size_t>(1, curves.count() / 300)) {
    guides.add(std::vector<Vec3>(curves.points.begin() + curves.offsets[k], curves.points.begin() + curves.offsets[k + 1]));
    guide_ids.push_back(ids[k]);
    bases.push_back(curves.point(k, 0));
  }
  Drawing3D guide_drawing;
  guide_drawing.meshes.push_back({&head, MeshStyle::shaded});
  CurveLayer guide_layer;
  guide_layer.curves = &guides;
  guide_layer.color_ids = guide_ids;
  guide_layer.width = 2.0;
  guide_drawing.curves.push_back(guide_layer);
  PointLayer base_layer;
  base_layer.points = &bases;
  base_layer.color_ids = guide_ids;
  base_layer.radius = 2.5;
  guide_drawing.points.push_back(base_layer);
  guide_drawing.title = "guides by cluster";
  const Image guides_image = render_3d(guide_drawing, fit_camera(ViewName::three_quarter, down, front, lo, hi, 800, 800), options);
  write_png(out + "/guides.png", guides_image);

  // Field slice, histogram, log-log plot, chart.
  HeatMap field;
  field.title = "scalp distance, slice z = 0";
  field.x_label = "x (cm)";
  field.y_label = "y (cm)";
  field.value_label = "signed distance (cm)";
  field.grid = sphere_slice();
  const Image field_image = render_heat_map(field, 800, 600);
  write_png(out + "/field.png", field_image);

  ScalarGrid density;
  density.width = 40, density.height = 50, density.x_min = -16, density.x_max = 16, density.y_min = -22, density.y_max = 14;
  for (int j = 0; j < density.height; ++j)
    for (int i = 0; i < density.width; ++i) {
      const double x = density.x_min + i * 32.0 / 39, y = density.y_min + j * 36.0 / 49;
      const double r = std::hypot(x / 11.0, (y + 3) / 14.0);
      density.values.push_back(r < 1 && std::hypot(x, y) > 8 ? 12.0 * (1 - r) * (1 + 0.3 * std::sin(x)) : 0.0);
    }
  HeatMap sagittal;
  sagittal.title = "strand density, sagittal slice";
  sagittal.x_label = "front (cm)";
  sagittal.y_label = "up (cm)";
  sagittal.value_label = "segments per cell";
  sagittal.grid = density;
  sagittal.scale = ColorScale::sequential;
  sagittal.smooth = false;
  sagittal.iso_lines = false;
  const Image density_image = render_heat_map(sagittal, 800, 600);
  write_png(out + "/density.png", density_image);

  BarPlot histogram;
  histogram.title = "segments per cell";
  histogram.x_label = "segments in a cell";
  histogram.y_label = "cells";
  for (int k = 0; k <= 40; ++k) histogram.values.push_back(std::round(5000.0 * std::exp(-0.5 * std::pow((k - 12) / 6.0, 2)) + 800.0 * std::exp(-k / 3.0)));
  const Image histogram_image = render_bar_plot(histogram, 800, 500);
  write_png(out + "/histogram.png", histogram_image);

  LinePlot bench;
  bench.title = "rod integrators: error vs time";
  bench.x_label = "time (ms)";
  bench.y_label = "tip error (cm)";
  bench.log_x = bench.log_y = true;
  for (int order : {2, 4}) {
    Series s;
    s.name = order == 2 ? "midpoint (order 2)" : "RK4 Lie (order 4)";
    for (int steps = 8; steps <= 1024; steps *= 2) {
      s.x.push_back(0.004 * steps * order / 2.0);
      s.y.push_back(3.0 * std::pow(1.0 / steps, order));
    }
    bench.series.push_back(s);
  }
  const Image bench_image = render_line_plot(bench, 800, 500);
  write_png(out + "/loglog.png", bench_image);

  ChartDrawing chart;
  chart.title = "scalp chart: pores and clusters";
  const int rings = 12;
  chart.vertices.push_back(Vec2::Zero());
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < 6 * r; ++k) {
      const double a = 2 * M_PI * k / (6 * r);
      chart.vertices.push_back(double(r) / rings * Vec2(std::cos(a), std::sin(a)));
    }
  // Triangulate consecutive rings by angle.
  auto ring_start = [](int r) { return r == 0 ? 0 : 1 + 3 * r * (r - 1); };
  for (int r = 0; r < rings; ++r) {
    const int n_in = r == 0 ? 1 : 6 * r, n_out = 6 * (r + 1);
    int i = 0, o = 0;
    while (i < n_in || o < n_out) {
      const double ai = r == 0 ? 1e9 : (i + 0.5) / n_in, ao = (o + 0.5) / n_out;
      const int vi = ring_start(r) + i % n_in, vo = ring_start(r + 1) + o % n_out;
      if (o < n_out && (ao <= ai || i >= n_in)) {
        chart.triangles.emplace_back(vi, vo, ring_start(r + 1) + (o + 1) % n_out);
        ++o;
      } else {
        chart.triangles.emplace_back(vi, vo, ring_start(r) + (i + 1) % n_in);
        ++i;
      }
    }
  }
  for (int k = 0; k < 1500; ++k) {
    const double r = 0.97 * std::sqrt((k + 0.5) / 1500), a = k * 2.399963229728653;
    chart.points.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  for (int c = 0; c < 12; ++c) {
    const double r = c < 4 ? 0.3 : 0.7, a = 2 * M_PI * c / (c < 4 ? 4 : 8);
    chart.circles.push_back({Vec2(r * std::cos(a), r * std::sin(a)), c < 4 ? 0.2 : 0.22, c});
    chart.highlights.push_back(chart.circles.back().centre);
  }
  for (const Vec2& p : chart.points) {
    int best = 0;
    for (int c = 1; c < 12; ++c)
      if ((p - chart.circles[c].centre).norm() < (p - chart.circles[best].centre).norm()) best = c;
    chart.point_ids.push_back(best);
  }
  const Image chart_image = render_chart(chart, 800, 800);
  write_png(out + "/chart.png", chart_image);

  write_png(out + "/views.png", contact_sheet(sheet, captions, 3));
  write_png(out + "/panels.png", side_by_side({histogram_image, bench_image}));
  write_png(out + "/sheet.png", contact_sheet({sheet[4], guides_image, field_image, density_image, histogram_image, chart_image},
                                              {"strands", "guides", "field", "density", "histogram", "chart"}, 3));
  return 0;
}
