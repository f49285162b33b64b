// Tests of the render library against independently computed answers: projected areas and
// lengths, camera geometry, colour-map endpoints, contour geometry, PNG round trips, determinism.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/png_image.h"
#include "render/camera.h"
#include "render/canvas.h"
#include "render/chart_plot.h"
#include "render/contact_sheet.h"
#include "render/plot.h"
#include "core/shapes.h"
#include "render/render_3d.h"
#include "../support/scratch.h"

using namespace hairfit;

namespace {

// Sum over pixels of the red channel in [0, 1].
double red_sum(const Image& image) {
  double sum = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) sum += image.rgba[i] / 255.0;
  return sum;
}

// Number of pixels with a non-zero red channel.
int touched(const Image& image) {
  int n = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) n += image.rgba[i] > 0;
  return n;
}

RenderOptions black_background() {
  RenderOptions o;
  o.background_top = o.background_bottom = {0, 0, 0};
  return o;
}

// Curves from point lists, for the tests' drawings.
Curves curves_of(const std::vector<std::vector<Vec3>>& lines) {
  Curves c;
  for (const std::vector<Vec3>& line : lines) c.add(line);
  return c;
}

CurveLayer flat_curves(const Curves* curves, const Color& color) {
  CurveLayer layer;
  layer.curves = curves;
  layer.color = color;
  layer.hair_shading = false;
  layer.root_darkening = 0;
  layer.depth_cue = 0;
  layer.variation = 0;
  return layer;
}

// A camera looking down −z at the plane z = 0 with 1 pixel per unit, origin at the image centre.
Camera plane_camera(int width, int height) {
  Camera c = orient_camera(ViewName::front, Vec3(0, -1, 0), Vec3(0, 0, 1));
  c.width = width;
  c.height = height;
  c.pixels_per_unit = 1.0;
  return c;
}

}  // namespace

TEST_CASE("views: names, errors listing the valid ones, and sizes") {
  CHECK(view_names().size() == 5);
  for (const std::string& name : view_names()) CHECK(view_name(parse_view(name)) == name);
  try {
    parse_view("frnt");
    FAIL("no error for an unknown view");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("frnt") != std::string::npos);
    for (const std::string& name : view_names()) CHECK(what.find(name) != std::string::npos);
  }
  CHECK(parse_size("640x480") == std::pair<int, int>(640, 480));
  CHECK_THROWS_AS(parse_size("640"), InputError);
  CHECK_THROWS_AS(parse_size("0x480"), InputError);
  CHECK_THROWS_AS(parse_size("64ax48"), InputError);
}

TEST_CASE("views are placed relative to the scene's down and front") {
  // A tilted frame: down = −z, front = +x; the person's left is up × front = z × x = +y.
  const Vec3 down(0, 0, -1), front(1, 0, 0), left(0, 1, 0), up(0, 0, 1);
  for (const std::string& name : view_names()) {
    const Camera c = orient_camera(parse_view(name), down, front);
    CHECK(c.forward.cross(c.up).dot(c.right) == doctest::Approx(1.0));  // right = forward × up, orthonormal
    CHECK(c.right.norm() == doctest::Approx(1.0));
    CHECK(c.up.dot(c.forward) == doctest::Approx(0.0).epsilon(1e-12));
  }
  const Camera f = orient_camera(ViewName::front, down, front);
  CHECK(f.forward.dot(front) == doctest::Approx(-1.0));  // looks back at the face
  CHECK(f.right.dot(left) == doctest::Approx(1.0));      // the person's left on the image's right
  CHECK(f.up.dot(up) == doctest::Approx(1.0));
  const Camera s = orient_camera(ViewName::side, down, front);
  CHECK(s.right.dot(front) == doctest::Approx(1.0));  // the face points to the image's right
  CHECK(s.forward.dot(left) == doctest::Approx(1.0));  // camera on the person's right
  const Camera b = orient_camera(ViewName::back, down, front);
  CHECK(b.forward.dot(front) == doctest::Approx(1.0));
  CHECK(b.right.dot(left) == doctest::Approx(-1.0));
  const Camera t = orient_camera(ViewName::top, down, front);
  CHECK(t.forward.dot(down) == doctest::Approx(1.0));
  CHECK(t.up.dot(front) == doctest::Approx(1.0));  // the face toward the image's top
  const Camera q = orient_camera(ViewName::three_quarter, down, front);
  CHECK(q.to_viewer().dot(up) == doctest::Approx(std::sin(20 * M_PI / 180)));
  CHECK(q.to_viewer().dot(front) == doctest::Approx(q.to_viewer().dot(-left)));  // 45° between front and side
  CHECK_THROWS_AS(orient_camera(ViewName::front, down, Vec3(0, 0, 2)), InputError);
}

