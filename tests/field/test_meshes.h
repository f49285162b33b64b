// Small procedural meshes for the distance-field tests, their specs, and an independent brute-force
// distance.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "core/mesh.h"
#include "core/shapes.h"
#include "field/distance_field.h"

namespace hairfit::test {

using hairfit::icosphere;

// A field spec with everything but the grid at its defaults.
inline FieldSpec spec_for(double voxel, double band, double margin) {
  FieldSpec s;
  s.voxel = voxel;
  s.band = band;
  s.margin = margin;
  return s;
}

// Axis-aligned cube [-s, s]³, outward counter-clockwise, two triangles per side.
inline Mesh cube(double s) {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back(Vec3(i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s));
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// The triangles of a sphere whose centroid lies above z = height·radius: an open cap.
inline Mesh open_cap(int level, double radius, double height) {
  Mesh s = icosphere(level, radius);
  Mesh m{s.positions, {}};
  for (const Vec3i& f : s.triangles)
    if ((s.positions[f[0]] + s.positions[f[1]] + s.positions[f[2]]).z() / 3 > height * radius) m.triangles.push_back(f);
  return m;
}

// A raw scan: a sphere with a hole, duplicated vertices, zero-area triangles and a flipped patch.
inline Mesh messy_sphere(int level, double radius) {
  Mesh m = icosphere(level, radius);
  std::vector<Vec3i> kept;
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const Vec3i f = m.triangles[i];
    const Vec3 c = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) / 3;
    if (c.x() > 0.8 * radius) continue;  // hole
    Vec3i g = f;
    if (c.y() > 0.75 * radius) std::swap(g[1], g[2]);  // flipped patch
    if (c.z() < -0.6 * radius) {                        // duplicated vertices on this patch
      for (int k = 0; k < 3; ++k) {
        m.positions.push_back(m.positions[g[k]]);
        g[k] = int(m.positions.size()) - 1;
      }
    }
    kept.push_back(g);
  }
  // Zero-area triangles: a repeated index, and collinear points on an existing edge.
  const Vec3i e = kept[5];
  kept.push_back({e[0], e[0], e[1]});
  m.positions.push_back(0.5 * (m.positions[e[0]] + m.positions[e[1]]));
  kept.push_back({e[0], int(m.positions.size()) - 1, e[1]});
  m.triangles = kept;
  return m;
}

// Distance from p to triangle abc by minimising over the candidate closest points: the
// unconstrained minimiser of the plane (Gram system, when inside), each edge's clamped
// projection, and the vertices. Independent of the field's prism/wedge/cone formulation.
inline double brute_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  double best = std::min({(p - a).norm(), (p - b).norm(), (p - c).norm()});
  const Vec3 pts[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3& s = pts[k];
    const Vec3 d = pts[(k + 1) % 3] - s;
    const double len2 = d.squaredNorm();
    if (len2 == 0) continue;
    const double t = std::clamp((p - s).dot(d) / len2, 0.0, 1.0);
    best = std::min(best, (p - (s + t * d)).norm());
  }
  const Vec3 u = b - a, v = c - a, w = p - a;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), wu = w.dot(u), wv = w.dot(v);
  const double det = uu * vv - uv * uv;
  if (det > 1e-14 * uu * vv) {
    const double s = (wu * vv - wv * uv) / det, t = (wv * uu - wu * uv) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) best = std::min(best, (p - (a + s * u + t * v)).norm());
  }
  return best;
}

inline double brute_distance(const Mesh& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3i& f : m.triangles)
    best = std::min(best, brute_triangle_distance(p, m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]));
  return best;
}

}  // namespace hairfit::test
