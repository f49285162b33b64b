#include "core/mesh_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <unordered_set>

#include "core/weld.h"

namespace hairfit {

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is a set's lowest element
  }
};

// Numbers the sets of `sets` 0, 1, … in the order of their lowest element.
std::vector<int> label_sets(UnionFind& sets, int& count) {
  const int n = static_cast<int>(sets.parent.size());
  std::vector<int> label(n, -1);
  count = 0;
  for (int i = 0; i < n; ++i) {
    const int root = sets.find(i);
    if (label[root] < 0) label[root] = count++;
    label[i] = label[root];
  }
  return label;
}

struct TriangleKeyHash {
  std::size_t operator()(const std::array<int, 3>& k) const {
    std::size_t h = static_cast<std::size_t>(k[0]);
    h = h * 1000003u ^ static_cast<std::size_t>(k[1]);
    return h * 1000003u ^ static_cast<std::size_t>(k[2]);
  }
};

// Whether triangle t runs a→b (rather than b→a) along one of its sides.
bool runs(const Vec3i& t, int a, int b) {
  return (t[0] == a && t[1] == b) || (t[1] == a && t[2] == b) || (t[2] == a && t[0] == b);
}

// Undirected edges and the triangles on each, ascending by edge key and, within an edge, by
// triangle index.
struct Edges {
  std::vector<long long> keys;
  std::vector<int> begin;      // edge e's triangles: on[begin[e] .. begin[e + 1])
  std::vector<int> on;
  std::vector<std::array<int, 2>> ends;  // its vertices, lower first

  explicit Edges(const std::vector<Vec3i>& triangles) {
    std::vector<std::pair<long long, int>> uses;
    uses.reserve(3 * triangles.size());
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
      for (int k = 0; k < 3; ++k) uses.emplace_back(edge_key(triangles[t][k], triangles[t][(k + 1) % 3]), t);
    std::sort(uses.begin(), uses.end());
    for (std::size_t i = 0; i < uses.size(); ++i) {
      if (i == 0 || uses[i].first != uses[i - 1].first) {
        keys.push_back(uses[i].first);
        begin.push_back(static_cast<int>(i));
        ends.push_back({static_cast<int>(uses[i].first >> 32), static_cast<int>(uses[i].first & 0xffffffffLL)});
      }
      on.push_back(uses[i].second);
    }
    begin.push_back(static_cast<int>(uses.size()));
  }
  int size() const { return static_cast<int>(keys.size()); }
  int count(int e) const { return begin[e + 1] - begin[e]; }
  int triangle(int e, int i) const { return on[begin[e] + i]; }
  int find(int a, int b) const {
    const long long key = edge_key(a, b);
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    return it != keys.end() && *it == key ? static_cast<int>(it - keys.begin()) : -1;
  }
};

