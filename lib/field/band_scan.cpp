#include "field/band_scan.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace hairfit::field {

namespace {

// A half-space g·p ≤ c.
struct Plane {
  Vec3 g;
  double c;
};

enum class Kind : uint8_t { face, edge, vertex };

// The polyhedron a feature scan-converts: its half-spaces and a bounding box.
struct Region {
  Vec3 lo, hi;
  int first_plane = 0;
  int plane_count = 0;
  int feature = 0;  // index within its kind
  Kind kind = Kind::face;
};

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kSlab = 8;  // z-layers per parallel work item (fixed: results must not depend on threads)

// Largest dir·u over u in the cone {g_j·u ≤ 0} (within the plane ⊥ axis when axis ≠ 0) and the
// unit ball. The maximiser is dir itself, its projection onto one facet, an extreme ray, or 0.
double cone_support(const Vec3& dir_in, const std::vector<Vec3>& g, const Vec3& axis) {
  const double tol = 1e-12;
  auto valid = [&](const Vec3& u) {
    for (const Vec3& q : g)
      if (q.dot(u) > tol) return false;
    return true;
  };
  const bool planar = axis.squaredNorm() > 0;
  const Vec3 dir = planar ? Vec3(dir_in - dir_in.dot(axis) * axis) : dir_in;
  double best = 0.0;
  const double len = dir.norm();
  if (len > 0 && valid(dir / len)) return len;
  if (!planar)
    for (const Vec3& q : g) {
      const Vec3 u = dir - dir.dot(q) * q;
      const double l = u.norm();
      if (l > 0 && valid(u / l)) best = std::max(best, l);
    }
  auto ray = [&](const Vec3& w) {
    const double l = w.norm();
    if (l < 1e-12) return;
    const Vec3 u = w / l;
    if (valid(u)) best = std::max(best, dir.dot(u));
    if (valid(-u)) best = std::max(best, -dir.dot(u));
  };
  if (planar)
    for (const Vec3& q : g) ray(axis.cross(q));
  else
    for (size_t i = 0; i < g.size(); ++i)
      for (size_t j = i + 1; j < g.size(); ++j) ray(g[i].cross(g[j]));
  return best;
}

// Bounding box of {base segment} ⊕ (cone ∩ ball of radius r).
void cone_box(const Vec3& a, const Vec3& b, const std::vector<Vec3>& g, const Vec3& axis, double r, double pad,
              Region& region) {
  for (int d = 0; d < 3; ++d) {
    const Vec3 e = Vec3::Unit(d);
    region.hi[d] = std::max(a[d], b[d]) + r * cone_support(e, g, axis) + pad;
    region.lo[d] = std::min(a[d], b[d]) - r * cone_support(-e, g, axis) - pad;
  }
}

struct Regions {
  std::vector<Region> regions;
  std::vector<Plane> planes;
  std::vector<Vec3> edge_dirs;  // unit direction of each edge (a → b)
  std::vector<double> edge_lengths;
};

Regions build_regions(const MeshFeatures& f, double r, double pad, int threads) {
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  const int nv = static_cast<int>(f.vertices.size());
  Regions out;
  out.regions.resize(nf + ne + nv);
  // Plane counts are known up front, so every feature fills its own slots in parallel.
  std::vector<int> offsets(nf + ne + nv + 1, 0);
  for (int i = 0; i < nf; ++i) offsets[i + 1] = 5;
  for (int e = 0; e < ne; ++e) offsets[nf + e + 1] = 2 + f.edge_face_offsets[e + 1] - f.edge_face_offsets[e];
  for (int v = 0; v < nv; ++v) offsets[nf + ne + v + 1] = f.vertex_edge_offsets[v + 1] - f.vertex_edge_offsets[v];
  for (size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
  out.planes.resize(offsets.back());
  out.edge_dirs.resize(ne);
  out.edge_lengths.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const Vec3 d = f.vertices[f.edges[e].second] - f.vertices[f.edges[e].first];
    out.edge_lengths[e] = d.norm();
    out.edge_dirs[e] = d / out.edge_lengths[e];
  }

  parallel_for(nf + ne + nv, threads, [&](int id) {
    Region& reg = out.regions[id];
    reg.first_plane = offsets[id];
    reg.plane_count = offsets[id + 1] - offsets[id];
    Plane* pl = out.planes.data() + reg.first_plane;
    if (id < nf) {
      // Face: the triangle's prism of half-height r along its normal.
      reg.kind = Kind::face;
      reg.feature = id;
      const Vec3& n = f.face_normals[id];
      const Vec3 p[3] = {f.vertices[f.faces[id][0]], f.vertices[f.faces[id][1]], f.vertices[f.faces[id][2]]};
      for (int k = 0; k < 3; ++k) {
        const Vec3 o = (p[(k + 1) % 3] - p[k]).cross(n).normalized();  // outward in-plane
        pl[k] = {o, o.dot(p[k]) + pad};
      }
      pl[3] = {n, n.dot(p[0]) + r + pad};
      pl[4] = {-n, -n.dot(p[0]) + r + pad};
      reg.lo = reg.hi = p[0];
      for (int k = 0; k < 3; ++k)
        for (double s : {-r, r}) {
          reg.lo = reg.lo.cwiseMin(p[k] + s * n);
          reg.hi = reg.hi.cwiseMax(p[k] + s * n);
        }
      reg.lo.array() -= pad;
      reg.hi.array() += pad;
    } else if (id < nf + ne) {
      // Edge: the segment's slab, cut by the half-spaces {(x−a)·d_f ≤ 0} of each adjacent face
      // (d_f: in-plane direction from the edge into f); a point whose closest point is inside
      // the edge cannot have (x−c)·d_f > 0, or moving into f would bring it closer.
      const int e = id - nf;
      reg.kind = Kind::edge;
      reg.feature = e;
      const Vec3& a = f.vertices[f.edges[e].first];
      const Vec3& b = f.vertices[f.edges[e].second];
      const Vec3& t = out.edge_dirs[e];
      pl[0] = {-t, -t.dot(a) + pad};
      pl[1] = {t, t.dot(b) + pad};
      std::vector<Vec3> g;
      for (int i = f.edge_face_offsets[e]; i < f.edge_face_offsets[e + 1]; ++i) {
        const Vec3i& tri = f.faces[f.edge_faces[i]];
        int opposite = tri[0];
        for (int k = 0; k < 3; ++k)
          if (tri[k] != f.edges[e].first && tri[k] != f.edges[e].second) opposite = tri[k];
        const Vec3 w = f.vertices[opposite] - a;
        const Vec3 d = (w - w.dot(t) * t).normalized();
        g.push_back(d);
        pl[2 + (i - f.edge_face_offsets[e])] = {d, d.dot(a) + pad};
      }
      cone_box(a, b, g, t, r, pad, reg);
    } else {
      // Vertex: the cone {(x−v)·u_j ≤ 0} over its incident edge directions u_j.
      const int v = id - nf - ne;
      reg.kind = Kind::vertex;
      reg.feature = v;
      const Vec3& p = f.vertices[v];
      std::vector<Vec3> g;
      for (int i = f.vertex_edge_offsets[v]; i < f.vertex_edge_offsets[v + 1]; ++i) {
        const int e = f.vertex_edges[i];
        const Vec3 u = f.edges[e].first == v ? out.edge_dirs[e] : Vec3(-out.edge_dirs[e]);
        g.push_back(u);
        pl[i - f.vertex_edge_offsets[v]] = {u, u.dot(p) + pad};
      }
      cone_box(p, p, g, Vec3::Zero(), r, pad, reg);
    }
  });
  return out;
}

}  // namespace

