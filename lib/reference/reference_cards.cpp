#include "reference/reference_cards.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "core/triangle_closest.h"
#include "strands/coverage.h"

namespace hairfit {

namespace {

// What one card triangle carries into the island analysis.
struct CardTriangle {
  bool valid = false;
  double area = 0.0;
  Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();
  Vec3 gradient[2] = {Vec3::Zero(), Vec3::Zero()};  // of u and of v, in the triangle's plane (1/cm)
  double coordinate[2] = {0.0, 0.0};                // u and v at the centroid
};

CardTriangle card_triangle(const TexturedMesh& cards, int t) {
  CardTriangle c;
  const Vec3i& tri = cards.mesh.triangles[t];
  const Vec3i& tex = cards.triangle_texture[t];
  if (tex.minCoeff() < 0) return c;
  const Vec3 &p0 = cards.mesh.positions[tri[0]], &p1 = cards.mesh.positions[tri[1]], &p2 = cards.mesh.positions[tri[2]];
  const Vec2 &t0 = cards.texture_coordinates[tex[0]], &t1 = cards.texture_coordinates[tex[1]],
             &t2 = cards.texture_coordinates[tex[2]];
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, cross = e1.cross(e2);
  const Vec2 f1 = t1 - t0, f2 = t2 - t0;
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2), det = g11 * g22 - g12 * g12;
  if (!(cross.norm() > 0.0) || !(det > 0.0) || f1.x() * f2.y() - f1.y() * f2.x() == 0.0) return c;
  c.valid = true;
  c.area = 0.5 * cross.norm();
  c.normal = cross.normalized();
  c.centroid = (p0 + p1 + p2) / 3.0;
  for (int axis = 0; axis < 2; ++axis) {
    // ∇f = a·e1 + b·e2 with ∇f·e1 = Δf1 and ∇f·e2 = Δf2 (the Gram system of the two edges).
    const double q1 = f1[axis], q2 = f2[axis];
    c.gradient[axis] = ((q1 * g22 - q2 * g12) / det) * e1 + ((q2 * g11 - q1 * g12) / det) * e2;
    c.coordinate[axis] = (t0[axis] + t1[axis] + t2[axis]) / 3.0;
  }
  return c;
}

int find_root(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Islands: valid triangles joined across every edge whose two corners have equal texture
// coordinates on both sides. Numbered in the order of their first triangle; −1 for invalid ones.
std::vector<int> uv_islands(const TexturedMesh& cards, const std::vector<CardTriangle>& info, int& count) {
  const int n = static_cast<int>(info.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  struct Side {
    int triangle;
    Vec2 at_low, at_high;  // texture coordinates at the edge's lower and higher vertex index
  };
  std::map<long long, std::vector<Side>> edges;
  for (int t = 0; t < n; ++t) {
    if (!info[t].valid) continue;
    const Vec3i& tri = cards.mesh.triangles[t];
    const Vec3i& tex = cards.triangle_texture[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      const Vec2 &ta = cards.texture_coordinates[tex[k]], &tb = cards.texture_coordinates[tex[(k + 1) % 3]];
      edges[edge_key(a, b)].push_back(a < b ? Side{t, ta, tb} : Side{t, tb, ta});
    }
  }
  for (const auto& [key, sides] : edges)
    for (std::size_t i = 0; i < sides.size(); ++i)
      for (std::size_t j = i + 1; j < sides.size(); ++j)
        if (sides[i].at_low == sides[j].at_low && sides[i].at_high == sides[j].at_high) {
          const int a = find_root(parent, sides[i].triangle), b = find_root(parent, sides[j].triangle);
          if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
  std::vector<int> island(n, -1), number(n, -1);
  count = 0;
  for (int t = 0; t < n; ++t) {
    if (!info[t].valid) continue;
    const int r = find_root(parent, t);
    if (number[r] < 0) number[r] = count++;
    island[t] = number[r];
  }
  return island;
}

double distance_to_mesh(const Vec3& p, const Mesh& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3i& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const Vec3 w = closest_barycentric(p, a, b, c);
    best = std::min(best, (w[0] * a + w[1] * b + w[2] * c - p).norm());
  }
  return best;
}

// An island's two ends along one texture axis: the triangles whose coordinate lies at or below
// the end_share quantile of the island's area, and those at or above the 1 − end_share one. Ties
// go in whole, so an axis that is constant along a strip (its across coordinate) has ends that
// span the strip's length side by side, not its two extremities.
struct Ends {
  std::vector<int> low, high;
  double separation = 0.0;  // cm, between the ends' area-weighted centroids
};

Ends island_ends(const std::vector<int>& triangles, const std::vector<CardTriangle>& info, int axis, double end_share) {
  std::vector<int> order = triangles;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return info[a].coordinate[axis] < info[b].coordinate[axis]; });
  double total = 0.0;
  for (int t : order) total += info[t].area;
  auto quantile = [&](auto begin, auto end) {  // the coordinate where the area from `begin` reaches the share
    double area = 0.0;
    for (auto it = begin; it != end; ++it)
      if ((area += info[*it].area) >= end_share * total) return info[*it].coordinate[axis];
    return info[*(end - 1)].coordinate[axis];
  };
  const double low_at = quantile(order.begin(), order.end()), high_at = quantile(order.rbegin(), order.rend());
  Ends ends;
  Vec3 low = Vec3::Zero(), high = Vec3::Zero();
  double low_area = 0.0, high_area = 0.0;
  for (int t : order) {
    if (info[t].coordinate[axis] <= low_at) {
      ends.low.push_back(t);
      low += info[t].area * info[t].centroid, low_area += info[t].area;
    }
    if (info[t].coordinate[axis] >= high_at) {
      ends.high.push_back(t);
      high += info[t].area * info[t].centroid, high_area += info[t].area;
    }
  }
  ends.separation = (high / high_area - low / low_area).norm();
  return ends;
}

double mean_scalp_distance(const std::vector<int>& triangles, const std::vector<CardTriangle>& info, const Mesh& scalp) {
  double sum = 0.0, area = 0.0;
  for (int t : triangles) sum += info[t].area * distance_to_mesh(info[t].centroid, scalp), area += info[t].area;
  return sum / area;
}

}  // namespace

