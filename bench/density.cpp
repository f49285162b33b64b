// Density deposits at the paper's scale (§3.5): 3000 guide strands × 64 segments, wisp radius
// 0.3–0.6 cm, voxel 0.25 cm, a 30 cm cube (120³ cells). Times BOM voxelisation (frustum and the
// paper's OBB test), CDM traversal (guides, and 90 000 fibres), the guide loop's batch pattern
// (deposit a batch, freeze, repeat) and the statistics; for 1 and 2 threads, best of 3.
//   bench_density [--guides N] [--batch B]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/random.h"
#include "density/accumulator.h"
#include "density/statistics.h"
#include "density/traversal.h"

using namespace hairfit;

namespace {

// Best wall time of `repeats` runs; prints the process CPU time of that run too, because the
// 2-core machine is shared and wall time alone overstates the cost when others are busy.
double best_seconds(const std::function<void()>& run, int repeats = 3) {
  double best = 1e300, cpu = 0.0;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    run();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (wall < best) {
      best = wall;
      cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    }
  }
  std::printf("  [cpu %.3f s] ", cpu);
  return best;
}

// Hair-like strands: roots on the upper half of a 9 cm sphere, out along the normal, then
// falling with a small random curl; 64 segments over about 24 cm.
std::vector<std::vector<Vec3>> make_guides(int count, int segments) {
  std::vector<std::vector<Vec3>> out;
  for (int g = 0; g < count; ++g) {
    Random rng(7, RandomStage::test, g);
    Vec3 n;
    do n = Vec3(rng.normal(), std::abs(rng.normal()), rng.normal()); while (n.norm() < 1e-3);
    n.normalize();
    Vec3 p = 9.0 * n, dir = n;
    std::vector<Vec3> strand;
    for (int s = 0; s <= segments; ++s) {
      strand.push_back(p);
      dir = (dir + 0.08 * Vec3(0, -1, 0) + 0.1 * Vec3(rng.normal(), rng.normal(), rng.normal())).normalized();
      if ((p + 0.375 * dir).norm() < 9.0) dir = (dir + p.normalized()).normalized();  // stay off the head
      p += 0.375 * dir;
    }
    out.push_back(strand);
  }
  return out;
}

std::vector<Tube> make_tubes(const std::vector<std::vector<Vec3>>& guides) {
  std::vector<Tube> tubes;
  for (size_t g = 0; g < guides.size(); ++g) {
    Random rng(8, RandomStage::test, g);
    const double root = rng.uniform(0.45, 0.6), tip = rng.uniform(0.3, 0.45);
    Tube t{guides[g], {}};
    for (size_t i = 0; i < guides[g].size(); ++i) t.radii.push_back(root + (tip - root) * i / (guides[g].size() - 1.0));
    tubes.push_back(t);
  }
  return tubes;
}