// Welds the used vertices, drops degenerate and duplicate triangles, and compacts the vertices:
// fills `out.mesh`, `out.old_to_new_vertex` and the input and dropping counts of the report.
void weld_and_filter(const Mesh& raw, double tolerance, CleanMesh& out) {
  MeshReport& r = out.report;
  const int n = static_cast<int>(raw.positions.size());
  r.input_vertices = n;
  r.input_triangles = static_cast<int>(raw.triangles.size());
  std::vector<char> used(n, 0);
  for (const Vec3i& t : raw.triangles)
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n) throw std::out_of_range("clean_mesh: a triangle refers to a vertex that does not exist");
      used[t[k]] = 1;
    }
  std::vector<int> used_ids;
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i)
    if (used[i]) {
      used_ids.push_back(i);
      points.push_back(raw.positions[i]);
    }
  const std::vector<int> kept_as = weld_points(points, tolerance);
  std::vector<int> representative(n, -1);  // per used input vertex: the input vertex it is welded to
  for (std::size_t j = 0; j < used_ids.size(); ++j) {
    representative[used_ids[j]] = used_ids[kept_as[j]];
    if (kept_as[j] != static_cast<int>(j)) ++r.welded_vertices;
  }

  // A triangle is degenerate when welding repeats a corner or its corners are collinear to
  // within 1e-12 of its longest edge: |(b−a)×(c−a)| = L·h ≤ 1e-12·L² says its height h over the
  // longest edge L is below 1e-12·L, whatever its size (rounding alone leaves about 1e-16·L²).
  std::vector<Vec3i> kept;
  std::unordered_set<std::array<int, 3>, TriangleKeyHash> seen;
  for (const Vec3i& t : raw.triangles) {
    const Vec3i w(representative[t[0]], representative[t[1]], representative[t[2]]);
    const Vec3 &a = raw.positions[w[0]], &b = raw.positions[w[1]], &c = raw.positions[w[2]];
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0] || (b - a).cross(c - a).norm() <= 1e-12 * longest) {
      ++r.degenerate_triangles;
      continue;
    }
    std::array<int, 3> key{w[0], w[1], w[2]};
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) {
      ++r.duplicate_triangles;
      continue;
    }
    kept.push_back(w);
  }

  // The kept triangles' vertices, in input order.
  std::vector<int> new_index(n, -1);
  for (const Vec3i& t : kept)
    for (int k = 0; k < 3; ++k) new_index[t[k]] = 0;
  for (int i = 0; i < n; ++i)
    if (new_index[i] == 0) {
      new_index[i] = static_cast<int>(out.mesh.positions.size());
      out.mesh.positions.push_back(raw.positions[i]);
    }
  out.mesh.triangles.reserve(kept.size());
  for (const Vec3i& t : kept) out.mesh.triangles.emplace_back(new_index[t[0]], new_index[t[1]], new_index[t[2]]);
  out.old_to_new_vertex.assign(n, -1);
  for (int i = 0; i < n; ++i)
    if (representative[i] >= 0) out.old_to_new_vertex[i] = new_index[representative[i]];
}

// Parts: triangles joined through any shared edge, numbered largest first (ties: the part with the
// earlier triangle first). Returns each triangle's part and fills the report's part counts.
std::vector<int> find_parts(const Edges& edges, int triangles, MeshReport& r) {
  UnionFind sets(triangles);
  for (int e = 0; e < edges.size(); ++e)
    for (int i = 1; i < edges.count(e); ++i) sets.join(edges.triangle(e, 0), edges.triangle(e, i));
  int count = 0;
  const std::vector<int> set_of = label_sets(sets, count);  // numbered by first triangle
  std::vector<int> size(count, 0);
  for (int s : set_of) ++size[s];
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return size[a] > size[b]; });
  std::vector<int> part_of_set(count);
  for (int p = 0; p < count; ++p) part_of_set[order[p]] = p;
  r.parts = count;
  r.part_triangles.resize(count);
  for (int p = 0; p < count; ++p) r.part_triangles[p] = size[order[p]];
  std::vector<int> part(triangles);
  for (int t = 0; t < triangles; ++t) part[t] = part_of_set[set_of[t]];
  return part;
}

