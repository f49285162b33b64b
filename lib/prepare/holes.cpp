#include "prepare/holes.h"

#include <algorithm>

namespace hairfit {

double loop_length(const Mesh& mesh, const std::vector<int>& loop) {
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    length += (mesh.positions[loop[(i + 1) % loop.size()]] - mesh.positions[loop[i]]).norm();
  return length;
}

FilledHoles fill_holes(Mesh& mesh, const MeshTopology& topology, double max_share) {
  FilledHoles f;
  const std::vector<std::vector<int>>& loops = topology.boundary_loops;
  if (loops.empty()) return f;
  std::vector<double> lengths;
  for (const auto& loop : loops) lengths.push_back(loop_length(mesh, loop));
  f.rim = static_cast<int>(std::max_element(lengths.begin(), lengths.end()) - lengths.begin());
  f.rim_length = lengths[f.rim];
  for (int l = 0; l < static_cast<int>(loops.size()); ++l) {
    if (l == f.rim) continue;
    const std::vector<int>& loop = loops[l];
    Vec3 centroid = Vec3::Zero();
    for (int v : loop) centroid += mesh.positions[v];
    centroid /= static_cast<double>(loop.size());
    if (lengths[l] > max_share * f.rim_length) {
      if (f.open++ == 0 || lengths[l] > f.longest_open) f.longest_open = lengths[l], f.open_at = centroid;
      continue;
    }
    // Boundary half-edges run a→b in the triangles' direction; the filling runs them b→a.
    int centre = -1;
    if (loop.size() == 3) {
      mesh.triangles.emplace_back(loop[2], loop[1], loop[0]);
    } else {
      centre = static_cast<int>(mesh.positions.size());
      mesh.positions.push_back(centroid);
      for (std::size_t i = 0; i < loop.size(); ++i) mesh.triangles.emplace_back(loop[(i + 1) % loop.size()], loop[i], centre);
    }
    f.loops.push_back(loop);
    f.centres.push_back(centre);
    f.longest_filled = std::max(f.longest_filled, lengths[l]);
    ++f.filled;
  }
  return f;
}

}  // namespace hairfit