TEST_CASE("fit_camera puts the box inside the margins and projects orthographically") {
  const Vec3 lo(-3, -1, -2), hi(5, 7, 4);
  const int w = 400, h = 300;
  for (const std::string& name : view_names()) {
    const Camera c = fit_camera(parse_view(name), Vec3(0, -1, 0), Vec3(0, 0, 1), lo, hi, w, h, 0.1);
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p = c.project(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
    const double pad = 0.1 * 300;
    CHECK(x0 >= pad - 1e-9);
    CHECK(x1 <= w - pad + 1e-9);
    CHECK(y0 >= pad - 1e-9);
    CHECK(y1 <= h - pad + 1e-9);
    // Tight along one axis; centred on both.
    CHECK(std::max(x1 - x0 - (w - 2 * pad), y1 - y0 - (h - 2 * pad)) == doctest::Approx(0.0).epsilon(1e-9));
    CHECK(0.5 * (x0 + x1) == doctest::Approx(0.5 * w));
    CHECK(0.5 * (y0 + y1) == doctest::Approx(0.5 * h));
  }
}

TEST_CASE("a sphere mesh renders where the orthographic camera projects it") {
  const Vec3 centre(1, 2, 3);
  const double radius = 2.0;
  const Mesh sphere = uv_sphere(centre, radius, 64, 128);
  Drawing3D d;
  d.meshes.push_back({&sphere, MeshStyle::shaded, {1, 1, 1}});
  const Camera c = fit_camera(ViewName::three_quarter, Vec3(0, -1, 0), Vec3(0, 0, 1), centre - Vec3::Constant(3),
                              centre + Vec3::Constant(3), 200, 160);
  const Image image = render_3d(d, c, black_background());
  REQUIRE(image.width == 200);
  REQUIRE(image.height == 160);
  const Vec3 p = c.project(centre);
  const double r = radius * c.pixels_per_unit;
  int inside_lit = 0, inside = 0, outside_dark = 0, outside = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double d2 = std::hypot(x + 0.5 - p.x(), y + 0.5 - p.y());
      const bool lit = image.pixel(x, y)[0] > 0;
      if (d2 < r - 1.5) ++inside, inside_lit += lit;
      if (d2 > r + 1.5) ++outside, outside_dark += !lit;
    }
  CHECK(inside > 1000);
  CHECK(inside_lit == inside);
  CHECK(outside_dark == outside);
  // Projected vertices land on the disk's rim or inside it.
  for (const Vec3& v : sphere.positions) CHECK((c.project(v) - p).head<2>().norm() <= r * (1 + 1e-9));
}

