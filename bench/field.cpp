// bench_field: make_distance_field against OpenVDB's meshToSignedDistanceField (when built with
// OpenVDB) on closed bumpy tori of 20k and 200k triangles, 128³ and 256³ grids, bands of 3 and 6
// voxels; times (best of 3) and errors against brute-force exact distances on sampled band voxels.
//   usage: bench_field [--threads N] [--quick] [--only LABEL]   (--only: the rows of one mesh, e.g. "20k tris")
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "bench_support.h"
#include "core/mesh.h"
#include "core/fast_winding.h"
#include "field/distance_field.h"
#include "field/hair_region.h"
#include "io/obj_mesh.h"

#ifdef HAIRFIT_HAVE_OPENVDB
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>
#endif

using namespace hairfit;
using hairfit::bench::bumpy_torus;
using hairfit::bench::cpu_seconds;

namespace {


double point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  double best = std::min({(p - a).norm(), (p - b).norm(), (p - c).norm()});
  const Vec3 q[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 d = q[(k + 1) % 3] - q[k];
    const double t = std::clamp((p - q[k]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (q[k] + t * d)).norm());
  }
  const Vec3 u = b - a, v = c - a, w = p - a;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), wu = w.dot(u), wv = w.dot(v);
  const double det = uu * vv - uv * uv;
  const double s = (wu * vv - wv * uv) / det, t = (wv * uu - wu * uv) / det;
  if (s >= 0 && t >= 0 && s + t <= 1) best = std::min(best, (p - (a + s * u + t * v)).norm());
  return best;
}

double brute(const Mesh& m, const Vec3& p) {
  double best = 1e300;
  for (const Vec3i& f : m.triangles) {
    // Cheap reject by a sphere about the first vertex that holds the triangle.
    const Vec3& a = m.positions[f[0]];
    const double reach = std::max((m.positions[f[1]] - a).norm(), (m.positions[f[2]] - a).norm());
    if ((p - a).norm() - reach > best) continue;
    best = std::min(best, point_triangle(p, a, m.positions[f[1]], m.positions[f[2]]));
  }
  return best;
}


template <typename F>
double best_of(int runs, F&& f) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const double t0 = cpu_seconds();
    f();
    best = std::min(best, cpu_seconds() - t0);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 1;
  bool quick = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
  }
