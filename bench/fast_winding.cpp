// bench_fast_winding: FastWindingNumber against the direct sum of solid angles on closed bumpy tori
// of 8 192 and 199 712 triangles, for beta = 1.5, 2, 3: queries per CPU second of the value, the
// estimate with its bound, above(p, ½) and the direct sum (on a subset, per point), with the
// measured errors against the direct sum on that subset. Points: uniform in the bounding box, and
// (small mesh) near the surface, within ±2 % of the box's longest side along the normal.
//   usage: bench_fast_winding [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "core/fast_winding.h"
#include "bench_support.h"
#include "core/mesh.h"
#include "core/random.h"

using namespace hairfit;
using hairfit::bench::bumpy_torus;
using hairfit::bench::cpu_seconds;

namespace {



// Queries per CPU second of f over the points, best of `runs`.
template <typename F>
double rate(const std::vector<Vec3>& points, int runs, F&& f) {
  double best = 1e300, sink = 0;
  for (int r = 0; r < runs; ++r) {
    const double t0 = cpu_seconds();
    for (const Vec3& p : points) sink += f(p);
    best = std::min(best, cpu_seconds() - t0);
  }
  if (sink == 12345.678) std::printf(" ");  // keeps the loop
  return points.size() / best;
}

std::vector<Vec3> box_points(const Mesh& m, int count, Random& r) {
  const auto [lo, hi] = bounding_box(m);
  std::vector<Vec3> points(count);
  for (Vec3& p : points) p = Vec3(r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y()), r.uniform(lo.z(), hi.z()));
  return points;
}

std::vector<Vec3> near_points(const Mesh& m, int count, double offset, Random& r) {
  std::vector<Vec3> points(count);
  for (Vec3& p : points) {
    const int t = static_cast<int>(r.below(m.triangles.size()));
    double s = r.uniform(), u = r.uniform();
    if (s + u > 1) s = 1 - s, u = 1 - u;
    const Vec3i& f = m.triangles[t];
    const Vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
    p = a + s * (b - a) + u * (c - a) + r.uniform(-offset, offset) * triangle_normal(m, t);
  }
  return points;
}

std::string per_second(double rate) {
  char s[32];
  if (rate >= 1e6)
    std::snprintf(s, sizeof s, "%.2f M", rate / 1e6);
  else
    std::snprintf(s, sizeof s, "%.1f k", rate / 1e3);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--quick")) quick = true;
  const int count = quick ? 20000 : 100000, runs = quick ? 1 : 3;

  std::printf("| mesh | points | beta | build s | value/s | estimate/s | above(·, ½)/s | direct/s | speed-up | max err | median err | max bound |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  struct Set {
    int n;
    bool near;
  };
  for (const Set set : {Set{64, false}, Set{64, true}, Set{316, false}}) {
    const Mesh mesh = bumpy_torus(set.n);
    const auto [lo, hi] = bounding_box(mesh);
    Random r(1, RandomStage::test, set.n * 2 + set.near);
    const std::vector<Vec3> points =
        set.near ? near_points(mesh, count, 0.02 * (hi - lo).maxCoeff(), r) : box_points(mesh, count, r);
    // The direct sum on a subset (every k-th point), for its speed and the errors.
    const std::size_t subset_size = quick ? 200 : (mesh.triangles.size() > 50000 ? 1000 : 10000);
    std::vector<Vec3> subset;
    for (std::size_t i = 0; i < subset_size; ++i) subset.push_back(points[i * points.size() / subset_size]);
    const FastWindingNumber reference(mesh);
    std::vector<double> exact(subset.size());
    const double t0 = cpu_seconds();
    for (std::size_t i = 0; i < subset.size(); ++i) exact[i] = reference.direct(subset[i]);
    const double direct_rate = subset.size() / (cpu_seconds() - t0);

    for (double beta : {1.5, 2.0, 3.0}) {
      const double b0 = cpu_seconds();
      const FastWindingNumber fast(mesh, beta);
      const double build = cpu_seconds() - b0;
      const double value_rate = rate(points, runs, [&](const Vec3& p) { return fast(p); });
      const double estimate_rate = rate(points, runs, [&](const Vec3& p) { return fast.estimate(p).error_bound; });
      const double above_rate = rate(points, runs, [&](const Vec3& p) { return fast.above(p, 0.5) ? 1.0 : 0.0; });
      std::vector<double> errors;
      double max_bound = 0;
      for (std::size_t i = 0; i < subset.size(); ++i) {
        const WindingEstimate e = fast.estimate(subset[i]);
        errors.push_back(std::fabs(e.value - exact[i]));
        max_bound = std::max(max_bound, e.error_bound);
      }
      std::sort(errors.begin(), errors.end());
      std::printf("| %zuk tris | %s, %zuk | %g | %.3f | %s | %s | %s | %s | %.0f× | %.1e | %.1e | %.1e |\n",
                  mesh.triangles.size() / 1000, set.near ? "near ±2 %" : "box", points.size() / 1000, beta, build,
                  per_second(value_rate).c_str(), per_second(estimate_rate).c_str(), per_second(above_rate).c_str(),
                  per_second(direct_rate).c_str(), value_rate / direct_rate, errors.back(), errors[errors.size() / 2],
                  max_bound);
      std::fflush(stdout);
    }
  }
  std::printf("\none thread; rates are queries per process CPU second (best of %d), the direct sum's on a subset of "
              "the points; errors |value − direct| on that subset\n",
              runs);
  return 0;
}
