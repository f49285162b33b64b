#include "prepare/surface_checks.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"
#include "field/hair_region.h"

namespace hairfit {

namespace {

// 2D segment intersection (closed), by orientation signs.
double orient2(const Vec2& a, const Vec2& b, const Vec2& c) { return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(); }

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = orient2(q1, q2, p1), d2 = orient2(q1, q2, p2), d3 = orient2(p1, p2, q1), d4 = orient2(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(q1, q2, p1)) || (d2 == 0 && on_segment(q1, q2, p2)) ||
         (d3 == 0 && on_segment(p1, p2, q1)) || (d4 == 0 && on_segment(p1, p2, q2));
}

bool inside_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = orient2(a, b, p), d2 = orient2(b, c, p), d3 = orient2(c, a, p);
  return !((d1 < 0 || d2 < 0 || d3 < 0) && (d1 > 0 || d2 > 0 || d3 > 0));
}

bool coplanar_intersect(const Vec3& normal, const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  // Drop the axis along which the normal is largest.
  int drop = 0;
  normal.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  std::array<Vec2, 3> p, q;
  for (int i = 0; i < 3; ++i) p[i] = Vec2(a[i][u], a[i][v]), q[i] = Vec2(b[i][u], b[i][v]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_intersect(p[i], p[(i + 1) % 3], q[j], q[(j + 1) % 3])) return true;
  return inside_triangle(p[0], q[0], q[1], q[2]) || inside_triangle(q[0], p[0], p[1], p[2]);
}

// The interval the triangle (projected values p, signed distances d to the other plane) cuts on
// the intersection line. The caller has excluded all-positive, all-negative and all-zero d.
std::pair<double, double> interval(const std::array<double, 3>& p, const std::array<double, 3>& d) {
  std::vector<double> t;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (d[i] == 0.0) t.push_back(p[i]);
    if ((d[i] < 0 && d[j] > 0) || (d[i] > 0 && d[j] < 0)) t.push_back(p[i] + (p[j] - p[i]) * d[i] / (d[i] - d[j]));
  }
  return {*std::min_element(t.begin(), t.end()), *std::max_element(t.begin(), t.end())};
}

bool same_side(const std::array<double, 3>& d) {
  return (d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0);
}

}  // namespace

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const std::array<Vec3, 3> a{a0, a1, a2}, b{b0, b1, b2};
  const Vec3 nb = (b1 - b0).cross(b2 - b0), na = (a1 - a0).cross(a2 - a0);
  std::array<double, 3> da, db;
  for (int i = 0; i < 3; ++i) da[i] = nb.dot(a[i] - b0), db[i] = na.dot(b[i] - a0);
  // Coplanar to rounding (each vertex within 1e-10 of its triangle's size from the other's plane,
  // as where a flat surface is split into neighbouring pieces): the intersection line below would
  // be rounding noise, so decide in the plane.
  auto longest_edge = [](const std::array<Vec3, 3>& t) {
    return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
  };
  auto flat = [](const std::array<double, 3>& d, double scale) {
    return std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}) <= 1e-10 * scale;
  };
  if (flat(da, nb.norm() * longest_edge(a)) && flat(db, na.norm() * longest_edge(b))) return coplanar_intersect(nb, a, b);
  if (same_side(da) || same_side(db)) return false;
  // Both triangles straddle (or touch) the other's plane: compare their intervals on the line.
  const Vec3 direction = na.cross(nb);
  int axis = 0;
  direction.cwiseAbs().maxCoeff(&axis);
  std::array<double, 3> pa, pb;
  for (int i = 0; i < 3; ++i) pa[i] = a[i][axis], pb[i] = b[i][axis];
  const auto [a_lo, a_hi] = interval(pa, da);
  const auto [b_lo, b_hi] = interval(pb, db);
  return a_lo <= b_hi && b_lo <= a_hi;
}

