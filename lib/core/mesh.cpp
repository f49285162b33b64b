#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <queue>

#include "core/vertex_sort.h"

namespace hairfit {

namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

MeshTopology analyse_topology(const Mesh& mesh) {
  MeshTopology topo;
  const int n = static_cast<int>(mesh.positions.size());
  topo.faces = static_cast<int>(mesh.triangles.size());

  // Directed half-edges (a→b) per undirected edge, sorted by edge; an edge is boundary when used once.
  struct HalfEdge {
    int low, high;
    bool forward;  // runs low → high
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * mesh.triangles.size());
  std::vector<char> used(n, 0);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Vec3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      used[a] = 1;
      half_edges.push_back({std::min(a, b), std::max(a, b), a < b});
      parent[find_root(parent, a)] = find_root(parent, b);
    }
  }
  sort_by_vertex(half_edges, n, [](const HalfEdge& h) { return h.low; },
                 [](const HalfEdge& x, const HalfEdge& y) { return x.high < y.high; });
  struct EdgeUse {
    int low, high;
    int count = 0;
    int forward = 0;  // uses as low → high
  };
  std::vector<EdgeUse> edges;
  for (std::size_t i = 0; i < half_edges.size(); ++i) {
    const HalfEdge& h = half_edges[i];
    if (i == 0 || h.low != half_edges[i - 1].low || h.high != half_edges[i - 1].high) edges.push_back({h.low, h.high});
    ++edges.back().count;
    edges.back().forward += h.forward;
  }
  topo.vertices = static_cast<int>(std::count(used.begin(), used.end(), 1));
  topo.edges = static_cast<int>(edges.size());
  topo.euler_characteristic = topo.vertices - topo.edges + topo.faces;
  for (int i = 0; i < n; ++i)
    if (used[i] && find_root(parent, i) == i) ++topo.components;

  // Boundary half-edges keep the triangle's direction, so loops come out consistently oriented.
  std::multimap<int, int> next;  // boundary half-edge a→b
  std::vector<int> nonmanifold;
  for (const EdgeUse& use : edges) {
    if (use.count > 2) {
      nonmanifold.push_back(use.low);
      nonmanifold.push_back(use.high);
    }
    if (use.count == 2 && use.forward != 1) topo.orientation_consistent = false;
    if (use.count == 1) {
      if (use.forward == 1)
        next.emplace(use.low, use.high);
      else
        next.emplace(use.high, use.low);
    }
  }
  std::sort(nonmanifold.begin(), nonmanifold.end());
  nonmanifold.erase(std::unique(nonmanifold.begin(), nonmanifold.end()), nonmanifold.end());
  topo.nonmanifold_vertices = nonmanifold;

  while (!next.empty()) {
    std::vector<int> loop;
    auto it = next.begin();
    const int start = it->first;
    int current = start;
    while (it != next.end()) {
      loop.push_back(current);
      const int to = it->second;
      next.erase(it);
      if (to == start) break;
      current = to;
      it = next.find(current);
    }
    topo.boundary_loops.push_back(std::move(loop));
  }
  return topo;
}

std::vector<double> edge_distances(const Mesh& mesh, const std::vector<std::vector<int>>& neighbours,
                                   const std::vector<int>& sources) {
  std::vector<double> d(mesh.positions.size(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int s : sources) d[s] = 0.0, queue.emplace(0.0, s);
  while (!queue.empty()) {
    const auto [dist, v] = queue.top();
    queue.pop();
    if (dist > d[v]) continue;
    for (int u : neighbours[v]) {
      const double through = dist + (mesh.positions[u] - mesh.positions[v]).norm();
      if (through < d[u]) d[u] = through, queue.emplace(through, u);
    }
  }
  return d;
}

std::vector<std::vector<int>> vertex_neighbours(const Mesh& mesh) {
  std::vector<std::vector<int>> out(mesh.positions.size());
  for (const Vec3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      out[t[k]].push_back(t[(k + 1) % 3]);
      out[t[(k + 1) % 3]].push_back(t[k]);
    }
  for (auto& n : out) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return out;
}

double triangle_area(const Mesh& mesh, int triangle) {
  const Vec3i& t = mesh.triangles[triangle];
  const Vec3& a = mesh.positions[t[0]];
  return 0.5 * (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm();
}

std::vector<double> vertex_areas(const Mesh& mesh) {
  std::vector<double> area(mesh.positions.size(), 0.0);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) area[v] += triangle_area(mesh, t) / 3.0;
  return area;
}

double surface_area(const Mesh& mesh) {
  double area = 0.0;
  for (int i = 0; i < static_cast<int>(mesh.triangles.size()); ++i) area += triangle_area(mesh, i);
  return area;
}

Vec3 triangle_normal(const Mesh& mesh, int triangle) {
  const Vec3i& t = mesh.triangles[triangle];
  const Vec3& a = mesh.positions[t[0]];
  const Vec3 n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

Vec3 triangle_centroid(const Mesh& mesh, int triangle) {
  const Vec3i& t = mesh.triangles[triangle];
  return (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
}

Vec3 frame_origin(const Vec3& lo, const Vec3& hi) {
  const double size = (hi - lo).maxCoeff();
  if (!(size > 0.0) || !(hi - lo).allFinite()) return Vec3::Zero();
  const double quantum = std::ldexp(1.0, std::ilogb(size) + 5);  // 2^(⌊log₂ size⌋ + 5) ∈ (16, 32] sizes
  Vec3 origin;
  for (int axis = 0; axis < 3; ++axis) origin[axis] = quantum * std::round(0.5 * (lo[axis] + hi[axis]) / quantum);
  return origin;
}

int digits_for_far_data(int digits, double farthest, double size) {
  if (!(size > 0.0) || !(farthest > 10.0 * size) || !std::isfinite(farthest)) return digits;
  return std::min(17, digits + static_cast<int>(std::floor(std::log10(farthest / size))));
}

std::pair<Vec3, Vec3> bounding_box(const Mesh& mesh) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.positions[t[k]]);
      hi = hi.cwiseMax(mesh.positions[t[k]]);
    }
  return {lo, hi};
}

double winding_number(const Mesh& mesh, const Vec3& point) {
  double total = 0.0;
  for (const Vec3i& t : mesh.triangles)
    total += triangle_solid_angle(mesh.positions[t[0]] - point, mesh.positions[t[1]] - point,
                                  mesh.positions[t[2]] - point);
  return total / (4.0 * M_PI);
}

}  // namespace hairfit
