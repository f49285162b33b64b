#include "field/band_scan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

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
  int feature = 0;  // index within its kind
  Kind kind = Kind::face;
};

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kSlab = 16;  // z-layers per parallel work item (fixed: results must not depend on threads); a region
                           // rebuilds its planes in every slab it meets, so thicker slabs cost fewer rebuilds

// Largest dir·u over u in the cone {g_j·u ≤ 0} (within the plane ⊥ axis when axis ≠ 0) and the
// unit ball. The maximiser is dir itself, its projection onto one facet, an extreme ray, or 0.
struct Cone {
  const std::vector<Vec3>& g;
  Vec3 axis;                // zero for a 3-D cone
  std::vector<Vec3> rays;   // its extreme rays (computed once)

  bool valid(const Vec3& u) const {
    for (const Vec3& q : g)
      if (q.dot(u) > 1e-12) return false;
    return true;
  }
  Cone(const std::vector<Vec3>& constraints, const Vec3& plane_axis) : g(constraints), axis(plane_axis) {
    auto ray = [&](const Vec3& w) {
      const double l = w.norm();
      if (l < 1e-12) return;
      const Vec3 u = w / l;
      if (valid(u)) rays.push_back(u);
      if (valid(-u)) rays.push_back(-u);
    };
    if (planar())
      for (const Vec3& q : g) ray(axis.cross(q));
    else
      for (size_t i = 0; i < g.size(); ++i)
        for (size_t j = i + 1; j < g.size(); ++j) ray(g[i].cross(g[j]));
  }
  bool planar() const { return axis.squaredNorm() > 0; }
  double support(const Vec3& dir_in) const {
    const Vec3 dir = planar() ? Vec3(dir_in - dir_in.dot(axis) * axis) : dir_in;
    const double len = dir.norm();
    if (len > 0 && valid(dir / len)) return len;
    double best = 0.0;
    if (!planar())
      for (const Vec3& q : g) {
        const Vec3 u = dir - dir.dot(q) * q;
        const double l = u.norm();
        if (l > best && valid(u / l)) best = l;
      }
    for (const Vec3& u : rays) best = std::max(best, dir.dot(u));
    return best;
  }
};

// Bounding box of {base segment} ⊕ (cone ∩ ball of radius r).
template <typename R>
void cone_box(const Vec3& a, const Vec3& b, const std::vector<Vec3>& g, const Vec3& axis, double r, double pad,
              R& region) {
  const Cone cone(g, axis);
  for (int d = 0; d < 3; ++d) {
    const Vec3 e = Vec3::Unit(d);
    region.hi[d] = std::max(a[d], b[d]) + r * cone.support(e) + pad;
    region.lo[d] = std::min(a[d], b[d]) - r * cone.support(-e) - pad;
  }
}

// Unit direction and length of every edge (a → b).
struct EdgeGeometry {
  std::vector<Vec3> dirs;
  std::vector<double> lengths;
};