// 30 fibres per guide, offset inside its wisp (the strand generator's job, approximated).
std::vector<std::vector<Vec3>> make_fibres(const std::vector<std::vector<Vec3>>& guides, int per_guide) {
  std::vector<std::vector<Vec3>> out;
  for (size_t g = 0; g < guides.size(); ++g)
    for (int f = 0; f < per_guide; ++f) {
      Random rng(9, RandomStage::test, g * per_guide + f);
      const Vec3 offset(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
      std::vector<Vec3> fibre = guides[g];
      for (Vec3& p : fibre) p += offset;
      out.push_back(fibre);
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int guides_count = 3000, batch = 64;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (!std::strcmp(argv[a], "--guides")) guides_count = std::atoi(argv[a + 1]);
    if (!std::strcmp(argv[a], "--batch")) batch = std::atoi(argv[a + 1]);
  }
  const int segments = 64;
  const GridGeometry grid = make_grid_geometry(Vec3(-15, -15, -15), Vec3(15, 15, 15), 0.25);
  const auto guides = make_guides(guides_count, segments);
  const auto tubes = make_tubes(guides);
  const auto fibres = make_fibres(guides, 30);
  const Curves guide_curves = make_curves(guides), fibre_curves = make_curves(fibres);
  std::printf("grid %dx%dx%d cells (h = %.2f cm), %d guides x %d segments, %zu fibres\n", grid.dims.x(),
              grid.dims.y(), grid.dims.z(), grid.voxel, guides_count, segments, fibres.size());

  // Work counts (untimed): voxel–frustum hits and cell crossings.
  int64_t hits = 0, hits_obb = 0, crossings = 0;
  for (const Tube& t : tubes)
    for (size_t s = 0; s + 1 < t.points.size(); ++s) {
      const Frustum f{t.points[s], t.points[s + 1], t.radii[s], t.radii[s + 1]};
      hits += int64_t(frustum_cells(grid, f, OccupancyShape::frustum).size());
      hits_obb += int64_t(frustum_cells(grid, f, OccupancyShape::obb).size());
    }
  for (const auto& g : guides)
    for (size_t s = 0; s + 1 < g.size(); ++s) crossings += int64_t(traverse_segment(grid, g[s], g[s + 1]).size());
  std::printf("voxel hits per deposit: frustum %lld, obb %lld (%.0f%% more); guide cell crossings %lld\n",
              (long long)hits, (long long)hits_obb, 100.0 * (hits_obb - hits) / hits, (long long)crossings);

  for (int threads : {1, 2}) {
    std::printf("\n--- %d thread(s) ---\n", threads);
    const double bom = best_seconds([&] {
      DensityAccumulator acc(grid);
      acc.occupy_all(tubes, threads, OccupancyShape::frustum);
    });
    std::printf("BOM frustum  : %.3f s  %.0f strands/s  %.3g voxel hits/s\n", bom, guides_count / bom, hits / bom);
    const double obb = best_seconds([&] {
      DensityAccumulator acc(grid);
      acc.occupy_all(tubes, threads, OccupancyShape::obb);
    });
    std::printf("BOM obb      : %.3f s  %.0f strands/s  %.3g voxel hits/s\n", obb, guides_count / obb, hits_obb / obb);
    const double cdm = best_seconds([&] {
      DensityAccumulator acc(grid);
      acc.add_fibres(guide_curves, threads);
    });
    std::printf("CDM guides   : %.4f s  %.0f strands/s  %.3g cell crossings/s\n", cdm, guides_count / cdm, crossings / cdm);
    const double cdm_fibres = best_seconds([&] {
      DensityAccumulator acc(grid);
      acc.add_fibres(fibre_curves, threads);
    }, 2);
    std::printf("CDM fibres   : %.3f s  %.0f fibres/s\n", cdm_fibres, fibres.size() / cdm_fibres);
    // The guide loop: deposit a batch, freeze the grid the next batch is optimised against.
    const double loop = best_seconds([&] {
      DensityAccumulator acc(grid);
      for (size_t b = 0; b < tubes.size(); b += size_t(batch)) {
        const std::vector<Tube> part(tubes.begin() + b, tubes.begin() + std::min(tubes.size(), b + size_t(batch)));
        acc.occupy_all(part, threads);
        const DensityGrid frozen = acc.freeze();
        (void)frozen;
      }
    });
    std::printf("BOM loop     : %.3f s  (batches of %d, deposit + freeze each)\n", loop, batch);
    const double hist = best_seconds([&] { (void)segment_histogram(grid, fibre_curves, threads); }, 2);
    std::printf("histogram    : %.3f s  (90k fibres)\n", hist);
  }
  DensityAccumulator acc(grid);
  acc.add_fibres(fibre_curves, 2);
  const double freeze = best_seconds([&] { (void)acc.freeze(); });
  const DensityGrid cdm_grid = acc.freeze();
  const double stats = best_seconds([&] { (void)density_statistics(cdm_grid); });
  const double slice = best_seconds([&] { (void)centre_slice(cdm_grid, Vec3(1, 0, 0), Vec3(0, 1, 0)); });
  const DensityStatistics s = density_statistics(cdm_grid);
  std::printf("\nfreeze (copy of %.1f MB): %.4f s; statistics: %.4f s; centre slice: %.4f s\n",
              grid.count() * 8.0 / 1e6, freeze, stats, slice);
  std::printf("90k-fibre CDM: occupied %lld cells, CV %.3f, empty share %.3f of the grid\n", (long long)s.occupied_cells,
              s.coefficient_of_variation, s.empty_share);
  return 0;
}
