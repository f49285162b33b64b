#include "core/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace hairfit {

Mesh icosphere(int levels, double radius, const Vec3& centre) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : m.positions) p.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      return midpoint[key] = static_cast<int>(m.positions.size()) - 1;
    };
    std::vector<Vec3i> next;
    for (const Vec3i& f : m.triangles) {
      const int a = middle(f[0], f[1]), b = middle(f[1], f[2]), c = middle(f[2], f[0]);
      next.insert(next.end(), {Vec3i(f[0], a, c), Vec3i(f[1], b, a), Vec3i(f[2], c, b), Vec3i(a, b, c)});
    }
    m.triangles = std::move(next);
  }
  for (Vec3& p : m.positions) p = centre + radius * p;
  return m;
}

Mesh uv_sphere(const Vec3& centre, double radius, int rings, int sectors) {
  Mesh mesh;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / sectors;
      mesh.positions.push_back(centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                      std::sin(theta) * std::sin(phi)));
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const int a = i * sectors + j, b = i * sectors + (j + 1) % sectors;
      mesh.triangles.emplace_back(a, a + sectors, b);
      mesh.triangles.emplace_back(b, a + sectors, b + sectors);
    }
  return mesh;
}

Mesh spherical_cap(double theta0, int rings, int sectors, double radius) {
  Mesh m;
  m.positions.push_back(Vec3(0, 0, 1));
  for (int i = 1; i <= rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double theta = theta0 * i / rings, phi = 2 * M_PI * j / sectors;
      m.positions.push_back(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  const auto at = [&](int i, int j) { return 1 + (i - 1) * sectors + j % sectors; };
  for (int j = 0; j < sectors; ++j) m.triangles.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (Vec3& p : m.positions) p *= radius;
  return m;
}

}  // namespace hairfit
