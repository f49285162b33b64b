#include "prepare/untangle.h"

#include <algorithm>

#include "prepare/surface_checks.h"

namespace hairfit {

Untangled untangle_self_intersections(Mesh& mesh, int threads, int max_rounds, int passes) {
  Untangled u;
  std::vector<std::pair<int, int>> pairs = self_intersections(mesh, kMaxUntanglePairs, threads);
  u.pairs_found = u.pairs_left = static_cast<int>(pairs.size());
  if (pairs.empty()) return u;
  u.first_found = triangle_centroid(mesh, pairs[0].first);
  const int n = static_cast<int>(mesh.positions.size());
  const std::vector<std::vector<int>> next = vertex_neighbours(mesh);
  std::vector<char> fixed(n, 0);
  for (const auto& loop : analyse_topology(mesh).boundary_loops)
    for (int v : loop) fixed[v] = 1;
  const std::vector<Vec3> start = mesh.positions;
  std::vector<char> moved(n, 0);
  for (int round = 1; round <= max_rounds && !pairs.empty(); ++round) {
    // The crossing triangles' vertices, grown by `round` rings.
    std::vector<char> in_region(n, 0);
    std::vector<int> region;
    for (const auto& [s, t] : pairs)
      for (int tri : {s, t})
        for (int k = 0; k < 3; ++k) {
          const int v = mesh.triangles[tri][k];
          if (!in_region[v]) in_region[v] = 1, region.push_back(v);
        }
    for (int ring = 0; ring < round; ++ring) {
      const std::size_t size = region.size();
      for (std::size_t i = 0; i < size; ++i)
        for (int w : next[region[i]])
          if (!in_region[w]) in_region[w] = 1, region.push_back(w);
    }
    std::sort(region.begin(), region.end());
    std::vector<Vec3> previous;
    for (int pass = 0; pass < passes; ++pass) {
      previous = mesh.positions;
      for (int v : region) {
        if (fixed[v] || next[v].empty()) continue;
        Vec3 mean = Vec3::Zero();
        for (int w : next[v]) mean += previous[w];
        mesh.positions[v] = 0.5 * (previous[v] + mean / static_cast<double>(next[v].size()));
        moved[v] = 1;
      }
    }
    u.rounds = round;
    pairs = self_intersections(mesh, kMaxUntanglePairs, threads);
  }
  u.pairs_left = static_cast<int>(pairs.size());
  if (!pairs.empty()) u.first_left = triangle_centroid(mesh, pairs[0].first);
  for (int v = 0; v < n; ++v)
    if (moved[v]) ++u.vertices_moved, u.largest_move = std::max(u.largest_move, (mesh.positions[v] - start[v]).norm());
  return u;
}

}  // namespace hairfit
