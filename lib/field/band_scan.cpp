#include "field/band_scan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "core/parallel.h"

namespace hairfit::field {

namespace {

// A half-space g·p ≤ c.
struct Plane {
  Vec3 g;
  double c;
};

enum class Kind : uint8_t { face, edge, vertex };

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kSlab = 16;  // z-layers per parallel work item (fixed: results must not depend on threads); a region
                           // rebuilds its planes in every slab it meets, so thicker slabs cost fewer rebuilds

// Largest dir·u over u in the cone {g_j·u ≤ 0} (within the plane ⊥ axis when axis ≠ 0) and the
// unit ball. The maximiser is dir itself, its projection onto one facet, an extreme ray, or 0.
struct Cone {
  const std::vector<Vec3>& g;
  Vec3 axis;                 // zero for a 3-D cone
  std::vector<Vec3>& rays;   // its extreme rays (computed once, into the caller's scratch)

  bool valid(const Vec3& u) const {
    for (const Vec3& q : g)
      if (q.dot(u) > 1e-12) return false;
    return true;
  }
  Cone(const std::vector<Vec3>& constraints, const Vec3& plane_axis, std::vector<Vec3>& scratch)
      : g(constraints), axis(plane_axis), rays(scratch) {
    rays.clear();
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

// The largest u·(±x), u·(±y), u·(±z) over u in the cone ∩ unit ball, in that order: a region
// {base segment} ⊕ (cone ∩ ball of radius r) spans the segment's box grown by r times these.
std::array<double, 6> cone_supports(const std::vector<Vec3>& g, const Vec3& axis, std::vector<Vec3>& rays) {
  const Cone cone(g, axis, rays);
  std::array<double, 6> out;
  for (int d = 0; d < 3; ++d) {
    out[2 * d] = cone.support(Vec3::Unit(d));
    out[2 * d + 1] = cone.support(-Vec3::Unit(d));
  }
  return out;
}

// The polyhedron of feature `id` (faces, then edges, then vertices): its half-spaces into
// `planes` (cleared first), and for an edge or a vertex its cone's constraints into `g`. Rebuilt
// in every slab a region meets, which is cheaper than storing them.
void make_region(const MeshFeatures& f, const ScanRegions& regions, int id, double r, double pad,
                 std::vector<Plane>& planes, std::vector<Vec3>& g) {
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
  } else if (id < nf + ne) {
    // Edge: the segment's slab, cut by the half-spaces {(x−a)·d_f ≤ 0} of each adjacent face
    // (d_f: in-plane direction from the edge into f); a point whose closest point is inside
    // the edge cannot have (x−c)·d_f > 0, or moving into f would bring it closer.
    const int e = id - nf;
    const Vec3& a = f.vertices[f.edges[e].first];
    const Vec3& b = f.vertices[f.edges[e].second];
    const Vec3& t = regions.edge_dirs[e];
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
  } else {
    // Vertex: the cone {(x−v)·u_j ≤ 0} over its incident edge directions u_j.
    const int v = id - nf - ne;
    const Vec3& p = f.vertices[v];
    for (int i = f.vertex_edge_offsets[v]; i < f.vertex_edge_offsets[v + 1]; ++i) {
      const int e = f.vertex_edges[i];
      const Vec3 u = f.edges[e].first == v ? regions.edge_dirs[e] : Vec3(-regions.edge_dirs[e]);
      g.push_back(u);
      planes.push_back({u, u.dot(p) + pad});
    }
  }
}

// The bounding box of region `id` at radius r: a face's prism from its corners, an edge's or a
// vertex's from its cone's unit supports.
void region_box(const MeshFeatures& f, const ScanRegions& regions, int id, double r, double pad, Vec3& lo,
                Vec3& hi) {
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  if (id < nf) {
    const Vec3& n = f.face_normals[id];
    lo = hi = f.vertices[f.faces[id][0]];
    for (int k = 0; k < 3; ++k)
      for (double s : {-r, r}) {
        lo = lo.cwiseMin(f.vertices[f.faces[id][k]] + s * n);
        hi = hi.cwiseMax(f.vertices[f.faces[id][k]] + s * n);
      }
    lo.array() -= pad;
    hi.array() += pad;
    return;
  }
  Vec3 a, b;
  const std::array<double, 6>* support;
  if (id < nf + ne) {
    a = f.vertices[f.edges[id - nf].first];
    b = f.vertices[f.edges[id - nf].second];
    support = &regions.edge_supports[id - nf];
  } else {
    a = b = f.vertices[id - nf - ne];
    support = &regions.vertex_supports[id - nf - ne];
  }
  for (int d = 0; d < 3; ++d) {
    hi[d] = std::max(a[d], b[d]) + r * (*support)[2 * d] + pad;
    lo[d] = std::min(a[d], b[d]) - r * (*support)[2 * d + 1] - pad;
  }
}

// Which rows of a face's or an edge's region can hold band samples, slice by slice. Both are
// needles: a face's region is its prism {q + s·n : q in the face grown by the pad, |s| ≤ r + pad},
// 2r long and a triangle wide; an edge's is its thin wedge of normals, up to r long and as wide as
// the wedge opens at r. A tilted needle's index box is mostly empty, and the box alone would send
// every (b, c) row of it to the per-row plane test. Each needle lies in {q + s·axis : q in a box,
// s in [s_min, s_max]}; in the slice x_c = z that confines s by the box's extent along c, and x_b
// to the box's extent along b plus s·axis_b. The rows found are a superset of those holding
// samples within r of the feature, in a few operations per slice.
struct NeedleRows {
  bool bounded = false;    // false: every row of the box (a region these bounds do not fit)
  double low[3], high[3];  // the box, grown by the margin
  Vec3 axis;
  double s_min = 0.0, s_max = 0.0;