// The polyhedron of feature `id` (faces, then edges, then vertices): its half-spaces into
// `planes` (cleared first) and, when `region` is given, its bounding box. Cheap except for the
// box of edges and vertices, so boxes are computed once and planes again in every slab.
void make_region(const MeshFeatures& f, const EdgeGeometry& eg, int id, double r, double pad,
                 std::vector<Plane>& planes, Region* region, std::vector<Vec3>& g) {
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  planes.clear();
  g.clear();
  if (id < nf) {
    // Face: the triangle's prism of half-height r along its normal.
    const Vec3& n = f.face_normals[id];
    const Vec3 p[3] = {f.vertices[f.faces[id][0]], f.vertices[f.faces[id][1]], f.vertices[f.faces[id][2]]};
    for (int k = 0; k < 3; ++k) {
      const Vec3 o = (p[(k + 1) % 3] - p[k]).cross(n).normalized();  // outward in-plane
      planes.push_back({o, o.dot(p[k]) + pad});
    }
    planes.push_back({n, n.dot(p[0]) + r + pad});
    planes.push_back({-n, -n.dot(p[0]) + r + pad});
    if (region) {
      region->kind = Kind::face;
      region->feature = id;
      region->lo = region->hi = p[0];
      for (int k = 0; k < 3; ++k)
        for (double s : {-r, r}) {
          region->lo = region->lo.cwiseMin(p[k] + s * n);
          region->hi = region->hi.cwiseMax(p[k] + s * n);
        }
      region->lo.array() -= pad;
      region->hi.array() += pad;
    }
  } else if (id < nf + ne) {
    // Edge: the segment's slab, cut by the half-spaces {(x−a)·d_f ≤ 0} of each adjacent face
    // (d_f: in-plane direction from the edge into f); a point whose closest point is inside
    // the edge cannot have (x−c)·d_f > 0, or moving into f would bring it closer.
    const int e = id - nf;
    const Vec3& a = f.vertices[f.edges[e].first];
    const Vec3& b = f.vertices[f.edges[e].second];
    const Vec3& t = eg.dirs[e];
    planes.push_back({-t, -t.dot(a) + pad});
    planes.push_back({t, t.dot(b) + pad});
    for (int i = f.edge_face_offsets[e]; i < f.edge_face_offsets[e + 1]; ++i) {
      const Vec3i& tri = f.faces[f.edge_faces[i]];
      int opposite = tri[0];
      for (int k = 0; k < 3; ++k)
        if (tri[k] != f.edges[e].first && tri[k] != f.edges[e].second) opposite = tri[k];
      const Vec3 w = f.vertices[opposite] - a;
      const Vec3 d = (w - w.dot(t) * t).normalized();
      g.push_back(d);
      planes.push_back({d, d.dot(a) + pad});
    }
    if (region) {
      region->kind = Kind::edge;
      region->feature = e;
      cone_box(a, b, g, t, r, pad, *region);
    }
  } else {
    // Vertex: the cone {(x−v)·u_j ≤ 0} over its incident edge directions u_j.
    const int v = id - nf - ne;
    const Vec3& p = f.vertices[v];
    for (int i = f.vertex_edge_offsets[v]; i < f.vertex_edge_offsets[v + 1]; ++i) {
      const int e = f.vertex_edges[i];
      const Vec3 u = f.edges[e].first == v ? eg.dirs[e] : Vec3(-eg.dirs[e]);
      g.push_back(u);
      planes.push_back({u, u.dot(p) + pad});
    }
    if (region) {
      region->kind = Kind::vertex;
      region->feature = v;
      cone_box(p, p, g, Vec3::Zero(), r, pad, *region);
    }
  }
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
  const double h = grid.voxel;
  const double pad = 1e-9 * h;  // covers round-off in the plane tests; far below the 1e-6 budget
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  const int nregions = nf + ne + static_cast<int>(f.vertices.size());
  EdgeGeometry eg;
  eg.dirs.resize(ne);
  eg.lengths.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const Vec3 d = f.vertices[f.edges[e].second] - f.vertices[f.edges[e].first];
    eg.lengths[e] = d.norm();
    eg.dirs[e] = d / eg.lengths[e];
  }

  BandScan out;
  out.value.assign(grid.count(), kInfinity);
  out.key.assign(grid.count(), -1);

  // Index box of every region (empty when outside the grid), then the slabs it meets. Only the
  // boxes are kept: planes are rebuilt per slab, which is cheaper than storing them.
  struct Box {
    int lo[3], hi[3];
  };
  std::unique_ptr<Box[]> boxes(new Box[nregions]);
  constexpr int kBlock = 4096;
  parallel_for((nregions + kBlock - 1) / kBlock, threads, [&](int block) {
    std::vector<Plane> planes;
    std::vector<Vec3> g;
    Region reg;
    for (int id = block * kBlock; id < std::min(nregions, (block + 1) * kBlock); ++id) {
      make_region(f, eg, id, r, pad, planes, &reg, g);
      Box& b = boxes[id];
      for (int d = 0; d < 3; ++d) {
        const double lo = std::ceil((reg.lo[d] - grid.origin[d]) / h);
        const double hi = std::floor((reg.hi[d] - grid.origin[d]) / h);
        b.lo[d] = static_cast<int>(std::max(0.0, std::min(lo, double(grid.dims[d]))));
        b.hi[d] = static_cast<int>(std::min(double(grid.dims[d] - 1), std::max(hi, -1.0)));
      }
      if (b.lo[0] > b.hi[0] || b.lo[1] > b.hi[1]) b.hi[2] = b.lo[2] - 1;  // empty
    }
  });
  const int nslabs = (grid.dims.z() + kSlab - 1) / kSlab;
  std::vector<int> slab_count(nslabs + 1, 0);
  for (int id = 0; id < nregions; ++id)
    if (boxes[id].lo[2] <= boxes[id].hi[2])
      for (int s = boxes[id].lo[2] / kSlab; s <= boxes[id].hi[2] / kSlab; ++s) ++slab_count[s + 1];
  for (int s = 0; s < nslabs; ++s) slab_count[s + 1] += slab_count[s];
  std::vector<int> slab_regions(slab_count[nslabs]);
  {
    std::vector<int> fill(slab_count.begin(), slab_count.end() - 1);
    for (int id = 0; id < nregions; ++id)
      if (boxes[id].lo[2] <= boxes[id].hi[2])
        for (int s = boxes[id].lo[2] / kSlab; s <= boxes[id].hi[2] / kSlab; ++s) slab_regions[fill[s]++] = id;
  }

  const int nx = grid.dims.x(), ny = grid.dims.y();
  parallel_for(nslabs, threads, [&](int slab) {
    std::vector<Plane> planes;
    std::vector<Vec3> g;
    const int k_begin = slab * kSlab;
    const int k_end = std::min(grid.dims.z() - 1, k_begin + kSlab - 1);
    for (int s = slab_count[slab]; s < slab_count[slab + 1]; ++s) {
      const int id = slab_regions[s];
      const Box& box = boxes[id];
      make_region(f, eg, id, r, pad, planes, nullptr, g);
      const Kind kind = id < nf ? Kind::face : id < nf + ne ? Kind::edge : Kind::vertex;
      const int feature = id < nf ? id : id < nf + ne ? id - nf : id - nf - ne;
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

      // Feature data for the distance evaluations.
      Vec3 p0, dir = Vec3::Zero(), normal;
      double len = 0.0;
      int key = 0;
      if (kind == Kind::face) {
        p0 = f.vertices[f.faces[feature][0]];
        normal = f.face_normals[feature];
        key = feature;
      } else if (kind == Kind::edge) {
        p0 = f.vertices[f.edges[feature].first];
        dir = eg.dirs[feature];
        len = eg.lengths[feature];
        normal = f.edge_normals[feature];
        key = nf + feature;
      } else {
        p0 = f.vertices[feature];
        normal = f.vertex_normals[feature];
        key = nf + ne + feature;
      }

      int idx[3];
      for (idx[c] = lo[c]; idx[c] <= hi[c]; ++idx[c]) {
        const double zc = grid.origin[c] + h * idx[c];
        for (idx[b] = lo[b]; idx[b] <= hi[b]; ++idx[b]) {
          const double yb = grid.origin[b] + h * idx[b];
          double t_lo = -kInfinity, t_hi = kInfinity;  // the index box clips the row
          for (size_t q = 0; q < planes.size(); ++q) {
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
          // Clamp in double before converting: the bounds may be infinite.
          const double u0 = std::ceil((t_lo - grid.origin[a]) / h), u1 = std::floor((t_hi - grid.origin[a]) / h);
          const int i0 = static_cast<int>(std::max(double(lo[a]), std::min(u0, double(hi[a]) + 1)));
          const int i1 = static_cast<int>(std::min(double(hi[a]), std::max(u1, double(lo[a]) - 1)));
          for (idx[a] = i0; idx[a] <= i1; ++idx[a]) {
            const Vec3 p = grid.origin + h * Vec3(idx[0], idx[1], idx[2]);
            double d;
            double side;
            int k = key;
            if (kind == Kind::face) {
              side = normal.dot(p - p0);
              d = std::abs(side);
            } else if (kind == Kind::edge) {
              const double t = (p - p0).dot(dir);
              Vec3 diff;
              if (t <= 0) {  // the closest point is the end vertex: sign and key are the vertex's
                diff = p - p0;
                k = nf + ne + f.edges[feature].first;
                side = diff.dot(f.vertex_normals[f.edges[feature].first]);
              } else if (t >= len) {
                diff = p - (p0 + len * dir);
                k = nf + ne + f.edges[feature].second;
                side = diff.dot(f.vertex_normals[f.edges[feature].second]);
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
