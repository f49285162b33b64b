// Renders demo pictures of every kind the render library draws, into a folder (default /tmp/
// hairfit_render_demo), and times the 3D renderer on many curves.
//   bench_render_demo [OUT_DIR] [--strands N] [--threads T]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "io/png_image.h"
#include "render/render_3d.h"

using namespace hairfit;

namespace {

Mesh make_sphere(const Vec3& centre, double radius, int rings, int sectors) {
  Mesh mesh;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / sectors;
      mesh.positions.push_back(centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                      std::sin(theta) * std::sin(phi)));
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const int a = i * sectors + j, b = i * sectors + (j + 1) % sectors;
      const int c = a + sectors, d = b + sectors;
      mesh.triangles.emplace_back(a, c, b);
      mesh.triangles.emplace_back(b, c, d);
    }
  return mesh;
}

// Strands growing from the upper part of a head-sized sphere, falling under a fake gravity with a
// helical wave: 16 points each.
Polylines make_strands(int count, std::vector<int>& ids) {
  Polylines curves;
  for (int s = 0; s < count; ++s) {
    const double u = (s + 0.5) / count;
    const double z = 1.0 - 0.9 * u;  // spherical Fibonacci points over the upper cap
    const double phi = s * 2.399963229728653;
    const Vec3 n(std::sqrt(1 - z * z) * std::cos(phi), z, std::sqrt(1 - z * z) * std::sin(phi));
    std::vector<Vec3> curve;
    Vec3 p = 8.0 * n, dir = n;
    const double wave = 0.6 + 0.3 * std::sin(7.0 * phi);
    for (int k = 0; k < 16; ++k) {
      const double t = k / 15.0;
      const Vec3 side = n.cross(Vec3(0, 1, 0)).normalized();
      curve.push_back(p + wave * std::sin(6.0 * t + phi) * side * t);
      dir = (dir + Vec3(0, -0.35, 0)).normalized();
      p += 1.3 * dir + 0.15 * Vec3(n.x(), 0, n.z());
    }
    curves.push_back(curve);
    ids.push_back(static_cast<int>(std::floor(phi / (2 * M_PI) * 3)) % 7 + (z > 0.6 ? 0 : 7));
  }
  return curves;
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
  const Mesh head = make_sphere(Vec3::Zero(), 8.0, 48, 96);
  const Mesh volume = make_sphere(Vec3(0, -4, 0), 16.0, 24, 48);
  std::vector<int> ids;
  const Polylines curves = make_strands(strands, ids);
  const Vec3 down(0, -1, 0), front(0, 0, 1);

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
  RenderOptions options;
  options.threads = threads;
  for (const std::string& name : view_names()) {
    const Camera camera = fit_camera(parse_view(name), down, front, lo, hi, 800, 800);
    drawing.title = "strands, " + name;
    const auto start = std::chrono::steady_clock::now();
    const Image image = render_3d(drawing, camera, options);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("render_3d %s: %d strands x 16 points, 800x800, ss 2, %d thread(s): %.1f ms\n", name.c_str(), strands,
                threads, ms);
    write_png(out + "/strands_" + name + ".png", image);
  }
  drawing.curves[0].color_ids = ids;
  drawing.title = "strands by cluster";
  write_png(out + "/strands_ids.png", render_3d(drawing, fit_camera(ViewName::three_quarter, down, front, lo, hi, 800, 800), options));
  return 0;
}
