#include "prepare/level_set_clip.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace hairfit {

namespace {

int sign_of(double f) { return f > 0.0 ? 1 : f < 0.0 ? -1 : 0; }

double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    return std::atan2((q - p).cross(r - p).norm(), (q - p).dot(r - p));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// Where f changes sign on the scan edge a–b (a < b, f[a], f[b] of opposite signs): the share t of
// the way from a, and the point. Geometric selections are bisected on the edge to rounding (a
// plane's f is linear there, a cap's is not); a mask's f is linear along the edge by definition.
struct Crossing {
  double t = 0.0;
  Vec3 point = Vec3::Zero();
};

Crossing find_crossing(const Vec3& pa, const Vec3& pb, double fa, double fb, const SelectionField& field) {
  Crossing c;
  if (!field.at) {
    c.t = fa / (fa - fb);
    c.point = pa + c.t * (pb - pa);
    return c;
  }
  const int sa = sign_of(fa);
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const double f = field.at(pa + mid * (pb - pa));
    if (f == 0.0) {
      lo = hi = mid;
      break;
    }
    (sign_of(f) == sa ? lo : hi) = mid;
  }
  // Of the two ends of the final bracket, the one nearer the level set.
  const Vec3 p_lo = pa + lo * (pb - pa), p_hi = pa + hi * (pb - pa);
  const bool take_lo = std::abs(field.at(p_lo)) <= std::abs(field.at(p_hi));
  c.t = take_lo ? lo : hi;
  c.point = take_lo ? p_lo : p_hi;
  return c;
}

}  // namespace

Clipped clip_at_level_set(const Mesh& scan, const SelectionField& field, const ClipOptions& options) {
  const int n = static_cast<int>(scan.positions.size());
  std::vector<double> f = field.values;
  std::vector<Vec3> position = scan.positions;
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(scan);
  // Crossings on the scan's own edges (both ends unmoved), computed once per edge from its lower end.
  std::unordered_map<long long, Crossing> crossings;
  auto crossing = [&](int a, int b) -> const Crossing& {
    if (a > b) std::swap(a, b);
    const auto found = crossings.find(edge_key(a, b));
    if (found != crossings.end()) return found->second;
    return crossings[edge_key(a, b)] = find_crossing(scan.positions[a], scan.positions[b], f[a], f[b], field);
  };
  auto mixed = [&](int a, int b) { return sign_of(f[a]) * sign_of(f[b]) < 0; };

  Clipped out;
  // Snap, in vertex order: a vertex with a crossing within options.snap of it along an edge moves
  // onto the nearest such crossing. Its edges then carry no crossing, so no later crossing moves.
  for (int v = 0; v < n; ++v) {
    if (f[v] == 0.0) continue;
    double nearest = options.snap;
    int onto = -1;
    for (int u : neighbours[v]) {
      if (!mixed(v, u)) continue;
      const double t = v < u ? crossing(v, u).t : 1.0 - crossing(v, u).t;
      if (t < nearest) nearest = t, onto = u;
    }
    if (onto < 0) continue;
    position[v] = crossing(v, onto).point;
    f[v] = 0.0;
    ++out.snapped_vertices;
  }

  std::vector<int> local(n, -1);
  std::unordered_map<long long, int> cut_point;
  auto vertex = [&](int v) {
    if (local[v] < 0) {
      local[v] = static_cast<int>(out.mesh.positions.size());
      out.mesh.positions.push_back(position[v]);
      out.scan_vertex.push_back(position[v] == scan.positions[v] ? v : -1);
    }
    return local[v];
  };
  auto edge_point = [&](int a, int b) {
    const auto [at, fresh] = cut_point.emplace(edge_key(a, b), static_cast<int>(out.mesh.positions.size()));
    if (fresh) {
      out.mesh.positions.push_back(crossing(a, b).point);
      out.scan_vertex.push_back(-1);
    }
    return at->second;
  };
  auto emit = [&](int a, int b, int c, int from) {
    out.mesh.triangles.emplace_back(a, b, c);
    out.scan_triangle.push_back(from);
  };

  for (int t = 0; t < static_cast<int>(scan.triangles.size()); ++t) {
    const Vec3i& tri = scan.triangles[t];
    int positive = 0, negative = 0;
    for (int k = 0; k < 3; ++k) positive += f[tri[k]] > 0.0, negative += f[tri[k]] < 0.0;
    if (positive == 0 && negative == 0) {
      // Three corners on the level set (snapped): kept when the selection held most of it.
      if (field.values[tri[0]] + field.values[tri[1]] + field.values[tri[2]] >= 0.0)
        emit(vertex(tri[0]), vertex(tri[1]), vertex(tri[2]), t);
      continue;
    }
    if (positive == 0) continue;
    if (negative == 0) {
      emit(vertex(tri[0]), vertex(tri[1]), vertex(tri[2]), t);
      continue;
    }
    // The kept polygon, in the triangle's order: its corners with f ≥ 0 and the crossings.
    std::vector<int> polygon;
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      if (f[a] >= 0.0) polygon.push_back(vertex(a));
      if (mixed(a, b)) polygon.push_back(edge_point(a, b));
    }
    ++out.cut_triangles;
    if (polygon.size() == 3) {
      emit(polygon[0], polygon[1], polygon[2], t);
      continue;
    }
    // A quadrilateral: the diagonal that keeps the smaller angle larger.
    const auto& p = out.mesh.positions;
    const double via02 = std::min(smallest_angle(p[polygon[0]], p[polygon[1]], p[polygon[2]]),
                                  smallest_angle(p[polygon[0]], p[polygon[2]], p[polygon[3]]));
    const double via13 = std::min(smallest_angle(p[polygon[1]], p[polygon[2]], p[polygon[3]]),
                                  smallest_angle(p[polygon[1]], p[polygon[3]], p[polygon[0]]));
    if (via02 >= via13) {
      emit(polygon[0], polygon[1], polygon[2], t);
      emit(polygon[0], polygon[2], polygon[3], t);
    } else {
      emit(polygon[1], polygon[2], polygon[3], t);
      emit(polygon[1], polygon[3], polygon[0], t);
    }
  }
  return out;
}

}  // namespace hairfit