std::vector<std::pair<int, int>> self_intersections(const Mesh& mesh, int max_pairs, int threads) {
  const int n = static_cast<int>(mesh.triangles.size());
  std::vector<std::pair<int, int>> found;
  if (n < 2) return found;
  std::vector<Vec3> lo(n), hi(n);
  double edge_sum = 0.0;
  for (int t = 0; t < n; ++t) {
    const Vec3i& f = mesh.triangles[t];
    lo[t] = mesh.positions[f[0]].cwiseMin(mesh.positions[f[1]]).cwiseMin(mesh.positions[f[2]]);
    hi[t] = mesh.positions[f[0]].cwiseMax(mesh.positions[f[1]]).cwiseMax(mesh.positions[f[2]]);
    edge_sum += (hi[t] - lo[t]).maxCoeff();
  }
  const double cell = std::max(1e-12, 2.0 * edge_sum / n);
  auto cell_index = [cell](double x) { return static_cast<long long>(std::floor(x / cell)); };
  // Every (cell, triangle) a triangle's box covers, sorted: each cell's triangles form one run,
  // ascending, and the runs come in the cells' order.
  struct Entry {
    std::array<long long, 3> cell;
    int triangle;
    bool operator<(const Entry& o) const { return cell != o.cell ? cell < o.cell : triangle < o.triangle; }
  };
  std::vector<Entry> entries;
  for (int t = 0; t < n; ++t)
    for (long long i = cell_index(lo[t].x()); i <= cell_index(hi[t].x()); ++i)
      for (long long j = cell_index(lo[t].y()); j <= cell_index(hi[t].y()); ++j)
        for (long long k = cell_index(lo[t].z()); k <= cell_index(hi[t].z()); ++k) entries.push_back({{i, j, k}, t});
  std::sort(entries.begin(), entries.end());
  std::vector<std::size_t> runs{0};
  for (std::size_t e = 1; e <= entries.size(); ++e)
    if (e == entries.size() || entries[e].cell != entries[e - 1].cell) runs.push_back(e);
  // The cells in chunks side by side, each keeping its first max_pairs in cell order; joined in
  // chunk order, the first max_pairs are the ones one pass in cell order would find.
  const int cells = static_cast<int>(runs.size()) - 1;
  constexpr int kChunk = 4096;
  const int chunks = (cells + kChunk - 1) / kChunk;
  std::vector<std::vector<std::pair<int, int>>> found_in(chunks);
  parallel_for(chunks, resolve_thread_count(threads), [&](int chunk) {
    std::vector<std::pair<int, int>>& out = found_in[chunk];
    for (int c = chunk * kChunk; c < std::min(cells, (chunk + 1) * kChunk); ++c) {
      const std::array<long long, 3>& key = entries[runs[c]].cell;
      for (std::size_t x = runs[c]; x < runs[c + 1]; ++x)
        for (std::size_t y = x + 1; y < runs[c + 1]; ++y) {
          const int s = entries[x].triangle, t = entries[y].triangle;
          const Vec3 overlap_lo = lo[s].cwiseMax(lo[t]), overlap_hi = hi[s].cwiseMin(hi[t]);
          if ((overlap_lo.array() > overlap_hi.array()).any()) continue;
          if (cell_index(overlap_lo.x()) != key[0] || cell_index(overlap_lo.y()) != key[1] ||
              cell_index(overlap_lo.z()) != key[2])
            continue;  // tested in another cell
          const Vec3i& f = mesh.triangles[s];
          const Vec3i& g = mesh.triangles[t];
          bool shared = false;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) shared |= f[i] == g[j];
          if (shared) continue;
          const auto& p = mesh.positions;
          if (triangles_intersect(p[f[0]], p[f[1]], p[f[2]], p[g[0]], p[g[1]], p[g[2]])) {
            out.emplace_back(s, t);
            if (static_cast<int>(out.size()) >= max_pairs) return;
          }
        }
    }
  });
  for (const auto& chunk : found_in)
    for (const auto& pair : chunk)
      if (static_cast<int>(found.size()) < max_pairs) found.push_back(pair);
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<double> mean_curvature(const Mesh& mesh) {
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<Vec3> laplace(n, Vec3::Zero());
  std::vector<double> area(n, 0.0);
  for (const Vec3i& f : mesh.triangles) {
    const double a = 0.5 * (mesh.positions[f[1]] - mesh.positions[f[0]]).cross(mesh.positions[f[2]] - mesh.positions[f[0]]).norm();
    for (int k = 0; k < 3; ++k) {
      const int i = f[k], j = f[(k + 1) % 3], o = f[(k + 2) % 3];
      area[i] += a / 3.0;
      // The angle at o faces edge (i, j).
      const Vec3 u = mesh.positions[i] - mesh.positions[o], v = mesh.positions[j] - mesh.positions[o];
      const double cot = u.dot(v) / std::max(1e-300, u.cross(v).norm());
      laplace[i] += cot * (mesh.positions[i] - mesh.positions[j]);
      laplace[j] += cot * (mesh.positions[j] - mesh.positions[i]);
    }
  }
  std::vector<double> h(n, 0.0);
  std::vector<char> boundary(n, 0);
  for (const auto& loop : analyse_topology(mesh).boundary_loops)
    for (int v : loop) boundary[v] = 1;
  for (int i = 0; i < n; ++i)
    if (!boundary[i] && area[i] > 0.0) h[i] = laplace[i].norm() / (4.0 * area[i]);
  return h;
}

std::vector<int> inward_triangles(const Mesh& mesh, const Vec3& centre) {
  std::vector<int> wrong;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Vec3i& f = mesh.triangles[t];
    const Vec3 a = mesh.positions[f[0]] - centre, b = mesh.positions[f[1]] - centre, c = mesh.positions[f[2]] - centre;
    if (a.dot(b.cross(c)) <= 0.0) wrong.push_back(t);
  }
  return wrong;
}

std::vector<int> facing_out_of(const Mesh& sheet, const FastWindingNumber& solid, int threads) {
  const int faces = static_cast<int>(sheet.triangles.size());
  std::vector<char> out(faces, 0);
  parallel_for(faces, threads, [&](int t) {
    const Vec3i& f = sheet.triangles[t];
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, (sheet.positions[f[(k + 1) % 3]] - sheet.positions[f[k]]).norm());
    const double altitude = longest > 0.0 ? 2.0 * triangle_area(sheet, t) / longest : 0.0;
    const double step = std::min(kFacingStep, 0.1 * altitude);
    out[t] = !(step > 0.0) || !winding_above_half(solid, triangle_centroid(sheet, t) + step * triangle_normal(sheet, t));
  });
  std::vector<int> listed;
  for (int t = 0; t < faces; ++t)
    if (out[t]) listed.push_back(t);
  return listed;
}

}  // namespace hairfit
