#include "field/band_sign.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit::field {

namespace {

// Whether face t runs along edge a→b (rather than b→a).
bool runs_forward(const MeshFeatures& f, int t, int a, int b) {
  const Vec3i& v = f.faces[t];
  for (int k = 0; k < 3; ++k)
    if (v[k] == a && v[(k + 1) % 3] == b) return true;
  return false;
}

// Where the inside may change along the surface: edges that are not shared by exactly two faces
// turning opposite ways (rims, non-manifold edges, the borders of flipped patches).
bool irregular(const MeshFeatures& f, int e) {
  const int first = f.edge_face_offsets[e];
  if (f.edge_face_offsets[e + 1] - first != 2) return true;
  const auto [a, b] = f.edges[e];
  return runs_forward(f, f.edge_faces[first], a, b) == runs_forward(f, f.edge_faces[first + 1], a, b);
}

// Faces with an irregular edge within `reach` of any of their points.
std::vector<char> near_rims(const MeshFeatures& f, double reach) {
  std::vector<Vec3> rim;
  const int ne = static_cast<int>(f.edges.size());
  for (int e = 0; e < ne; ++e) {
    if (!irregular(f, e)) continue;
    const Vec3& a = f.vertices[f.edges[e].first];
    const Vec3& b = f.vertices[f.edges[e].second];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / reach)));
    for (int s = 0; s <= steps; ++s) rim.push_back(a + (b - a) * (double(s) / steps));
  }
  std::vector<char> near(f.faces.size(), 0);
  if (rim.empty()) return near;
  const PointGrid grid(rim, reach);
  for (std::size_t t = 0; t < f.faces.size(); ++t) {
    const Vec3i& v = f.faces[t];
    const Vec3 c = (f.vertices[v[0]] + f.vertices[v[1]] + f.vertices[v[2]]) / 3.0;
    double radius = 0;
    for (int k = 0; k < 3; ++k) radius = std::max(radius, (f.vertices[v[k]] - c).norm());
    grid.for_each_within(c, reach + radius, [&](int, double) { near[t] = 1; });
  }
  return near;
}

}  // namespace

namespace {

// Per face and side, how many of the band's samples could take that side's settled answer.
std::vector<std::array<int, 2>> samples_per_side(const MeshFeatures& f, const BandScan& band) {
  const int nf = static_cast<int>(f.faces.size()), ne = static_cast<int>(f.edges.size());
  std::vector<std::array<int, 2>> count(f.faces.size(), {0, 0});
  auto edge = [&](int e, int side) {
    for (int i = f.edge_face_offsets[e]; i < f.edge_face_offsets[e + 1]; ++i) ++count[f.edge_faces[i]][side];
  };
  for (std::size_t n = 0; n < band.key.size(); ++n) {
    const int key = band.key[n];
    if (key < 0) continue;
    const int side = band.value[n] < 0 ? 1 : 0;
    if (key < nf) {
      ++count[key][side];
    } else if (key < nf + ne) {
      edge(key - nf, side);
    } else {
      const int v = key - nf - ne;
      for (int i = f.vertex_edge_offsets[v]; i < f.vertex_edge_offsets[v + 1]; ++i) edge(f.vertex_edges[i], side);
    }
  }
  return count;
}

}  // namespace

SettledSigns::SettledSigns(const MeshFeatures& f, double r, const InsideTest& inside, int threads,
                           const BandScan* band)
    : features_(f), inside_(inside), faces_(f.faces.size(), {-1, -1}) {
  const std::vector<char> near = near_rims(f, 2 * r);
  const std::vector<std::array<int, 2>> samples = band ? samples_per_side(f, *band) : std::vector<std::array<int, 2>>{};
  parallel_for(static_cast<int>(f.faces.size()), threads, [&](int t) {
    if (near[t]) return;
    const Vec3i& v = f.faces[t];
    const Vec3 c = (f.vertices[v[0]] + f.vertices[v[1]] + f.vertices[v[2]]) / 3.0;
    const Vec3& n = f.face_normals[t];
    for (int side = 0; side < 2; ++side) {
      if (band && samples[t][side] < kWorthProbing) continue;
      const double s = side == 0 ? 1.0 : -1.0;
      // Two probes: one just off the face (a hundredth of the band's width), one a band width out.
      const bool close = inside(c + s * 0.01 * r * n);
      if (inside(c + s * r * n) == close) faces_[t][side] = close;
    }
  });
}

int SettledSigns::settled(int key, int side) const {
  const MeshFeatures& f = features_;
  const int nf = static_cast<int>(f.faces.size()), ne = static_cast<int>(f.edges.size());
  if (key < nf) return faces_[key][side];
  int answer = -2;
  auto edge = [&](int e) {
    if (irregular(f, e)) return false;
    for (int i = f.edge_face_offsets[e]; i < f.edge_face_offsets[e + 1]; ++i) {
      const int a = faces_[f.edge_faces[i]][side];
      if (a < 0 || (answer != -2 && a != answer)) return false;
      answer = a;
    }
    return true;
  };
  if (key < nf + ne) return edge(key - nf) ? answer : -1;
  const int v = key - nf - ne;
  for (int i = f.vertex_edge_offsets[v]; i < f.vertex_edge_offsets[v + 1]; ++i)
    if (!edge(f.vertex_edges[i])) return -1;
  return answer == -2 ? -1 : answer;
}

bool SettledSigns::inside(const Vec3& p, int key, int side) const {
  const int answer = key >= 0 ? settled(key, side) : -1;
  return answer >= 0 ? answer == 1 : inside_(p);
}

void sign_band(const SettledSigns& signs, const GridGeometry& grid, BandScan& band, int threads) {
  const int nx = grid.dims.x(), ny = grid.dims.y();
  parallel_for(grid.dims.z(), threads, [&](int k) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int64_t n = grid.index(i, j, k);
        if (band.key[n] < 0) continue;
        double& v = band.value[n];
        // The pseudo-normal's side: in front of the surface where the scan's sign is +.
        const bool in = signs.inside(grid.node(i, j, k), band.key[n], v < 0 ? 1 : 0);
        v = in ? -std::abs(v) : std::abs(v);
      }
  });
}

}  // namespace hairfit::field