TEST_CASE("a triangle covers its projected area in pixels") {
  // Facing the camera: flat shading gives one colour, so coverage = red / interior red.
  Mesh tri;
  tri.positions = {Vec3(-60, -40, 0), Vec3(70, -20, 0), Vec3(-10, 55, 0)};
  tri.triangles = {Vec3i(0, 1, 2)};
  Drawing3D d;
  d.meshes.push_back({&tri, MeshStyle::shaded, {1, 1, 1}});
  const Camera c = plane_camera(200, 160);
  const Image image = render_3d(d, c, black_background());
  const double interior = image.pixel(100, 80)[0] / 255.0;
  REQUIRE(interior > 0.5);
  const double area = 0.5 * std::abs((70 + 60) * (55 + 40) - (-10 + 60) * (-20 + 40));
  CHECK(red_sum(image) / interior == doctest::Approx(area).epsilon(0.01));
}

TEST_CASE("silhouette coverage of a sphere is its projected disk") {
  const Mesh sphere = uv_sphere(Vec3::Zero(), 50.0, 64, 128);
  MeshLayer layer;
  layer.mesh = &sphere;
  layer.style = MeshStyle::silhouette;
  layer.color = {1, 1, 1};
  layer.opacity = 1.0f;
  layer.outline_width = 0;
  Drawing3D d;
  d.meshes.push_back(layer);
  const Image image = render_3d(d, plane_camera(160, 160), black_background());
  CHECK(red_sum(image) == doctest::Approx(M_PI * 50 * 50).epsilon(0.01));
}

TEST_CASE("anti-aliased lines deposit width × length in coverage, at any angle and offset") {
  for (const Vec2& a : {Vec2(40, 40), Vec2(40.3, 40.17)})
    for (double angle : {0.0, 0.3, M_PI / 4, 1.2, M_PI / 2})
      for (double width : {1.0, 2.5}) {
        const Vec2 b = a + 120.0 * Vec2(std::cos(angle), std::sin(angle));
        INFO("start ", a.x(), " angle ", angle, " width ", width);
        Canvas canvas(200, 200, {0, 0, 0});
        canvas.line(a, b, {1, 1, 1}, width);
        // Bytes round each pixel by at most ½/255: allow that, nothing more.
        const Image image = canvas.image();
        CHECK(std::abs(red_sum(image) - 120.0 * width) <= 0.5 / 255 * touched(image) + 1e-3);
        // The same through the 3D renderer (a flat white curve in the plane z = 0), split in two
        // segments: the joint must not add or lose coverage.
        const Vec2 m = 0.5 * (a + b) + Vec2(0.01, 0.0);
        const Curves curves = curves_of({{Vec3(a.x() - 100, 80 - a.y(), 0), Vec3(m.x() - 100, 80 - m.y(), 0),
                                          Vec3(b.x() - 100, 80 - b.y(), 0)}});
        Drawing3D d;
        d.curves.push_back(flat_curves(&curves, {1, 1, 1}));
        d.curves[0].width = width;
        const double length = (m - a).norm() + (b - m).norm();
        // Over-compositing the joint column's two partial covers (1 − (1 − c₁)(1 − c₂) < c₁ + c₂)
        // may lose at most that column's coverage, about the width.
        const Image rendered = render_3d(d, plane_camera(200, 160), black_background());
        CHECK(red_sum(rendered) <= length * width + 0.5 / 255 * touched(rendered) + 1e-3);
        CHECK(red_sum(rendered) >= length * width - 0.5 / 255 * touched(rendered) - 1.5 * width);
      }
}

TEST_CASE("a near curve hides a far one, whatever the drawing order") {
  // Two crossing curves; the camera looks along −z, so larger z is nearer.
  const std::vector<Vec3> near_curve{Vec3(-50, 0, 5), Vec3(50, 0, 5)};
  const std::vector<Vec3> far_curve{Vec3(0, -50, -5), Vec3(0, 50, -5)};
  for (int order = 0; order < 2; ++order) {
    const Curves curves = order ? curves_of({far_curve, near_curve}) : curves_of({near_curve, far_curve});
    CurveLayer layer = flat_curves(&curves, {0, 0, 0});
    layer.color_ids = order ? std::vector<int>{2, 4} : std::vector<int>{4, 2};  // near: palette 4 (green)
    layer.width = 3.0;
    Drawing3D d;
    d.curves.push_back(layer);
    const Image image = render_3d(d, plane_camera(120, 120), black_background());
    const std::uint8_t* p = image.pixel(60, 60);
    const Color near_color = palette_color(4);
    CHECK(p[0] == to_byte(near_color.r));
    CHECK(p[1] == to_byte(near_color.g));
    CHECK(p[2] == to_byte(near_color.b));
  }
}