ReferenceHair reference_from_cards(const TexturedMesh& cards, const Mesh& scalp, const CardOptions& o) {
  if (cards.triangle_texture.size() != cards.mesh.triangles.size())
    throw std::invalid_argument("reference_from_cards: texture corners must pair with the triangles");
  if (!(o.end_share > 0.0 && o.end_share < 0.5) || !(o.samples_per_cm2 > 0.0) || !(o.sense_tolerance >= 0.0))
    throw std::invalid_argument("reference_from_cards: needs end_share in (0, ½), samples_per_cm2 > 0, sense_tolerance ≥ 0");
  if (scalp.triangles.empty()) throw std::invalid_argument("reference_from_cards: the scalp has no triangles");
  const int n = static_cast<int>(cards.mesh.triangles.size());
  std::vector<CardTriangle> info(n);
  for (int t = 0; t < n; ++t) info[t] = card_triangle(cards, t);

  ReferenceHair hair;
  int count = 0;
  hair.triangle_island = uv_islands(cards, info, count);
  hair.triangle_directions.assign(n, Vec3::Zero());
  std::vector<std::vector<int>> members(count);
  for (int t = 0; t < n; ++t) {
    hair.total_area += triangle_area(cards.mesh, t);
    if (hair.triangle_island[t] >= 0) members[hair.triangle_island[t]].push_back(t);
  }

  hair.islands.resize(count);
  for (int i = 0; i < count; ++i) {
    CardIsland& island = hair.islands[i];
    island.triangles = static_cast<int>(members[i].size());
    for (int t : members[i]) island.area += info[t].area;
    const Ends u = island_ends(members[i], info, 0, o.end_share), v = island_ends(members[i], info, 1, o.end_share);
    island.along = u.separation > v.separation ? 0 : 1;
    const Ends& ends = island.along == 0 ? u : v;
    island.end_separation = ends.separation;
    island.across_separation = (island.along == 0 ? v : u).separation;
    island.used = island.triangles >= o.min_island_triangles;
    if (!island.used) continue;
    const double low = mean_scalp_distance(ends.low, info, scalp), high = mean_scalp_distance(ends.high, info, scalp);
    island.sense_from_scalp = std::abs(high - low) >= o.sense_tolerance;
    island.root_at_high = island.sense_from_scalp ? high < low : true;
    island.root_scalp_distance = island.root_at_high ? high : low;
    island.tip_scalp_distance = island.root_at_high ? low : high;
    hair.used_area += island.area;
    if (island.sense_from_scalp) hair.sensed_area += island.area;
    for (int t : members[i]) {
      // Root to tip is where the along coordinate falls (root at its high end) or rises.
      const Vec3 toward_tip = island.root_at_high ? -info[t].gradient[island.along] : info[t].gradient[island.along];
      Vec3 d = info[t].normal.cross(info[t].gradient[1 - island.along]);
      if (d.dot(toward_tip) < 0.0) d = -d;
      hair.triangle_directions[t] = d.normalized();
    }
  }

  // Reference points: area samples over the used triangles.
  Mesh used;
  used.positions = cards.mesh.positions;
  std::vector<int> original;
  for (int t = 0; t < n; ++t)
    if (hair.triangle_island[t] >= 0 && hair.islands[hair.triangle_island[t]].used) {
      used.triangles.push_back(cards.mesh.triangles[t]);
      original.push_back(t);
    }
  const int samples = static_cast<int>(std::lround(o.samples_per_cm2 * hair.used_area));
  for (const AreaSample& s : area_samples_on_triangles(used, samples)) {
    hair.samples.points.push_back(s.point);
    hair.samples.directions.push_back(hair.triangle_directions[original[s.triangle]]);
  }
  return hair;
}

}  // namespace hairfit
