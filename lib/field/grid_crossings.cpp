#include "field/grid_crossings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"

namespace hairfit::field {

namespace {

using Int = __int128;
constexpr int kLatticeBits = 16;             // lattice points per voxel: 2^16
constexpr int64_t kNode = int64_t(1) << kLatticeBits;  // a node's spacing in lattice units
constexpr double kRange = double(int64_t(1) << 40);    // |coordinate| < 2^40 keeps every product in 126 bits

int sign(Int v) { return (v > 0) - (v < 0); }

// floor(a / b) for b > 0.
Int floor_div(Int a, Int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The side of the edge a→b (in the plane of axes u, v) that the point q displaced by (ε_u, ε_v),
// ε_u ≫ ε_v, lies on: the sign of the edge function (b − a) × (q − a) with the displacement's
// terms (b_u − a_u)·ε_v − (b_v − a_v)·ε_u where it is zero; 0 only for a = b.
int edge_side(const int64_t a[2], const int64_t b[2], const int64_t q[2]) {
  const Int e = Int(b[0] - a[0]) * (q[1] - a[1]) - Int(b[1] - a[1]) * (q[0] - a[0]);
  if (e != 0) return sign(e);
  if (b[1] != a[1]) return a[1] > b[1] ? 1 : -1;
  return (b[0] > a[0]) - (b[0] < a[0]);
}

struct Crossing {
  int64_t line;
  int32_t edge;
  int32_t jump;
  bool operator<(const Crossing& o) const { return line != o.line ? line < o.line : edge < o.edge; }
};

// The grid edges whose lines one triangle (lattice coordinates, weight w) crosses, per axis.
void rasterise(const int64_t v[3][3], int w, const Vec3i& dims, std::array<std::vector<Crossing>, 3>& out) {
  Int n[3];
  {
    const Int e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const Int e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  }
  // The displacement (ε, ε², ε³) of a node on the triangle's plane puts it on this side.
  const int tie = n[0] != 0 ? sign(n[0]) : n[1] != 0 ? sign(n[1]) : sign(n[2]);
  if (tie == 0) return;  // zero area: no jump anywhere
  for (int a = 0; a < 3; ++a) {
    if (n[a] == 0) continue;  // the triangle contains the axis' direction: no line crosses it
    const int u = a == 0 ? 1 : 0, t = a == 2 ? 1 : 2;  // the other two axes, the lower first
    int64_t lo[2] = {v[0][u], v[0][t]}, hi[2] = {v[0][u], v[0][t]};
    for (int c = 1; c < 3; ++c) {
      lo[0] = std::min(lo[0], v[c][u]), hi[0] = std::max(hi[0], v[c][u]);
      lo[1] = std::min(lo[1], v[c][t]), hi[1] = std::max(hi[1], v[c][t]);
    }
    // The lines (at multiples of kNode, displaced up by ε) that can pass through the projected box.
    auto first_line = [](int64_t x) { return -int64_t(floor_div(-Int(x), kNode)); };
    const int64_t u0 = std::max<int64_t>(0, first_line(lo[0])), u1 = std::min<int64_t>(dims[u] - 1, int64_t(floor_div(hi[0], kNode)));
    const int64_t t0 = std::max<int64_t>(0, first_line(lo[1])), t1 = std::min<int64_t>(dims[t] - 1, int64_t(floor_div(hi[1], kNode)));
    const int64_t p[3][2] = {{v[0][u], v[0][t]}, {v[1][u], v[1][t]}, {v[2][u], v[2][t]}};
    const int along_sign = sign(n[a]);
    for (int64_t lt = t0; lt <= t1; ++lt)
      for (int64_t lu = u0; lu <= u1; ++lu) {
        const int64_t q[2] = {lu * kNode, lt * kNode};
        const int s0 = edge_side(p[0], p[1], q);
        if (s0 == 0 || edge_side(p[1], p[2], q) != s0 || edge_side(p[2], p[0], q) != s0) continue;
        // Where along the line it crosses: s(m) = sign(n_a)·n·(node m − v0) = m·step − threshold
        // grows with m, and the crossing edge leads into the first node with s > 0 (s = 0: the
        // displacement's side decides).
        int64_t node[3];  // the line's node 0
        node[a] = 0, node[u] = lu * kNode, node[t] = lt * kNode;
        Int d0 = 0;
        for (int c = 0; c < 3; ++c) d0 += n[c] * (Int(node[c]) - v[0][c]);
        const Int threshold = -along_sign * d0, step = (along_sign > 0 ? n[a] : -n[a]) * kNode;
        Int first = floor_div(threshold, step) + 1;
        if ((first - 1) * step == threshold && tie * along_sign > 0) first -= 1;  // on the plane: the tie decides
        const Int edge = first - 1;
        if (edge < 0 || edge > dims[a] - 2) continue;
        out[a].push_back({lu + int64_t(dims[u]) * lt, int32_t(edge), -along_sign * w});
      }
  }
}

}  // namespace

int GridCrossings::prefix(const Axis& a, int64_t first, int64_t last, int n) {
  const auto begin = a.edge.begin() + first, end = a.edge.begin() + last;
  const int64_t at = std::lower_bound(begin, end, n) - a.edge.begin();
  return at < last ? a.before[at] : a.before[last - 1] + a.jump[last - 1];
}

GridCrossings::GridCrossings(const std::vector<SoupPart>& soup, const GridGeometry& grid, int threads) : dims_(grid.dims) {
  // Every part's vertices in lattice coordinates.
  std::vector<std::vector<std::array<int64_t, 3>>> lattice(soup.size());
  const double scale = double(kNode) / grid.voxel;
  for (std::size_t s = 0; s < soup.size(); ++s)
    for (const Vec3& x : soup[s].mesh->positions) {
      std::array<int64_t, 3> q;
      for (int c = 0; c < 3; ++c) {
        const double l = std::nearbyint((x[c] - grid.origin[c]) * scale);
        if (!(std::abs(l) < kRange))
          throw std::invalid_argument("a vertex lies more than 2^24 voxels from the grid's origin");
        q[c] = int64_t(l);
      }
      lattice[s].push_back(q);
    }
  // Triangles in chunks, each chunk's crossings in its own lists; sorted afterwards, so the order
  // of the chunks does not matter.
  std::vector<std::pair<int, int>> chunks;  // (part, first triangle)
  constexpr int kChunk = 256;
  for (std::size_t s = 0; s < soup.size(); ++s)
    for (std::size_t t = 0; t < soup[s].mesh->triangles.size(); t += kChunk) chunks.push_back({int(s), int(t)});
  std::vector<std::array<std::vector<Crossing>, 3>> found(chunks.size());
  parallel_for(static_cast<int>(chunks.size()), threads, [&](int c) {
    const auto [s, first] = chunks[c];
    const Mesh& mesh = *soup[s].mesh;
    const int last = std::min<int>(int(mesh.triangles.size()), first + kChunk);
    for (int t = first; t < last; ++t) {
      int64_t v[3][3];
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) v[k][d] = lattice[s][mesh.triangles[t][k]][d];
      rasterise(v, soup[s].weight, dims_, found[c]);
    }
  });
  for (int a = 0; a < 3; ++a) {
    std::vector<Crossing> all;
    for (auto& f : found) all.insert(all.end(), f[a].begin(), f[a].end());
    std::sort(all.begin(), all.end());
    const int u = a == 0 ? 1 : 0, t = a == 2 ? 1 : 2;
    const int64_t lines = int64_t(dims_[u]) * dims_[t];
    Axis& axis = axes_[a];
    axis.offsets.assign(lines + 1, 0);
    for (std::size_t e = 0; e < all.size();) {
      std::size_t f = e;
      int jump = 0;
      for (; f < all.size() && all[f].line == all[e].line && all[f].edge == all[e].edge; ++f) jump += all[f].jump;
      if (jump != 0) {
        axis.edge.push_back(all[e].edge);
        axis.jump.push_back(jump);
        ++axis.offsets[all[e].line + 1];
      }
      e = f;
    }
    for (int64_t l = 0; l < lines; ++l) axis.offsets[l + 1] += axis.offsets[l];
    axis.before.resize(axis.edge.size());
    for (int64_t l = 0; l < lines; ++l) {
      int sum = 0;
      for (int64_t e = axis.offsets[l]; e < axis.offsets[l + 1]; ++e) {
        axis.before[e] = sum;
        sum += axis.jump[e];
      }
    }
  }
}

}  // namespace hairfit::field
