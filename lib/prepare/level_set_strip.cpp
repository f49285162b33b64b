#include "prepare/level_set_strip.h"

#include <algorithm>
#include <array>

#include "prepare/surface_checks.h"

namespace hairfit {

namespace {

constexpr int kMaxCrossings = 1 << 16;  // strip triangles against the hull, more than a strip can cross

}  // namespace

void zip_strip(LevelSetSheet& s, const std::vector<double>& depth, const std::vector<Vec3>& inward) {
  const int na = static_cast<int>(s.inner.size()), nb = static_cast<int>(s.outer.size());
  s.mesh.triangles.resize(s.strip_begin);
  s.mesh.positions.resize(s.piece_vertices + nb);
  s.thickness.resize(s.piece_vertices + nb);
  s.feet = s.outer;
  for (int j = 0; j < nb; ++j) {
    if (!(depth[j] > 0.0)) continue;
    s.feet[j] = static_cast<int>(s.mesh.positions.size());
    s.mesh.positions.push_back(s.mesh.positions[s.outer[j]] + depth[j] * inward[j]);
    s.thickness.push_back(depth[j]);
  }
  auto add = [&](int a, int b, int c) {
    if (a != b && b != c && c != a) s.mesh.triangles.emplace_back(a, b, c);
  };
  // The band: each outer edge and its feet, as the zipper below orients an outer edge over the
  // piece and a piece edge under the outer loop.
  for (int j = 0; j < nb; ++j) {
    const int k = (j + 1) % nb;
    add(s.outer[j], s.outer[k], s.feet[j]);
    add(s.feet[k], s.feet[j], s.outer[k]);
  }
  const std::vector<int>& a = s.inner;
  const std::vector<double>&sa = s.inner_at, &sb = s.outer_at;
  int i = 0, j = 0;
  while (i < na || j < nb) {
    const bool advance_a = j == nb || (i < na && sa[i + 1] <= sb[j + 1]);
    if (advance_a) {
      add(a[(i + 1) % na], a[i % na], s.feet[j % nb]);
      ++i;
    } else {
      add(s.feet[j % nb], s.feet[(j + 1) % nb], a[i % na]);
      ++j;
    }
  }
}

std::vector<int> strip_crossings(const LevelSetSheet& s, const Mesh& hull, const std::vector<int>& hairline, int threads) {
  const int hull_vertices = static_cast<int>(hull.positions.size());
  std::vector<int> loop_index(s.mesh.positions.size(), -1), vertex(s.mesh.positions.size());
  for (std::size_t v = 0; v < vertex.size(); ++v) vertex[v] = hull_vertices + static_cast<int>(v);
  for (std::size_t j = 0; j < s.outer.size(); ++j) {
    vertex[s.outer[j]] = hairline[j];
    loop_index[s.outer[j]] = loop_index[s.feet[j]] = static_cast<int>(j);
  }
  Mesh both;
  both.positions = hull.positions;
  both.positions.insert(both.positions.end(), s.mesh.positions.begin(), s.mesh.positions.end());
  // Only the hull triangles whose box meets a strip triangle's box (in cells as wide as the
  // strip's longest edge) can cross it.
  double cell = 0.0;
  for (std::size_t t = s.strip_begin; t < s.mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      cell = std::max(cell, (s.mesh.positions[s.mesh.triangles[t][k]] - s.mesh.positions[s.mesh.triangles[t][(k + 1) % 3]]).norm());
  cell = std::max(cell, 1e-9);
  auto box = [&](const Mesh& m, const Vec3i& f) {
    const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    return std::pair<Vec3, Vec3>((a.cwiseMin(b).cwiseMin(c) / cell).array().floor(), (a.cwiseMax(b).cwiseMax(c) / cell).array().floor());
  };
  std::vector<std::array<long long, 3>> strip_cells;
  for (std::size_t t = s.strip_begin; t < s.mesh.triangles.size(); ++t) {
    const auto [lo, hi] = box(s.mesh, s.mesh.triangles[t]);
    for (double x = lo.x(); x <= hi.x(); ++x)
      for (double y = lo.y(); y <= hi.y(); ++y)
        for (double z = lo.z(); z <= hi.z(); ++z) strip_cells.push_back({(long long)x, (long long)y, (long long)z});
  }
  std::sort(strip_cells.begin(), strip_cells.end());
  for (const Vec3i& f : hull.triangles) {
    const auto [lo, hi] = box(hull, f);
    bool meets = false;
    for (double x = lo.x(); x <= hi.x() && !meets; ++x)
      for (double y = lo.y(); y <= hi.y() && !meets; ++y)
        for (double z = lo.z(); z <= hi.z() && !meets; ++z)
          meets = std::binary_search(strip_cells.begin(), strip_cells.end(), std::array<long long, 3>{(long long)x, (long long)y, (long long)z});
    if (meets) both.triangles.push_back(f);
  }
  const int hull_triangles = static_cast<int>(both.triangles.size());
  for (std::size_t t = s.strip_begin; t < s.mesh.triangles.size(); ++t) {
    const Vec3i& f = s.mesh.triangles[t];
    both.triangles.emplace_back(vertex[f[0]], vertex[f[1]], vertex[f[2]]);
  }
  std::vector<int> crossing;
  for (const auto& [a, b] : self_intersections(both, kMaxCrossings, threads)) {
    if (a >= hull_triangles || b < hull_triangles) continue;  // hull with strip only
    const Vec3i& f = s.mesh.triangles[s.strip_begin + (b - hull_triangles)];
    for (int k = 0; k < 3; ++k)
      if (loop_index[f[k]] >= 0) crossing.push_back(loop_index[f[k]]);
  }
  std::sort(crossing.begin(), crossing.end());
  crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
  return crossing;
}

int lower_strip(LevelSetSheet& s, const Mesh& hull, const std::vector<int>& hairline, const DistanceField& field, double epsilon,
                int threads) {
  const int n = static_cast<int>(s.outer.size());
  std::vector<int> crossing = strip_crossings(s, hull, hairline, threads);
  if (crossing.empty()) return 0;
  std::vector<Vec3> inward(n);
  for (int j = 0; j < n; ++j) {
    const Vec3 g = field.smooth(s.mesh.positions[s.outer[j]]).gradient;
    inward[j] = g.squaredNorm() > 0.0 ? Vec3(-g.normalized()) : Vec3::Zero();
  }
  std::vector<char> marked(n, 0);
  std::vector<double> depth(n, 0.0);
  for (int round = 1; round <= kFootRounds && !crossing.empty(); ++round) {
    for (int j : crossing) marked[j] = 1;
    // Each hairline vertex's distance (in vertices, around the loop) from the nearest marked one.
    std::vector<int> away(n, n);
    for (int pass = 0; pass < 2; ++pass)
      for (int step = 0; step < 2 * n; ++step) {
        const int j = pass == 0 ? step % n : (2 * n - 1 - step) % n, previous = pass == 0 ? (j + n - 1) % n : (j + 1) % n;
        away[j] = marked[j] ? 0 : std::min(away[j], away[previous] + 1);
      }
    const int run = kFootRun * round;
    const double full = (0.25 + 0.25 * round) * epsilon;
    for (int j = 0; j < n; ++j) depth[j] = full * std::clamp(double(2 * run + 1 - away[j]) / (run + 1), 0.0, 1.0);
    zip_strip(s, depth, inward);
    crossing = strip_crossings(s, hull, hairline, threads);
  }
  return static_cast<int>(std::count_if(depth.begin(), depth.end(), [](double d) { return d > 0.0; }));
}

}  // namespace hairfit
