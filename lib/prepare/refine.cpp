#include "prepare/refine.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace hairfit {

namespace {


// One round: every triangle into four, the midpoints numbered in the order the triangles meet
// their edges (deterministic).
void split_once(Mesh& mesh, std::vector<Vec3>& colors) {
  std::unordered_map<long long, int> midpoint;
  midpoint.reserve(mesh.triangles.size() * 2);
  const bool with_colors = colors.size() == mesh.positions.size();
  auto middle = [&](int a, int b) {
    const auto [at, added] = midpoint.try_emplace(edge_key(a, b), static_cast<int>(mesh.positions.size()));
    if (added) {
      mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
      if (with_colors) colors.push_back(0.5 * (colors[a] + colors[b]));
    }
    return at->second;
  };
  std::vector<Vec3i> triangles;
  triangles.reserve(4 * mesh.triangles.size());
  for (const Vec3i& t : mesh.triangles) {
    const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
    triangles.emplace_back(t[0], ab, ca);
    triangles.emplace_back(ab, t[1], bc);
    triangles.emplace_back(ca, bc, t[2]);
    triangles.emplace_back(ab, bc, ca);
  }
  mesh.triangles = std::move(triangles);
}

}  // namespace

double median_edge_length(const Mesh& mesh) {
  std::vector<std::pair<long long, double>> edges;  // each edge once, by its key
  edges.reserve(3 * mesh.triangles.size());
  for (const Vec3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(edge_key(t[k], t[(k + 1) % 3]), (mesh.positions[t[k]] - mesh.positions[t[(k + 1) % 3]]).norm());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
              edges.end());
  if (edges.empty()) return 0.0;
  std::vector<double> lengths;
  lengths.reserve(edges.size());
  for (const auto& e : edges) lengths.push_back(e.second);
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  return lengths[lengths.size() / 2];
}

Refined refine_coarse_scan(const Mesh& mesh, const std::vector<Vec3>& colors, double max_median_edge) {
  Refined r;
  r.mesh = mesh;
  r.colors = colors;
  r.median_edge_before = r.median_edge_after = median_edge_length(mesh);
  while (r.splits < 4 && r.median_edge_after > max_median_edge) {
    split_once(r.mesh, r.colors);
    ++r.splits;
    r.median_edge_after = median_edge_length(r.mesh);
  }
  return r;
}

}  // namespace hairfit