// Orients the triangles consistently where the mesh allows it.
//
// A patch is a maximal set of triangles joined through manifold edges (exactly 2 triangles) that
// the two triangles run in opposite directions, i.e. a consistently wound piece of the input.
// Patches meeting at a manifold edge run it the same way, so one of the two must turn over; a
// region is a maximal set of patches joined that way, and its patches get alternating signs by a
// breadth-first search in the order of their first triangle. A region keeps the sign whose patches
// cover more area (a tie keeps the region's first patch) and flips the others; in a part without
// non-manifold edges the region is the whole part, so the winding covering more of the part wins.
// Regions of one part meet only at non-manifold edges, across which agreeing is not defined (three
// sheets on one edge cannot pairwise agree), so each region decides alone and two patches joined
// only through a non-manifold edge may stay wound against each other. In a non-orientable region
// (a Möbius strip) some edge stays misoriented whatever is flipped; it is counted, and which edge
// it is depends only on the triangle order.
void orient(const Edges& edges, const std::vector<Vec3>& positions, std::vector<Vec3i>& triangles, MeshReport& r) {
  const int n = static_cast<int>(triangles.size());
  auto same_way = [&](int e) {
    const auto [a, b] = edges.ends[e];
    return runs(triangles[edges.triangle(e, 0)], a, b) == runs(triangles[edges.triangle(e, 1)], a, b);
  };
  UnionFind sets(n);
  for (int e = 0; e < edges.size(); ++e)
    if (edges.count(e) == 2 && !same_way(e)) sets.join(edges.triangle(e, 0), edges.triangle(e, 1));
  int patches = 0;
  const std::vector<int> patch = label_sets(sets, patches);
  std::vector<double> area(patches, 0.0);
  std::vector<int> size(patches, 0);
  for (int t = 0; t < n; ++t) {
    const Vec3 &a = positions[triangles[t][0]], &b = positions[triangles[t][1]], &c = positions[triangles[t][2]];
    area[patch[t]] += 0.5 * (b - a).cross(c - a).norm();
    ++size[patch[t]];
  }
  std::vector<std::vector<int>> across(patches);  // patches that meet this one at a same-way edge
  for (int e = 0; e < edges.size(); ++e)
    if (edges.count(e) == 2 && same_way(e)) {
      const int p = patch[edges.triangle(e, 0)], q = patch[edges.triangle(e, 1)];
      if (p == q) continue;  // a twisted patch: nothing to flip
      across[p].push_back(q);
      across[q].push_back(p);
    }
  for (auto& list : across) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  std::vector<int> sign(patches, 0);  // ±1 within the region, 0 before the search reaches it
  std::vector<char> flip(patches, 0);
  for (int start = 0; start < patches; ++start) {
    if (sign[start]) continue;
    std::vector<int> region{start};
    sign[start] = 1;
    double plus = 0.0, minus = 0.0;
    for (std::size_t i = 0; i < region.size(); ++i) {
      const int p = region[i];
      (sign[p] > 0 ? plus : minus) += area[p];
      for (int q : across[p])
        if (!sign[q]) {
          sign[q] = -sign[p];
          region.push_back(q);
        }
    }
    const int keep = minus > plus ? -1 : 1;
    for (int p : region)
      if (sign[p] != keep) {
        flip[p] = 1;
        ++r.flipped_patches;
        r.flipped_triangles += size[p];
      }
  }
  for (int t = 0; t < n; ++t)
    if (flip[patch[t]]) std::swap(triangles[t][1], triangles[t][2]);
  for (int e = 0; e < edges.size(); ++e) {
    if (edges.count(e) == 2 && same_way(e)) ++r.misoriented_edges;
    if (edges.count(e) >= 3) ++r.nonmanifold_edges;
  }
}