#ifdef HAIRFIT_HAVE_OPENVDB
  openvdb::initialize();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("| mesh | grid | band | ours CPU s | ours, robust sign, CPU s | OpenVDB CPU s | ratio | robust ratio | ours max err (voxel) | OpenVDB max err (voxel) | sign disagreements |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
#else
  std::printf("(built without OpenVDB: ours only)\n| mesh | grid | band | ours CPU s | ours, robust sign, CPU s | ours max err (voxel) |\n|---|---|---|---|---|---|\n");
#endif
  const int n_small = 100, n_large = 316;  // 20 000 and 199 712 triangles
  // Real, raw hulls (fixtures/makehuman, decimetres): open, in many parts, non-manifold.
  std::vector<std::pair<std::string, Mesh>> meshes;
  for (const char* name : {"hair_short04_full", "hair_bob01_full"})
    meshes.emplace_back(name, load_obj_mesh(std::string(HAIRFIT_SOURCE_DIR) + "/fixtures/makehuman/" + name + ".obj", 10.0).mesh);
  for (int n : {n_small, n_large}) meshes.emplace_back(std::to_string(n * n * 2 / 1000) + "k tris", bumpy_torus(n));
  for (const auto& [label, mesh] : meshes) {
    if (!only.empty() && label != only) continue;
    const auto box = bounding_box(mesh);
    const double extent = (box.second - box.first).maxCoeff();
    for (int cells : {128, 256}) {
      if (quick && cells == 256) continue;
      for (double band : {3.0, 6.0}) {
        // The voxel that makes the longest side of the grid about `cells` voxels.
        FieldSpec spec;
        spec.band = band;
        spec.voxel = extent / (cells - 2 * band - 8);
        spec.margin = (band + 2) * spec.voxel;
        const int runs = 3;
        DistanceField ours = make_distance_field(mesh, spec, threads);
        const double t_ours = best_of(runs, [&] { ours = make_distance_field(mesh, spec, threads); });
        // With the robust sign: the mesh's own generalized winding number > ½ (its tree built inside).
        const double t_robust = best_of(runs, [&] {
          const FastWindingNumber winding(mesh, HairRegion::kFirstBeta);
          const DistanceField robust = make_distance_field(mesh, spec, threads, RobustInside{{winding_soup(mesh, winding)}});
          if (robust.band_voxels() != ours.band_voxels()) std::abort();
        });
        const double h = ours.voxel();

        // Sample band voxels deterministically (every m-th in scan order) and compare.
        std::vector<Vec3i> samples;
        const int64_t stride = std::max<int64_t>(1, ours.band_voxels() / 300);
        int64_t seen = 0;
        for (int k = 0; k < ours.dims().z(); ++k)
          for (int j = 0; j < ours.dims().y(); ++j)
            for (int i = 0; i < ours.dims().x(); ++i)
              if (ours.in_band(i, j, k) && seen++ % stride == 0) samples.push_back(Vec3i(i, j, k));
        std::vector<double> exact(samples.size());
        for (size_t s = 0; s < samples.size(); ++s)
          exact[s] = brute(mesh, ours.origin() + h * samples[s].cast<double>());
        double err_ours = 0;
        for (size_t s = 0; s < samples.size(); ++s)
          err_ours = std::max(err_ours, std::abs(std::abs(ours.sample(samples[s][0], samples[s][1], samples[s][2])) - exact[s]));

#ifdef HAIRFIT_HAVE_OPENVDB
        std::vector<openvdb::Vec3s> points;
        for (const Vec3& p : mesh.positions) points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
        std::vector<openvdb::Vec3I> tris;
        for (const Vec3i& t : mesh.triangles) tris.emplace_back(t[0], t[1], t[2]);
        const std::vector<openvdb::Vec4I> quads;
        openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
        xform->postTranslate(openvdb::Vec3d(ours.origin().x(), ours.origin().y(), ours.origin().z()));
        openvdb::FloatGrid::Ptr vdb;
        const double t_vdb = best_of(runs, [&] {
          vdb = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(*xform, points, tris, quads, float(band),
                                                                              float(band));
        });
        auto acc = vdb->getConstAccessor();
        double err_vdb = 0;
        int disagree = 0, compared = 0;
        for (size_t s = 0; s < samples.size(); ++s) {
          if (exact[s] > 0.9 * band * h) continue;  // inside OpenVDB's band too
          const double v = acc.getValue(openvdb::Coord(samples[s][0], samples[s][1], samples[s][2]));
          const double o = ours.sample(samples[s][0], samples[s][1], samples[s][2]);
          err_vdb = std::max(err_vdb, std::abs(std::abs(v) - exact[s]));
          if (exact[s] > 0.5 * h && (v < 0) != (o < 0)) ++disagree;
          ++compared;
        }
        std::printf("| %s | %d×%d×%d | %g | %.3f | %.3f | %.3f | %.2f | %.2f | %.1e | %.1e | %d / %d |\n", label.c_str(),
                    ours.dims().x(), ours.dims().y(), ours.dims().z(), band, t_ours, t_robust, t_vdb, t_ours / t_vdb,
                    t_robust / t_vdb, err_ours / h, err_vdb / h, disagree, compared);
#else
        std::printf("| %s | %d×%d×%d | %g | %.3f | %.3f | %.1e |\n", label.c_str(), ours.dims().x(), ours.dims().y(),
                    ours.dims().z(), band, t_ours, t_robust, err_ours / h);
#endif
        std::fflush(stdout);
      }
    }
  }
  std::printf("\nthreads: %d for both (OpenVDB limited by tbb::global_control); times are process CPU seconds, best of 3\n",
              threads);
  return 0;
}