  // A face's prism. The side planes, each moved out by the pad, meet at corners moved by
  // pad·|o + o'|/(1 + o·o') (o, o': the two sides' outward normals, the first three of the face's
  // `planes` from make_region), unbounded only for a face with an angle near 0, which keeps its box.
  static NeedleRows face(const MeshFeatures& f, int face, const std::vector<Plane>& planes, double r, double pad,
                         double slack) {
    NeedleRows out;
    const Vec3 p[3] = {f.vertices[f.faces[face][0]], f.vertices[f.faces[face][1]], f.vertices[f.faces[face][2]]};
    const Vec3& n = f.face_normals[face];
    double grow = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 &o = planes[k].g, &o_before = planes[(k + 2) % 3].g;
      const double cosine = 1.0 + o.dot(o_before);
      if (!(cosine > 1e-6)) return out;
      grow = std::max(grow, pad * (o + o_before).norm() / cosine);
    }
    out.axis = n;
    out.s_min = -(r + pad);
    out.s_max = r + pad;
    for (int d = 0; d < 3; ++d) {
      out.low[d] = std::min({p[0][d], p[1][d], p[2][d]}) - grow - slack;
      out.high[d] = std::max({p[0][d], p[1][d], p[2][d]}) + grow + slack;
    }
    out.bounded = n.allFinite() && std::isfinite(grow);
    return out;
  }

  // An edge a → a + len·t between two faces, d1 and d2 the directions from it into each face (in
  // the face's plane, ⊥ t).
  // Its normals form the wedge {u ⊥ t : u·d1 ≤ 0, u·d2 ≤ 0}, of half-angle θ about the bisector
  // m = −(d1 + d2)/|d1 + d2| (sin θ = √((1 + d1·d2)/2)); on a flat edge (d2 = −d1) it is the whole
  // line through ±(t × d1). A sample u within r of the edge and inside the pad-moved planes has
  // −r ≤ u·m ≤ r, u·m ≥ −pad/sin θ, and |u·(t × m)| ≤ (pad + r·sin θ)/cos θ. Sharp edges
  // (θ > 60°), border and non-manifold edges keep their box.
  static NeedleRows edge(const Vec3& a, const Vec3& t, double len, const std::vector<Vec3>& d, double r, double pad,
                         double slack) {
    NeedleRows out;
    if (d.size() != 2) return out;
    const double cos_between = std::clamp(d[0].dot(d[1]), -1.0, 1.0);
    const double sin_half = std::sqrt(0.5 * (1.0 + cos_between)), cos_half = std::sqrt(0.5 * (1.0 - cos_between));
    if (!(cos_half > 0.5)) return out;
    const Vec3 sum = d[0] + d[1];
    const double sum_norm = sum.norm();
    out.axis = sum_norm > 1e-12 ? Vec3(-sum / sum_norm) : Vec3(t.cross(d[0]).normalized());
    const Vec3 across = t.cross(out.axis);
    out.s_min = sin_half > 0.0 ? std::max(-r, -pad / sin_half) : -r;
    out.s_max = r;
    if (sum_norm <= 1e-12) out.s_min = -r;  // the flat edge's line goes both ways
    const double width = (pad + r * sin_half) / cos_half;
    const Vec3 b = a + len * t;
    for (int k = 0; k < 3; ++k) {
      const double grow = width * std::abs(across[k]) + pad * std::abs(t[k]) + slack;
      out.low[k] = std::min(a[k], b[k]) - grow;
      out.high[k] = std::max(a[k], b[k]) + grow;
    }
    out.bounded = out.axis.allFinite() && std::isfinite(width);
    return out;
  }