TEST_CASE("colour maps: endpoints and the middle") {
  const Color blue = diverging_color(-1), white = diverging_color(0), red = diverging_color(1);
  CHECK(blue.b > blue.r + 0.4f);
  CHECK(red.r > red.b + 0.4f);
  CHECK(std::min({white.r, white.g, white.b}) > 0.95f);
  CHECK(diverging_color(-7).b == blue.b);  // clamped
  const Color dark = sequential_color(0), light = sequential_color(1);
  CHECK(dark.r + dark.g + dark.b < 0.1f);
  CHECK(light.r + light.g + light.b > 2.5f);
  for (int id = 0; id < 50; ++id) CHECK((palette_color(id).r != palette_color(id + 1).r || palette_color(id).g != palette_color(id + 1).g));
}

TEST_CASE("marching squares traces a circle") {
  ScalarGrid g;
  g.width = 61, g.height = 41;
  g.x_min = -3, g.x_max = 3, g.y_min = -2, g.y_max = 2;
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) g.values.push_back(std::hypot(-3 + 0.1 * i, -2 + 0.1 * j) - 1.5);
  const auto segments = contour_segments(g, 0.0);
  double length = 0;
  for (const auto& s : segments) {
    length += (s[1] - s[0]).norm();
    for (const Vec2& p : s) CHECK(p.norm() == doctest::Approx(1.5).epsilon(0.005));
  }
  CHECK(length == doctest::Approx(2 * M_PI * 1.5).epsilon(0.005));
  g.values[0] = NAN;  // a corner without data skips only its cell
  CHECK(contour_segments(g, 0.0).size() == segments.size());
}

TEST_CASE("plots, chart and sheets have the sizes asked for") {
  BarPlot bars;
  bars.values = {1, 5, 3, 0, 2};
  CHECK(render_bar_plot(bars, 320, 200).width == 320);
  CHECK(render_bar_plot(bars, 320, 200).height == 200);
  LinePlot lines;
  lines.log_x = lines.log_y = true;
  lines.series.push_back({"a", {1, 10, 100}, {1e-3, 1e-5, 0}});  // the 0 is skipped on a log axis
  const Image line_image = render_line_plot(lines, 300, 220);
  CHECK((line_image.width == 300 && line_image.height == 220));
  lines.series.push_back({"bad", {1, 2}, {1}});
  CHECK_THROWS_AS(render_line_plot(lines, 300, 220), std::invalid_argument);
  HeatMap heat;
  heat.grid.width = heat.grid.height = 2;
  heat.grid.values = {-1, 1, 2, NAN};
  const Image heat_image = render_heat_map(heat, 333, 222);
  CHECK((heat_image.width == 333 && heat_image.height == 222));
  heat.grid.values.pop_back();
  CHECK_THROWS_AS(render_heat_map(heat, 333, 222), std::invalid_argument);
  ChartDrawing chart;
  chart.vertices = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  chart.triangles = {Vec3i(0, 1, 2)};
  chart.points = {Vec2(0.2, 0.2)};
  chart.point_ids = {3};
  const Image chart_image = render_chart(chart, 256, 300);
  CHECK((chart_image.width == 256 && chart_image.height == 300));
  const Image sheet = contact_sheet({chart_image, heat_image, line_image}, {"chart", "heat"}, 2);
  CHECK(sheet.width == 2 * 333 + 3 * 8);
  CHECK(sheet.height == 2 * (300 + 30) + 3 * 8);
}