// Boundary loops: the edges of one triangle, chained end to end. From the far end v of a boundary
// edge the walk turns about v through the triangles on v's manifold edges to the next boundary edge
// at v, so a loop that touches itself at a vertex stays one loop. The walk ignores which way the
// triangles run, so a non-orientable part's rim (a Möbius strip's single loop) is one loop too.
// Where the turn meets a non-manifold edge, the walk takes the lowest unwalked boundary edge of the
// same part at v, and where there is none it ends (an open chain, counted as a loop as well).
void find_loops(const Edges& edges, const Mesh& mesh, const std::vector<int>& part, MeshReport& r) {
  const std::vector<Vec3i>& triangles = mesh.triangles;
  std::vector<std::vector<int>> boundary_at(mesh.positions.size());  // boundary edges at a vertex, ascending
  for (int e = 0; e < edges.size(); ++e)
    if (edges.count(e) == 1)
      for (int v : edges.ends[e]) boundary_at[v].push_back(e);
  // The boundary edge after boundary edge e about its end v, or −1.
  auto turn = [&](int e, int v) {
    int t = edges.triangle(e, 0);
    int f = e;
    for (int step = 0; step <= static_cast<int>(triangles.size()); ++step) {
      const auto [a, b] = edges.ends[f];
      const int came_from = a == v ? b : a;
      int w = triangles[t][0];  // the corner of t that is neither v nor came_from
      for (int k = 0; k < 3; ++k)
        if (triangles[t][k] != v && triangles[t][k] != came_from) w = triangles[t][k];
      f = edges.find(v, w);
      if (edges.count(f) == 1) return f;
      if (edges.count(f) != 2) return -1;
      t = edges.triangle(f, 0) == t ? edges.triangle(f, 1) : edges.triangle(f, 0);
    }
    return -1;
  };

  std::vector<std::vector<double>> lengths(r.parts);  // per part, its loops' lengths
  std::vector<char> walked(edges.size(), 0);
  for (int start = 0; start < edges.size(); ++start) {
    if (edges.count(start) != 1 || walked[start]) continue;
    const int loop_part = part[edges.triangle(start, 0)];
    double length = 0.0;
    int v = edges.ends[start][1];
    for (int e = start; e >= 0;) {
      walked[e] = 1;
      length += (mesh.positions[edges.ends[e][0]] - mesh.positions[edges.ends[e][1]]).norm();
      int next = turn(e, v);
      if (next == start) break;
      if (next < 0 || walked[next]) {
        next = -1;
        for (int g : boundary_at[v])
          if (!walked[g] && part[edges.triangle(g, 0)] == loop_part) {
            next = g;
            break;
          }
      }
      if (next >= 0) v = edges.ends[next][0] == v ? edges.ends[next][1] : edges.ends[next][0];
      e = next;
    }
    lengths[loop_part].push_back(length);
  }
  for (const std::vector<double>& loops : lengths) {
    if (loops.empty()) continue;
    r.boundary_loops += static_cast<int>(loops.size());
    const std::size_t rim = std::max_element(loops.begin(), loops.end()) - loops.begin();
    for (std::size_t i = 0; i < loops.size(); ++i)
      if (i != rim) {
        ++r.holes;
        r.longest_hole = std::max(r.longest_hole, loops[i]);
      }
  }
}

std::string counted(long long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

CleanMesh clean_mesh(const Mesh& raw, double weld_tolerance) {
  CleanMesh out;
  weld_and_filter(raw, weld_tolerance, out);
  const Edges edges(out.mesh.triangles);
  const std::vector<int> part = find_parts(edges, static_cast<int>(out.mesh.triangles.size()), out.report);
  orient(edges, out.mesh.positions, out.mesh.triangles, out.report);
  find_loops(edges, out.mesh, part, out.report);
  return out;
}

std::string describe(const MeshReport& r) {
  std::string s = counted(r.parts, "part", "parts");
  if (r.parts > 0) {
    // The eight largest parts' sizes; the others are only counted.
    s += " (";
    const int shown = std::min(r.parts, 8);
    for (int p = 0; p < shown; ++p) s += (p ? ", " : "") + std::to_string(r.part_triangles[p]);
    s += r.parts == 1 && r.part_triangles[0] == 1 ? " triangle" : " triangles";
    if (r.parts > shown) s += " and " + counted(r.parts - shown, "smaller part", "smaller parts");
    s += ")";
  }
  const int rims = r.boundary_loops - r.holes;
  s += ", " + counted(r.boundary_loops, "boundary loop", "boundary loops");
  if (r.boundary_loops == 1)
    s += " (the rim)";
  else if (rims > 0)
    s += " (" + counted(rims, "rim", "rims") + ")";
  s += ", " + counted(r.holes, "hole", "holes");
  if (r.holes > 0) {
    char longest[32];
    std::snprintf(longest, sizeof longest, "%.3g", r.longest_hole);
    s += " (longest perimeter " + std::string(longest) + ")";
  }
  s += ", " + counted(r.nonmanifold_edges, "non-manifold edge", "non-manifold edges");
  s += ", " + counted(r.flipped_patches, "flipped patch", "flipped patches");
  if (r.flipped_patches > 0) s += " (" + counted(r.flipped_triangles, "triangle", "triangles") + ")";
  if (r.misoriented_edges > 0)
    s += ", " + counted(r.misoriented_edges, "edge", "edges") + " left misoriented (a non-orientable part)";
  s += ", " + counted(r.welded_vertices, "welded vertex", "welded vertices");
  s += ", " + std::to_string(r.duplicate_triangles) + " duplicate and " + std::to_string(r.degenerate_triangles) +
       " zero-area triangles dropped";
  return s;
}

}  // namespace hairfit
