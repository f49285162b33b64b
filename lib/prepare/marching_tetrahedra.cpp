#include "prepare/marching_tetrahedra.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "core/grid_geometry.h"

namespace hairfit {

namespace {

// Corner c of a cell is the node at offset (c & 1, c >> 1 & 1, c >> 2 & 1).
Vec3 corner_offset(int c) { return Vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1); }

// The Kuhn split: one tetrahedron per order of the axes, 0 → e_p → e_p + e_q → (1, 1, 1). Every
// edge runs from a corner to a corner whose bits include it, so an edge is named by its lower node
// and the bits it adds, the same from every cell around it.
std::array<std::array<int, 4>, 6> kuhn_tetrahedra() {
  std::array<std::array<int, 4>, 6> tets{};
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int t = 0; t < 6; ++t) {
    const int a = 1 << orders[t][0], b = a | (1 << orders[t][1]);
    tets[t] = {0, a, b, 7};
  }
  return tets;
}

double orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

}  // namespace

Vec3 SampleGrid::position(std::int64_t n) const {
  const Vec3i v = grid_indices(n, dims);
  return position(v.x(), v.y(), v.z());
}

ZeroSet marching_tetrahedra(const SampleGrid& grid, const std::vector<double>& values) {
  static const std::array<std::array<int, 4>, 6> kTets = kuhn_tetrahedra();
  ZeroSet out;
  std::unordered_map<std::int64_t, int> vertex_of_edge;
  std::array<std::int64_t, 8> node{};
  std::array<double, 8> value{};
  // The vertex on the edge between cell corners ca ⊂ cb (as bit sets).
  auto vertex = [&](int ca, int cb) {
    if (ca > cb) std::swap(ca, cb);
    const std::int64_t key = node[ca] * 8 + (ca ^ cb);
    const auto [it, added] = vertex_of_edge.emplace(key, static_cast<int>(out.at.size()));
    if (added) {
      const double va = value[ca], vb = value[cb];
      const double t = std::clamp(va / (va - vb), 0.0, 1.0);
      const Vec3 pa = grid.position(node[ca]), pb = grid.position(node[cb]);
      out.mesh.positions.push_back(pa + t * (pb - pa));
      out.at.push_back({node[ca], node[cb], t});
    }
    return it->second;
  };
  auto emit = [&](int a, int b, int c) { out.mesh.triangles.emplace_back(a, b, c); };

  // A node value of exactly 0 is read as slightly positive: the surface then passes by the node
  // instead of through it, where the vertices of all its crossing edges would coincide.
  const double zero = 1e-7 * grid.spacing;
  const Vec3i& n = grid.dims;
  for (int k = 0; k + 1 < n.z(); ++k)
    for (int j = 0; j + 1 < n.y(); ++j)
      for (int i = 0; i + 1 < n.x(); ++i) {
        int negatives = 0;
        for (int c = 0; c < 8; ++c) {
          node[c] = grid.node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          value[c] = values[node[c]] == 0.0 ? zero : values[node[c]];
          negatives += value[c] < 0.0;
        }
        if (negatives == 0 || negatives == 8) continue;
        for (const auto& tet : kTets) {
          std::array<int, 4> neg{}, pos{};
          int nn = 0, np = 0;
          for (int c : tet) (value[c] < 0.0 ? neg[nn++] : pos[np++]) = c;
          if (nn == 0 || np == 0) continue;
          if (nn == 2) {
            // A quadrilateral around the two negative corners a, b, facing the positive c, d.
            const int a = neg[0], b = neg[1], c = pos[0], d = pos[1];
            const bool turn = orientation(corner_offset(a), corner_offset(b), corner_offset(c), corner_offset(d)) > 0.0;
            int q[4] = {vertex(a, c), vertex(a, d), vertex(b, d), vertex(b, c)};
            if (!turn) std::swap(q[1], q[3]);
            const auto& x = out.mesh.positions;
            if ((x[q[0]] - x[q[2]]).squaredNorm() <= (x[q[1]] - x[q[3]]).squaredNorm()) {
              emit(q[0], q[1], q[2]);
              emit(q[0], q[2], q[3]);
            } else {
              emit(q[0], q[1], q[3]);
              emit(q[1], q[2], q[3]);
            }
            continue;
          }
          // One corner on its own side: a triangle across its three edges, facing away from it
          // when it is negative and toward it when it is positive.
          const bool lone_negative = nn == 1;
          const int lone = lone_negative ? neg[0] : pos[0];
          const int* others = lone_negative ? pos.data() : neg.data();
          int o[3] = {others[0], others[1], others[2]};
          const bool away = orientation(corner_offset(o[0]), corner_offset(o[1]), corner_offset(o[2]), corner_offset(lone)) < 0.0;
          if (away != lone_negative) std::swap(o[1], o[2]);
          emit(vertex(lone, o[0]), vertex(lone, o[1]), vertex(lone, o[2]));
        }
      }
  return out;
}

}  // namespace hairfit