  // The range of b indices (first > last when none) in the slice x_c = z, within [lo, hi].
  std::pair<int, int> rows(int b, int c, double z, const GridGeometry& grid, int lo, int hi, double slack) const {
    if (!bounded) return {lo, hi};
    double s0 = s_min - slack, s1 = s_max + slack;
    if (axis[c] != 0.0) {
      const double u = (z - high[c]) / axis[c], v = (z - low[c]) / axis[c];
      s0 = std::max(s0, std::min(u, v) - slack);
      s1 = std::min(s1, std::max(u, v) + slack);
    } else if (z < low[c] || z > high[c]) {
      return {1, 0};
    }
    if (s0 > s1) return {1, 0};
    const double b0 = low[b] + std::min(s0 * axis[b], s1 * axis[b]) - slack;
    const double b1 = high[b] + std::max(s0 * axis[b], s1 * axis[b]) + slack;
    const double h = grid.voxel;
    const double first = std::ceil((b0 - grid.origin[b]) / h), last = std::floor((b1 - grid.origin[b]) / h);
    return {static_cast<int>(std::max(double(lo), std::min(first, double(hi) + 1))),
            static_cast<int>(std::min(double(hi), std::max(last, double(lo) - 1)))};
  }
};

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

ScanRegions scan_regions(const MeshFeatures& f, int threads) {
  const int ne = static_cast<int>(f.edges.size()), nv = static_cast<int>(f.vertices.size());
  ScanRegions out;
  out.edge_dirs.resize(ne);
  out.edge_lengths.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const Vec3 d = f.vertices[f.edges[e].second] - f.vertices[f.edges[e].first];
    out.edge_lengths[e] = d.norm();
    out.edge_dirs[e] = d / out.edge_lengths[e];
  }
  out.edge_supports.resize(ne);
  out.vertex_supports.resize(nv);
  parallel_for_ranges(ne + nv, 4096, threads, [&](int begin, int end) {
    std::vector<Plane> planes;
    std::vector<Vec3> g, rays;
    const int nf = static_cast<int>(f.faces.size());
    for (int k = begin; k < end; ++k) {
      make_region(f, out, nf + k, 1.0, 0.0, planes, g);
      if (k < ne)
        out.edge_supports[k] = cone_supports(g, out.edge_dirs[k], rays);
      else
        out.vertex_supports[k - ne] = cone_supports(g, Vec3::Zero(), rays);
    }
  });
  return out;
}

BandScan scan_band(const MeshFeatures& f, const ScanRegions& regions, const GridGeometry& grid, double r,
                   int threads) {
  const double h = grid.voxel;
  const double pad = 1e-9 * h;  // covers round-off in the plane tests; far below the 1e-6 budget
  const double slack = 1e-6 * h;  // row bounds are widened by this, far beyond their round-off
  const int nf = static_cast<int>(f.faces.size());
  const int ne = static_cast<int>(f.edges.size());
  const int nregions = nf + ne + static_cast<int>(f.vertices.size());

  BandScan out;
  out.value.assign(grid.count(), kInfinity);
  out.key.assign(grid.count(), -1);

  // Index box of every region (empty when outside the grid), then the slabs it meets. Only the
  // boxes are kept: planes are rebuilt per slab, which is cheaper than storing them.
  struct Box {
    int lo[3], hi[3];
  };
  std::unique_ptr<Box[]> boxes(new Box[nregions]);
  parallel_for_ranges(nregions, 4096, threads, [&](int begin, int end) {
    Vec3 low, high;
    for (int id = begin; id < end; ++id) {
      region_box(f, regions, id, r, pad, low, high);
      Box& b = boxes[id];
      for (int d = 0; d < 3; ++d) {
        const double lo = std::ceil((low[d] - grid.origin[d]) / h);
        const double hi = std::floor((high[d] - grid.origin[d]) / h);
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
      make_region(f, regions, id, r, pad, planes, g);
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
        dir = regions.edge_dirs[feature];
        len = regions.edge_lengths[feature];
        normal = f.edge_normals[feature];
        key = nf + feature;
      } else {
        p0 = f.vertices[feature];
        normal = f.vertex_normals[feature];
        key = nf + ne + feature;
      }

      NeedleRows needle;
      if (kind == Kind::face)
        needle = NeedleRows::face(f, feature, planes, r, pad, slack);
      else if (kind == Kind::edge)
        needle = NeedleRows::edge(f.vertices[f.edges[feature].first], regions.edge_dirs[feature],
                                  regions.edge_lengths[feature], g, r, pad, slack);
      int idx[3];
      for (idx[c] = lo[c]; idx[c] <= hi[c]; ++idx[c]) {
        const double zc = grid.origin[c] + h * idx[c];
        const auto [b_first, b_last] = needle.rows(b, c, zc, grid, lo[b], hi[b], slack);
        for (idx[b] = b_first; idx[b] <= b_last; ++idx[b]) {
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