FeaturePoint closest_on_feature(const MeshFeatures& f, int key, const Vec3& p) {
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  if (key < nf) {
    const Vec3& n = f.face_normals[key];
    return {p - n.dot(p - f.vertices[f.faces[key][0]]) * n, n};
  }
  if (key < nf + ne) {
    const int e = key - nf;
    const Vec3& a = f.vertices[f.edges[e].first];
    const Vec3 d = f.vertices[f.edges[e].second] - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return {a + t * d, f.edge_normals[e]};
  }
  const int v = key - nf - ne;
  return {f.vertices[v], f.vertex_normals[v]};
}

BandScan scan_band(const MeshFeatures& f, const GridGeometry& grid, double r, int threads) {
  const double h = grid.h;
  const double pad = 1e-9 * h;  // covers round-off in the plane tests; far below the 1e-6 budget
  const Regions R = build_regions(f, r, pad, threads);
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());

  BandScan out;
  out.value.assign(grid.count(), kInfinity);
  out.key.assign(grid.count(), -1);

  // Index box of every region (empty when outside the grid), and its slabs.
  struct Box {
    int lo[3], hi[3];
  };
  const int nregions = static_cast<int>(R.regions.size());
  std::vector<Box> boxes(nregions);
  const int nslabs = (grid.dims.z() + kSlab - 1) / kSlab;
  std::vector<int> slab_count(nslabs + 1, 0);
  for (int id = 0; id < nregions; ++id) {
    Box& b = boxes[id];
    bool empty = false;
    for (int d = 0; d < 3; ++d) {
      const double lo = std::ceil((R.regions[id].lo[d] - grid.origin[d]) / h);
      const double hi = std::floor((R.regions[id].hi[d] - grid.origin[d]) / h);
      b.lo[d] = static_cast<int>(std::max(0.0, lo));
      b.hi[d] = static_cast<int>(std::min(double(grid.dims[d] - 1), hi));
      if (b.lo[d] > b.hi[d]) empty = true;
    }
    if (empty) {
      b.lo[2] = 1;
      b.hi[2] = 0;
      continue;
    }
    for (int s = b.lo[2] / kSlab; s <= b.hi[2] / kSlab; ++s) ++slab_count[s + 1];
  }
  for (int s = 0; s < nslabs; ++s) slab_count[s + 1] += slab_count[s];
  std::vector<int> slab_regions(slab_count[nslabs]);
  {
    std::vector<int> fill(slab_count.begin(), slab_count.end() - 1);
    for (int id = 0; id < nregions; ++id)
      for (int s = boxes[id].lo[2] / kSlab; boxes[id].lo[2] <= boxes[id].hi[2] && s <= boxes[id].hi[2] / kSlab; ++s)
        slab_regions[fill[s]++] = id;
  }

  const int nx = grid.dims.x(), ny = grid.dims.y();
  parallel_for(nslabs, threads, [&](int slab) {
    const int k_begin = slab * kSlab;
    const int k_end = std::min(grid.dims.z() - 1, k_begin + kSlab - 1);
    for (int s = slab_count[slab]; s < slab_count[slab + 1]; ++s) {
      const int id = slab_regions[s];
      const Region& reg = R.regions[id];
      const Box& box = boxes[id];
      // Rows run along the box's longest axis (fewest rows); chosen from the whole box, not the
      // slab's part, so the voxels a region visits do not depend on the slab split.
      int ext[3];
      for (int d = 0; d < 3; ++d) ext[d] = box.hi[d] - box.lo[d];
      const int a = (ext[0] >= ext[1] && ext[0] >= ext[2]) ? 0 : (ext[1] >= ext[2] ? 1 : 2);
      const int b = a == 0 ? 1 : 0;
      const int c = a == 2 ? 1 : 2;
      int lo[3] = {box.lo[0], box.lo[1], box.lo[2]};
      int hi[3] = {box.hi[0], box.hi[1], box.hi[2]};
      lo[2] = std::max(lo[2], k_begin);
      hi[2] = std::min(hi[2], k_end);
      if (lo[2] > hi[2]) continue;
      const Plane* planes = R.planes.data() + reg.first_plane;

      // Feature data for the distance evaluations.
      Vec3 p0, dir = Vec3::Zero(), normal;
      double len = 0.0;
      int key = 0;
      if (reg.kind == Kind::face) {
        p0 = f.vertices[f.faces[reg.feature][0]];
        normal = f.face_normals[reg.feature];
        key = reg.feature;
      } else if (reg.kind == Kind::edge) {
        p0 = f.vertices[f.edges[reg.feature].first];
        dir = R.edge_dirs[reg.feature];
        len = R.edge_lengths[reg.feature];
        normal = f.edge_normals[reg.feature];
        key = nf + reg.feature;
      } else {
        p0 = f.vertices[reg.feature];
        normal = f.vertex_normals[reg.feature];
        key = nf + ne + reg.feature;
      }

      int idx[3];
      for (idx[c] = lo[c]; idx[c] <= hi[c]; ++idx[c]) {
        const double zc = grid.origin[c] + h * idx[c];
        for (idx[b] = lo[b]; idx[b] <= hi[b]; ++idx[b]) {
          const double yb = grid.origin[b] + h * idx[b];
          double t_lo = reg.lo[a], t_hi = reg.hi[a];
          for (int q = 0; q < reg.plane_count; ++q) {
            const Plane& P = planes[q];
            const double rest = P.c - P.g[b] * yb - P.g[c] * zc;
            if (P.g[a] > 0)
              t_hi = std::min(t_hi, rest / P.g[a]);
            else if (P.g[a] < 0)
              t_lo = std::max(t_lo, rest / P.g[a]);
            else if (rest < 0)
              t_hi = -kInfinity;
          }
          if (!(t_lo <= t_hi)) continue;
          const int i0 = std::max(lo[a], static_cast<int>(std::ceil((t_lo - grid.origin[a]) / h)));
          const int i1 = std::min(hi[a], static_cast<int>(std::floor((t_hi - grid.origin[a]) / h)));
          for (idx[a] = i0; idx[a] <= i1; ++idx[a]) {
            const Vec3 p = grid.origin + h * Vec3(idx[0], idx[1], idx[2]);
            double d;
            double side;
            int k = key;
            if (reg.kind == Kind::face) {
              side = normal.dot(p - p0);
              d = std::abs(side);
            } else if (reg.kind == Kind::edge) {
              const double t = (p - p0).dot(dir);
              Vec3 diff;
              if (t <= 0) {  // the closest point is the end vertex: sign and key are the vertex's
                diff = p - p0;
                k = nf + ne + f.edges[reg.feature].first;
                side = diff.dot(f.vertex_normals[f.edges[reg.feature].first]);
              } else if (t >= len) {
                diff = p - (p0 + len * dir);
                k = nf + ne + f.edges[reg.feature].second;
                side = diff.dot(f.vertex_normals[f.edges[reg.feature].second]);
              } else {
                diff = p - (p0 + t * dir);
                side = diff.dot(normal);
              }
              d = diff.norm();
            } else {
              const Vec3 diff = p - p0;
              d = diff.norm();
              side = diff.dot(normal);
            }
            if (d > r) continue;
            const int64_t at = idx[0] + int64_t(nx) * (idx[1] + int64_t(ny) * idx[2]);
            double& best = out.value[at];
            int32_t& best_key = out.key[at];
            const double best_d = std::abs(best);
            if (d < best_d || (d == best_d && k < best_key)) {
              best = side < 0 ? -d : d;
              best_key = k;
            }
          }
        }
      }
    }
  });
  for (double v : out.value) out.band_voxels += v != kInfinity;
  return out;
}

}  // namespace hairfit::field
