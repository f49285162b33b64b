// Procedural scalp-like meshes for the scalp tests and bench/scalp.cpp: concentric-ring disk
// triangulations (ring k has 6k vertices, 6K² triangles in all) embedded as a flat disk or as
// the upper part of a head-like ellipsoid, optionally bumpy. Up is +y, the front is +z.
#pragma once
#include <cmath>
#include <functional>

#include "core/mesh.h"
#include "core/random.h"

namespace hairfit::test {

// Ring-disk triangulation with K rings; embed(r, φ) gives the position of the point at parameter
// radius r ∈ [0, 1] and angle φ. The triangles are turned so that their normals have a positive
// component along outward(p) at the first triangle (the embeddings here are orientation-consistent).
inline Mesh ring_disk(int rings, const std::function<Vec3(double, double)>& embed,
                      const std::function<Vec3(const Vec3&)>& outward) {
  Mesh m;
  m.positions.push_back(embed(0.0, 0.0));
  std::vector<int> inner{0};
  for (int k = 1; k <= rings; ++k) {
    const int no = 6 * k;
    std::vector<int> outer;
    for (int j = 0; j < no; ++j) {
      outer.push_back(static_cast<int>(m.positions.size()));
      m.positions.push_back(embed(static_cast<double>(k) / rings, 2 * M_PI * j / no));
    }
    const int ni = static_cast<int>(inner.size());
    if (ni == 1) {
      for (int j = 0; j < no; ++j) m.triangles.emplace_back(inner[0], outer[j], outer[(j + 1) % no]);
    } else {
      int i = 0, j = 0;
      while (i < ni || j < no) {
        const bool advance_outer = j < no && (i == ni || static_cast<double>(j + 1) / no <= static_cast<double>(i + 1) / ni);
        if (advance_outer) {
          m.triangles.emplace_back(inner[i % ni], outer[j], outer[(j + 1) % no]);
          ++j;
        } else {
          m.triangles.emplace_back(inner[i % ni], outer[j % no], inner[(i + 1) % ni]);
          ++i;
        }
      }
    }
    inner = outer;
  }
  const Vec3i& f = m.triangles.front();
  const Vec3 n = (m.positions[f[1]] - m.positions[f[0]]).cross(m.positions[f[2]] - m.positions[f[0]]);
  if (n.dot(outward(m.positions[f[0]])) < 0)
    for (Vec3i& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// A flat disk of radius R in the plane y = 0, normals up (+y). Interior vertices are moved by up
// to `jitter` × ring spacing within the plane (deterministically), the hairline stays a regular
// 6K-gon on the circle of radius R.
inline Mesh flat_disk(int rings, double radius, double jitter = 0.0, std::uint64_t seed = 1) {
  int index = 0;
  return ring_disk(
      rings,
      [&](double r, double phi) {
        Vec3 p(radius * r * std::cos(phi), 0.0, radius * r * std::sin(phi));
        Random rng(seed, RandomStage::test, static_cast<std::uint64_t>(index++));
        if (r < 1.0 && jitter > 0) {
          const double h = jitter * radius / rings;
          p += Vec3(rng.uniform(-h, h), 0.0, rng.uniform(-h, h));
        }
        return p;
      },
      [](const Vec3&) { return Vec3(0, 1, 0); });
}

// The upper part of the ellipsoid x²/a² + y²/b² + z²/c² = 1 (a: half-width, b: height above the
// centre, c: half-depth, cm) down to the polar angle theta_max from +y; with bumps, the radius is
// scaled by 1 + bump·sin(7φ)·sin(9θ).
inline Mesh head_cap(int rings, double theta_max = 1.75, double bump = 0.0, double a = 7.6, double b = 10.0,
                     double c = 9.6) {
  return ring_disk(
      rings,
      [&](double r, double phi) {
        const double theta = r * theta_max;
        const double s = 1.0 + bump * std::sin(7 * phi) * std::sin(9 * theta);
        return Vec3(s * a * std::sin(theta) * std::cos(phi), s * b * std::cos(theta), s * c * std::sin(theta) * std::sin(phi));
      },
      [](const Vec3& p) { return p; });
}

}  // namespace hairfit::test
