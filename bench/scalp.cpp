// bench_scalp: the scalp chart against CGAL's mean-value parameterizer (same caps, same run), and
// roots per second at 200 hairs/cm² on a full scalp. Usage: bench_scalp [threads]
#include <algorithm>
#include <chrono>
#include <complex>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>

#include "scalp/chart.h"
#include "scalp/roots.h"
#include "tests/scalp/scalp_meshes.h"

#ifdef HAIRFIT_HAVE_CGAL
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#endif

using namespace hairfit;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Median wall time of `runs` calls; cpu gets the median process CPU time (all threads), which
// is what the work costs when the shared machine is busy with other jobs.
double median_time(int runs, const std::function<void()>& f, double* cpu = nullptr) {
  std::vector<double> t, c;
  for (int r = 0; r < runs; ++r) {
    const std::clock_t c0 = std::clock();
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds_since(start));
    c.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
  }
  std::sort(t.begin(), t.end());
  std::sort(c.begin(), c.end());
  if (cpu) *cpu = c[c.size() / 2];
  return t[t.size() / 2];
}

#ifdef HAIRFIT_HAVE_CGAL
// Largest distance between our chart and another parameterisation after the best similarity
// (rotation, uniform scale, translation, optionally a reflection) maps the other onto ours:
// in complex numbers the least-squares map z ↦ a·z + b has a = Σ(w−w̄)·conj(z−z̄) / Σ|z−z̄|².
double aligned_difference(const std::vector<Vec2>& ours, const std::vector<Vec2>& other) {
  using C = std::complex<double>;
  double best = INFINITY;
  for (int mirror = 0; mirror < 2; ++mirror) {
    std::vector<C> z, w;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      z.emplace_back(other[i].x(), mirror ? -other[i].y() : other[i].y());
      w.emplace_back(ours[i].x(), ours[i].y());
    }
    const C zm = std::accumulate(z.begin(), z.end(), C(0)) / static_cast<double>(z.size());
    const C wm = std::accumulate(w.begin(), w.end(), C(0)) / static_cast<double>(w.size());
    C num(0);
    double den = 0;
    for (std::size_t i = 0; i < z.size(); ++i) {
      num += (w[i] - wm) * std::conj(z[i] - zm);
      den += std::norm(z[i] - zm);
    }
    const C a = num / den, b = wm - a * zm;
    double worst = 0.0;
    for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(a * z[i] + b - w[i]));
    best = std::min(best, worst);
  }
  return best;
}

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;

// CGAL's Floater mean-value map with arc-length circular border (its defaults: BiCGSTAB with an
// incomplete-LUT preconditioner, one solve per coordinate). Returns the time of parameterize().
double cgal_chart(const Mesh& mesh, std::vector<Vec2>& uv, double& cpu) {
  SurfaceMesh sm;
  std::vector<VertexIndex> v;
  for (const Vec3& p : mesh.positions) v.push_back(sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (const Vec3i& f : mesh.triangles) sm.add_face(v[f[0]], v[f[1]], v[f[2]]);
  const auto border = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  auto uv_map = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
  namespace SMP = CGAL::Surface_mesh_parameterization;
  using Border = SMP::Circular_border_arc_length_parameterizer_3<SurfaceMesh>;
  using Parameterizer = SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh, Border>;
  const std::clock_t c0 = std::clock();
  const auto start = std::chrono::steady_clock::now();
  const SMP::Error_code status = SMP::parameterize(sm, Parameterizer(), border, uv_map);
  const double t = seconds_since(start);
  cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  if (status != SMP::OK) {
    std::fprintf(stderr, "CGAL parameterize failed: %s\n", SMP::get_error_message(status));
    std::exit(1);
  }
  uv.resize(mesh.positions.size());
  for (std::size_t i = 0; i < uv.size(); ++i) uv[i] = Vec2(uv_map[v[i]].x(), uv_map[v[i]].y());
  return t;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const Vec3 front(0, 0, 1), down(0, -1, 0);

  std::printf("## Chart (Floater mean-value map onto the unit disk), wall / CPU ms, median of 5\n\n");
  std::printf("| cap | triangles | hairfit (SparseLU) | CGAL %s MVC (BiCGSTAB+ILUT) | max chart difference after similarity | flipped |\n",
#ifdef HAIRFIT_HAVE_CGAL
              CGAL_VERSION_STR
#else
              ""
#endif
  );
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: |\n");
  for (int rings : {29, 91}) {
    const Mesh cap = test::head_cap(rings, 1.6, 0.03);
    ScalpChart chart;
    double ours_cpu = 0;
    const double ours = median_time(5, [&] { chart = make_scalp_chart(cap, front, down, "cap"); }, &ours_cpu);
#ifdef HAIRFIT_HAVE_CGAL
    std::vector<Vec2> uv;
    std::vector<double> t, c;
    for (int r = 0; r < 5; ++r) {
      double cpu = 0;
      t.push_back(cgal_chart(cap, uv, cpu));
      c.push_back(cpu);
    }
    std::sort(t.begin(), t.end());
    std::sort(c.begin(), c.end());
    char cgal[64], diff[64];
    std::snprintf(cgal, sizeof cgal, "%.1f / %.1f ms", 1e3 * t[2], 1e3 * c[2]);
    std::snprintf(diff, sizeof diff, "%.1e", aligned_difference(chart.chart, uv));
#else
    const char* cgal = "(CGAL not built)";
    const char* diff = "–";
#endif
    std::printf("| bumpy, %d rings | %zu | %.1f / %.1f ms | %s | %s | %d |\n", rings, cap.triangles.size(), 1e3 * ours,
                1e3 * ours_cpu, cgal, diff, chart.flipped_triangles);
  }

  std::printf("\n## Roots at 200 hairs/cm² on a full scalp, threads: %d\n\n", threads);
  const Mesh scalp = test::head_cap(91, 1.45, 0.02);
  const ScalpChart chart = make_scalp_chart(scalp, front, down, "scalp");
  RootOptions o;
  o.density = 200.0;
  o.guides = 3000;
  o.seed = 1;
  const Exec exec{threads, {}};
  Roots roots;
  Clusters clusters;
  PreguideRoots pre;
  double c_roots = 0, c_clusters = 0, c_pre = 0;
  const double t_roots = median_time(3, [&] { roots = make_roots(chart, {}, o, exec); }, &c_roots);
  const double t_clusters = median_time(3, [&] { clusters = make_clusters(chart, roots, o, exec); }, &c_clusters);
  const double t_pre = median_time(3, [&] { pre = make_preguide_roots(chart, {}, o, exec); }, &c_pre);
  const ScalpFigures f = scalp_figures(chart, roots, clusters, pre, threads);
  const double hex = std::sqrt(2.0 / (std::sqrt(3.0) * o.density));
  std::printf("| scalp area | roots (expected) | roots wall / CPU | roots/s (wall) | clusters (3000) wall / CPU | pre-guides (1 cm) | NN min / mean / hex spacing |\n");
  std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  std::printf("| %.1f cm² | %d (%.1f) | %.0f / %.0f ms | %.0f | %.0f / %.0f ms | %d in %.1f ms | %.4f / %.4f / %.4f cm |\n",
              f.scalp_area, f.roots, f.expected_roots, 1e3 * t_roots, 1e3 * c_roots, f.roots / t_roots, 1e3 * t_clusters,
              1e3 * c_clusters, f.preguide_roots, 1e3 * t_pre, f.min_spacing, f.mean_spacing, hex);
  return 0;
}