TEST_CASE("heat map colours follow the data") {
  // A grid constant at +range: every map pixel is the diverging map's red end.
  HeatMap heat;
  heat.grid.width = heat.grid.height = 3;
  heat.grid.values.assign(9, 2.0);
  heat.range = 2.0;
  heat.iso_lines = heat.zero_contour = false;
  const Image image = render_heat_map(heat, 400, 400);
  const Color red = diverging_color(1.0);
  // The map is centred in the space left of the colour bar; its middle is well inside.
  const std::uint8_t* p = image.pixel(static_cast<int>(0.5 * (std::min(100.0, 0.18 * 400) + 400 - std::min(130.0, 0.22 * 400))), 200);
  CHECK(p[0] == to_byte(red.r));
  CHECK(p[1] == to_byte(red.g));
  CHECK(p[2] == to_byte(red.b));
}

TEST_CASE("same inputs give byte-identical PNGs, on 1 or 2 threads") {
  const Mesh head = uv_sphere(Vec3::Zero(), 8.0, 24, 48);
  const Mesh shell = uv_sphere(Vec3(0, -2, 0), 12.0, 16, 32);
  Curves curves;
  std::vector<int> ids;
  for (int s = 0; s < 400; ++s) {
    std::vector<Vec3> curve;
    const double phi = 0.1 * s;
    for (int k = 0; k < 16; ++k)
      curve.push_back(Vec3((8.2 + 0.2 * k) * std::cos(phi), 6.0 - 0.9 * k, (8.2 + 0.2 * k) * std::sin(phi)) +
                      0.5 * Vec3(std::sin(k + s), 0, std::cos(k + s)));
    curves.add(curve);
    ids.push_back(s % 13);
  }
  std::vector<Vec3> roots;
  for (std::size_t c = 0; c < curves.count(); ++c) roots.push_back(curves.point(c, 0));
  Drawing3D d;
  d.meshes.push_back({&head, MeshStyle::shaded});
  MeshLayer volume;
  volume.mesh = &shell;
  volume.style = MeshStyle::silhouette;
  d.meshes.push_back(volume);
  CurveLayer hair;
  hair.curves = &curves;
  hair.color_ids = ids;
  d.curves.push_back(hair);
  PointLayer points;
  points.points = &roots;
  d.points.push_back(points);
  d.title = "determinism";
  const auto [lo, hi] = drawing_bounds(d);
  const Camera c = fit_camera(ViewName::three_quarter, Vec3(0, -1, 0), Vec3(0, 0, 1), lo, hi, 256, 200);
  RenderOptions one, two;
  two.threads = 2;
  const std::vector<std::uint8_t> a = encode_png(render_3d(d, c, one));
  CHECK(a == encode_png(render_3d(d, c, one)));
  CHECK(a == encode_png(render_3d(d, c, two)));
  hair.color_ids.pop_back();
  d.curves[0] = hair;
  CHECK_THROWS_AS(render_3d(d, c, one), std::invalid_argument);
}

TEST_CASE("PNG round trip through stb_image gives back the buffer") {
  Image image = make_image(37, 23, 10, 20, 30);
  for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<std::uint8_t>((i * 7919) % 256);
  const auto folder = hairfit::testing::fresh_scratch_folder("render");
  write_png(folder / "rgba.png", image);
  const Image back = load_png_image(folder / "rgba.png");
  CHECK(back.width == 37);
  CHECK(back.height == 23);
  CHECK(back.rgba == image.rgba);
  Image opaque = make_image(5, 4, 200, 100, 50);
  opaque.rgba[4] = 1;
  write_png(folder / "rgb.png", opaque);
  CHECK(load_png_image(folder / "rgb.png").rgba == opaque.rgba);
  CHECK_THROWS_AS(load_png_image(folder / "missing.png"), InputError);
  CHECK_THROWS_AS(encode_png(Image{}), std::invalid_argument);
  std::filesystem::remove_all(folder);
}
